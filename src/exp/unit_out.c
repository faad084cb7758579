/* unit_out: see unit_out.h. */
#include "unit_out.h"
#include "figdata.h"
#include <stdio.h>

#define NS CROWN_NSEC

cs_status unit_out_open(const exp_opts *o, const char *experiment, const char *file, tsv_writer **w,
                          char *path, size_t pathsz)
{
    snprintf(path, pathsz, "%s/%s/%s", o->out, experiment, file);
    return tsv_writer_open(w, path);
}

cs_status unit_out_finish(tsv_writer *w, prov *pv, const char *path)
{
    cs_status st = tsv_writer_commit(w);
    if (!st) fprintf(stderr, "wrote %s (%.1f s)\n", path, prov_now() - pv->t0);
    return st;
}

/* Metadata lines shared by all units (after the provenance block). */
void unit_out_meta(tsv_writer *w, const exp_opts *o)
{
    tsv_writer_meta(w, "stands_per_cell", "%d", o->stands);
    tsv_writer_meta(w, "teacher_resolution", "N = %d unless a column says otherwise; gamma = 1", exp_nres(&o->rd));
    exp_variant_meta(w, &o->rd);
}

/* Crowns of one panel: one row per tree: panel, tree, x, y, h, interior, r0..r23. */
void unit_out_crowns(tsv_writer *w, const char *panel, double d, const stand *sd, const double *r)
{
    for (size_t i = 0; i < sd->s->n; i++) {
        tsv_writer_str(w, panel);
        tsv_writer_dbl(w, d);
        tsv_writer_long(w, (long)i);
        tsv_writer_dbl(w, sd->s->x[i]);
        tsv_writer_dbl(w, sd->s->y[i]);
        tsv_writer_dbl(w, sd->h[i]);
        tsv_writer_long(w, stems_interior(sd->s, i));
        for (int s = 0; s < NS; s++) tsv_writer_dbl(w, r[i * NS + s]);
        tsv_writer_endrow(w);
    }
}

void unit_out_crown_columns(tsv_writer *w)
{
    char cols[1024];
    int off = snprintf(cols, sizeof cols, "panel\tspacing_m\ttree\tx_m\ty_m\th_m\tinterior");
    for (int s = 0; s < NS; s++) off += snprintf(cols + off, sizeof cols - (size_t)off, "\tr%d", s);
    tsv_writer_columns(w, cols);
}

cs_status unit_out_polygons(const exp_opts *o, prov *pv, const char *experiment, const char *panel, double d,
                                const stand *sd, const double *r, double k1)
{
    char file[128], path[512];
    snprintf(file, sizeof file, "figure_poly_%s_%.1f.tsv", panel, d);
    tsv_writer *w = NULL;
    cs_status st = unit_out_open(o, experiment, file, &w, path, sizeof path);
    if (st) return st;
    st = prov_write(w, pv);
    if (st) { tsv_writer_abort(w); return st; }
    size_t n = sd->s->n;
    tsv_writer_meta(w, "panel", "%s, spacing %.2f m, footprint %.0f m, %zu trees, %d rows per tree", panel, d, sd->s->L,
                    n, FIGDATA_ROWS);
    tsv_writer_meta(w, "k1_median_m", "%.3f", k1);
    st = figdata_write_polygons(w, n, sd->s->x, sd->s->y, sd->h, r, NULL, NULL);
    if (st) { tsv_writer_abort(w); return st; }
    return tsv_writer_commit(w);
}
