/* claim_comp: computing functions for E7 (reference paper Fig. teaser b-d,
 * Limitations) from frozen/comparison/{patch,dart_probe}.tsv written by
 * src/exp/exp_comp.c, and the lidar span of teaser panel a (needs CHM=path). */
#include "claims.h"
#include "tsv.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static cs_status source_value(const claim_row *row, claim_result *res, const char *source, const char *col)
{
    tsv *t;
    cs_status st = tsv_read(row->source, &t);
    if (st) return st;
    long r = tsv_find(t, "source", source);
    double v;
    if (r < 0) st = cs_err(CS_EINPUT, "%s: no row with source = %s", row->source, source);
    else if (!(st = tsv_double(t, (size_t)r, col, &v))) {
        snprintf(res->where, sizeof res->where, "%s:%d (%s, %s)", row->source, tsv_line(t, (size_t)r), source, col);
        claim_set_value(row, res, v);
    }
    tsv_free(t);
    return st;
}

cs_status claim_comp_overlap(const claim_row *row, claim_result *res)
{
    const char *s = !strcmp(row->macro, "CompGenOverlap") ? "joint" : !strcmp(row->macro, "CompTeachOverlap") ? "teacher" : "indep";
    return source_value(row, res, s, "overlapping");
}

cs_status claim_comp_k(const claim_row *row, claim_result *res)
{
    const char *s = strstr(row->macro, "Teach") ? "teacher" : strstr(row->macro, "Indep") ? "indep" : "joint";
    return source_value(row, res, s, "median_nn_clearance_m");
}

cs_status claim_comp_dart(const claim_row *row, claim_result *res)
{
    return source_value(row, res, strstr(row->macro, "Teach") ? "teacher" : "joint", "median_focal_nn_clearance_m");
}

/* Span of the lidar window (teaser panel a): side of the CHM grid in metres,
 * capped at the panel's window. Needs a canopy height model supplied as
 * CHM=path (ESRI ASCII grid); this machine has none. */
cs_status claim_chm_span(const claim_row *row, claim_result *res)
{
    const char *path = getenv("CHM");
    if (!path || !path[0]) {
        claim_pending(res, "lidar canopy height model (Swinfield et al. 2020, doi:10.5281/zenodo.4020697) not on this machine: set CHM=path to an ESRI ASCII grid");
        return CS_OK;
    }
    FILE *f = fopen(path, "r");
    if (!f) return cs_err(CS_EINPUT, "%s: cannot open (CHM)", path);
    char key[64];
    double v, ncols = -1, nrows = -1, cell = -1;
    for (int line = 1; line <= 6 && fscanf(f, "%63s %lf", key, &v) == 2; line++) {
        for (char *c = key; *c; c++) *c = (char)(*c | 0x20);
        if (!strcmp(key, "ncols")) ncols = v;
        else if (!strcmp(key, "nrows")) nrows = v;
        else if (!strcmp(key, "cellsize")) cell = v;
    }
    fclose(f);
    if (ncols <= 0 || nrows <= 0 || cell <= 0) return cs_err(CS_EINPUT, "%s: field 'ncols'/'nrows'/'cellsize': ESRI ASCII header incomplete", path);
    double side = (ncols < nrows ? ncols : nrows) * cell;
    snprintf(res->where, sizeof res->where, "%s (ESRI ASCII header)", path);
    claim_set_value(row, res, side);
    return CS_OK;
}
