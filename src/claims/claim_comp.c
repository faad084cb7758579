/* claim_comp: computing functions for E7 (reference paper Fig. teaser b-d,
 * Limitations) from a reading's comparison/dist_summary.tsv written by
 * `crownshy comparison-dist` (src/exp/exp_compdist.c: 256 fresh patches per
 * arm; the paper reading under frozen/paper-reading/, the pair extension
 * under frozen/extension-pair/; the row's params name the arm and the
 * statistic), and the lidar span of teaser panel a (needs CHM=path). */
#include "claims.h"
#include "paths.h"
#include "tsv.h"
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* One cell of dist_summary.tsv: the row of (probe, the row's arm as the
 * table's source), column <stat>_q50 as the value (stat=median); stat=range
 * gives its 5-95 % range "<q05> to <q95>" (text, in fmt) instead. `arms`
 * lists the arms the function computes. */
static cs_status dist_value(const claim_row *row, claim_result *res, const char *probe, const char *arms,
                            const char *stat, const char *fmt)
{
    const claim_params *p = &row->param;
    cs_status st = claim_param_need(row, PARAM_ARM | PARAM_STAT);
    if (st) return st;
    const char *source = param_arm_name(p->arm);
    if (!strstr(arms, source)) return claim_param_bad(row, "arm", arms);
    if (p->stat != STAT_MEDIAN && p->stat != STAT_RANGE) return claim_param_bad(row, "stat", "median or range");
    tsv *t;
    if ((st = tsv_read(row->source, &t))) return st;
    long r = -1;
    for (size_t i = 0; i < tsv_nrows(t) && r < 0; i++) {
        const char *p = tsv_str(t, i, "probe"), *s = tsv_str(t, i, "source");
        if (p && s && !strcmp(p, probe) && !strcmp(s, source)) r = (long)i;
    }
    char c05[64], c50[64], c95[64];
    snprintf(c05, sizeof c05, "%s_q05", stat);
    snprintf(c50, sizeof c50, "%s_q50", stat);
    snprintf(c95, sizeof c95, "%s_q95", stat);
    double q05, q50, q95, n;
    if (r < 0) st = cs_err(CS_EINPUT, "%s: no row with probe = %s and source = %s", row->source, probe, source);
    else if (!(st = tsv_double(t, (size_t)r, c05, &q05)) && !(st = tsv_double(t, (size_t)r, c50, &q50)) &&
             !(st = tsv_double(t, (size_t)r, c95, &q95)) && !(st = tsv_double(t, (size_t)r, "patches", &n))) {
        int range = p->stat == STAT_RANGE;
        snprintf(res->where, sizeof res->where, "%s:%d (%s, %s: %s over %.0f patches)", row->source,
                 tsv_line(t, (size_t)r), probe, source, range ? "5 % and 95 % quantiles" : "median", n);
        if (range) {
            char a[32], b[32];
            snprintf(a, sizeof a, fmt, q05);
            snprintf(b, sizeof b, fmt, q95);
            res->value = q05;
            snprintf(res->text, sizeof res->text, "%s to %s", a, b);
        } else
            claim_set_value(row, res, q50);
    }
    tsv_free(t);
    return st;
}

/* E7 as distributions over fresh patches (design.md §7 E7): medians over the
 * patches of dist_summary.tsv with their 5-95 % ranges. */
cs_status claim_comp_overlap(const claim_row *row, claim_result *res)
{
    return dist_value(row, res, "comparison", "joint, indep or teacher", "overlapping", "%.0f");
}

cs_status claim_comp_k(const claim_row *row, claim_result *res)
{
    return dist_value(row, res, "comparison", "joint, indep or teacher", "median_nn", "%+.3f");
}

cs_status claim_comp_dart(const claim_row *row, claim_result *res)
{
    return dist_value(row, res, "dart", "joint or teacher", "median_nn", "%+.3f");
}

/* The share of patches (percent) in which no crown of the joint arm overlaps. */
cs_status claim_comp_no_overlap(const claim_row *row, claim_result *res)
{
    tsv *t;
    cs_status st = tsv_read(row->source, &t);
    if (st) return st;
    long r = -1;
    for (size_t i = 0; i < tsv_nrows(t) && r < 0; i++) {
        const char *p = tsv_str(t, i, "probe"), *s = tsv_str(t, i, "source");
        if (p && s && !strcmp(p, "comparison") && !strcmp(s, "joint")) r = (long)i;
    }
    double f;
    if (r < 0) st = cs_err(CS_EINPUT, "%s: no row with probe = comparison and source = joint", row->source);
    else if (!(st = tsv_double(t, (size_t)r, "no_overlap_fraction", &f))) {
        snprintf(res->where, sizeof res->where, "%s:%d (comparison, joint: no_overlap_fraction)", row->source,
                 tsv_line(t, (size_t)r));
        claim_set_value(row, res, 100.0 * f);
    }
    tsv_free(t);
    return st;
}

/* One number of a CHM file: the whole token, finite. */
static int chm_number(const char *tok, double *v)
{
    char *end;
    *v = strtod(tok, &end);
    return end != tok && !*end && isfinite(*v);
}

/* The ESRI ASCII header: ncols, nrows (positive integers), xllcorner or
 * xllcenter, yllcorner or yllcenter (finite), cellsize (finite, > 0) and an
 * optional NODATA_value, each once, in any order, before the first data row. */
typedef struct { double ncols, nrows, cell; int line; } chm_header;

static cs_status chm_header_read(FILE *f, const char *path, chm_header *h, char *first, size_t fn, int *lineno)
{
    static const char *keys[] = {"ncols",    "nrows",        "xllcorner", "yllcorner",
                                 "cellsize", "nodata_value", "xllcenter", "yllcenter"};
    double val[8];
    int seen[8] = {0};
    char line[4096];
    first[0] = '\0';
    while (fgets(line, sizeof line, f)) {
        (*lineno)++;
        if (!strchr(line, '\n') && !feof(f))
            return cs_err(CS_EINPUT, "%s:%d: line too long for a header", path, *lineno);
        char key[64], vs[128], extra[8];
        int nt = sscanf(line, "%63s %127s %7s", key, vs, extra);
        if (nt <= 0) continue;
        double d;
        if (chm_number(key, &d)) { snprintf(first, fn, "%s", line); break; } /* the first data row */
        for (char *c = key; *c; c++) *c = (char)tolower((unsigned char)*c);
        int k = 0;
        while (k < 8 && strcmp(keys[k], key)) k++;
        if (k == 8) return cs_err(CS_EINPUT, "%s:%d: field '%s': not an ESRI ASCII header field", path, *lineno, key);
        if (seen[k]) return cs_err(CS_EINPUT, "%s:%d: field '%s': given twice", path, *lineno, key);
        if (nt != 2 || !chm_number(vs, &val[k]))
            return cs_err(CS_EINPUT, "%s:%d: field '%s': '%s' is not one finite number", path, *lineno, key,
                          nt >= 2 ? vs : "");
        seen[k] = *lineno;
    }
    if (seen[2] && seen[6]) return cs_err(CS_EINPUT, "%s:%d: field 'xllcenter': xllcorner given too", path, seen[6]);
    if (seen[3] && seen[7]) return cs_err(CS_EINPUT, "%s:%d: field 'yllcenter': yllcorner given too", path, seen[7]);
    const char *miss = !seen[0]                ? "ncols"
                       : !seen[1]              ? "nrows"
                       : !(seen[2] || seen[6]) ? "xllcorner"
                       : !(seen[3] || seen[7]) ? "yllcorner"
                       : !seen[4]              ? "cellsize"
                                               : NULL;
    if (miss) return cs_err(CS_EINPUT, "%s: field '%s': missing from the ESRI ASCII header", path, miss);
    for (int k = 0; k < 2; k++)
        if (val[k] < 1 || val[k] > 1e6 || val[k] != floor(val[k]))
            return cs_err(CS_EINPUT, "%s:%d: field '%s': %g is not a whole number of cells in 1..1000000", path,
                          seen[k], keys[k], val[k]);
    if (val[4] <= 0) return cs_err(CS_EINPUT, "%s:%d: field 'cellsize': %g is not positive", path, seen[4], val[4]);
    h->ncols = val[0];
    h->nrows = val[1];
    h->cell = val[4];
    h->line = *lineno;
    return CS_OK;
}

/* The data: nrows lines of ncols finite numbers each, nothing after them. */
static cs_status chm_data_check(FILE *f, const char *path, const chm_header *h, const char *first, int lineno)
{
    char line[1 << 16];
    long rows = 0;
    int have = first[0] != '\0';
    if (have) snprintf(line, sizeof line, "%s", first);
    while (have || fgets(line, sizeof line, f)) {
        if (!have) lineno++;
        have = 0;
        if (!strchr(line, '\n') && !feof(f))
            return cs_err(CS_EINPUT, "%s:%d: line longer than %zu bytes", path, lineno, sizeof line);
        long cols = 0;
        for (char *save = NULL, *tok = strtok_r(line, " \t\r\n", &save); tok; tok = strtok_r(NULL, " \t\r\n", &save)) {
            double v;
            cols++;
            if (!chm_number(tok, &v))
                return cs_err(CS_EINPUT, "%s:%d: field 'column %ld': '%s' is not a finite number", path, lineno, cols,
                              tok);
        }
        if (!cols) continue;
        if (++rows > (long)h->nrows)
            return cs_err(CS_EINPUT, "%s:%d: more data rows than nrows = %.0f", path, lineno, h->nrows);
        if (cols != (long)h->ncols)
            return cs_err(CS_EINPUT, "%s:%d: field 'ncols': %ld values on the row, the header says %.0f", path, lineno,
                          cols, h->ncols);
    }
    if (rows != (long)h->nrows)
        return cs_err(CS_EINPUT, "%s: field 'nrows': %ld data rows after the header (line %d), the header says %.0f",
                      path, rows, h->line, h->nrows);
    return CS_OK;
}

/* Span of the lidar window (teaser panel a): side of the CHM grid in metres.
 * Needs a canopy height model supplied as CHM=path (ESRI ASCII grid); this
 * machine has none. The whole file is validated: every header field, and
 * exactly ncols x nrows finite values. */
cs_status claim_chm_span(const claim_row *row, claim_result *res)
{
    const char *path = getenv("CHM");
    if (!path || !path[0]) {
        claim_pending(res, "lidar canopy height model (Swinfield et al. 2020, doi:10.5281/zenodo.4020697) not on this "
                           "machine: set CHM=path to an ESRI ASCII grid");
        return CS_OK;
    }
    cs_status st = paths_input_file(path);
    if (st) return st;
    FILE *f = fopen(path, "r");
    if (!f) return cs_err(CS_EINPUT, "%s: cannot open (CHM)", path);
    chm_header h = {0};
    char first[1 << 16];
    int lineno = 0;
    st = chm_header_read(f, path, &h, first, sizeof first, &lineno);
    if (!st) st = chm_data_check(f, path, &h, first, lineno);
    fclose(f);
    if (st) return st;
    double side = (h.ncols < h.nrows ? h.ncols : h.nrows) * h.cell;
    snprintf(res->where, sizeof res->where, "%s (ESRI ASCII grid, %.0f x %.0f cells of %g m)", path, h.ncols, h.nrows,
             h.cell);
    claim_set_value(row, res, side);
    return CS_OK;
}
