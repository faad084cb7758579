/* exp_stands: the hard-core canopy stands of E8 (point cloud, design.md §7 E8,
 * frozen/pointcloud) and E9 (hero, design.md §7 E9, frozen/hero): L = 36 m,
 * one stand per spacing with its crown draws shared within a column.
 * Outputs: <exp>/figure_crowns.tsv and figure_poly_<panel>_<d>.tsv
 * (exp_common.h); pointcloud/stats.tsv: spacing_m trees contact_fraction
 * overlap_fraction_coupled overlap_fraction_uncoupled k1_coupled_m k1_uncoupled_m, each row
 * figstand.c's numbers on the figure's point-cloud stand (as for its replicates). */
#include "exp_stands.h"
#include "exp_common.h"
#include "figstand.h"
#include "unit_out.h"
#include "gate.h"
#include "paths.h"
#include "stand_grow.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define NS CROWN_NSEC

/* Hero (E9) and point cloud (E8): hard-core stands at L = 36 m over spacings;
 * crown draws shared within a column (one stand per spacing, both rows). */
static cs_status unit_fig_stands(const exp_opts *o, const char *experiment, const char *key,
                                 const double *ds, size_t nd, const double *betas, const char **rows,
                                 size_t nrows, int with_uncoupled)
{
    prov pv;
    exp_prov_begin(&pv, experiment, &o->rd, o->argc, o->argv);
    tsv_writer *w = NULL;
    char path[512];
    cs_status st = unit_out_open(o, experiment, "figure_crowns.tsv", &w, path, sizeof path);
    if (st) return st;
    /* Grow everything first (the provenance needs the worst overlap). */
    size_t total = nd * (nrows + (size_t)with_uncoupled);
    stand **sds = calloc(nd, sizeof *sds);
    double **rs = calloc(total, sizeof *rs);
    double worst = 0.0;
    if (!sds || !rs) st = cs_err(CS_ENOMEM, "experiments: out of memory");
    for (size_t a = 0; a < nd && !st; a++) {
        st = exp_stand_alloc(&o->rd, &sds[a], stems_hardcore, ds[a], EXP_FIG_L, exp_fig_c(&o->rd), key, 0);
        for (size_t b = 0; b < nrows + (size_t)with_uncoupled && !st; b++) {
            double *r = malloc(sds[a]->s->n * NS * sizeof *r);
            rs[a * (nrows + (size_t)with_uncoupled) + b] = r;
            if (!r) { st = cs_err(CS_ENOMEM, "experiments: out of memory"); break; }
            teacher_params p;
            EXP_TEACHER_PARAMS(&o->rd, &p);
            if (b < nrows) p.beta = betas[b];
            else p.coupled = 0;
            st = stand_grow(sds[a], &p, NULL, r, NULL, &worst);
        }
    }
    if (!st) {
        pv.worst_overlap_m = worst;
        snprintf(pv.seeds, sizeof pv.seeds, "seed_derive(%s,d,0,stems|crowns)", key);
        st = prov_write(w, &pv);
    }
    if (!st) {
        tsv_writer_meta(w, "stems", "hard-core Poisson c = %.2f, L = %.0f m; crown draws shared within a column",
                        exp_fig_c(&o->rd), EXP_FIG_L);
        for (size_t b = 0; b < nrows; b++) tsv_writer_meta(w, rows[b], "dieback %.17g", betas[b]);
        unit_out_crown_columns(w);
        for (size_t a = 0; a < nd; a++)
            for (size_t b = 0; b < nrows + (size_t)with_uncoupled; b++)
                unit_out_crowns(w, b < nrows ? rows[b] : "uncoupled", ds[a], sds[a],
                                rs[a * (nrows + (size_t)with_uncoupled) + b]);
        for (size_t a = 0; a < nd && !st; a++)
            for (size_t b = 0; b < nrows + (size_t)with_uncoupled && !st; b++) {
                const double *r = rs[a * (nrows + (size_t)with_uncoupled) + b];
                st = unit_out_polygons(o, &pv, experiment, b < nrows ? rows[b] : "uncoupled", ds[a], sds[a], r,
                                    exp_stand_k1(sds[a], r));
            }
        if (st) tsv_writer_abort(w);
        else st = unit_out_finish(w, &pv, path);
    } else if (w) tsv_writer_abort(w);
    for (size_t a = 0; sds && a < nd; a++) stand_free(sds[a]);
    for (size_t k = 0; rs && k < total; k++) free(rs[k]);
    free(sds); free(rs);
    return st;
}

/* E8 numbers on the point-cloud stands: per spacing, the share of interior
 * crowns that made contact during coupled growth (a sector froze), the share
 * of interior crowns that interpenetrate a neighbour (some g(i,j) < 0) in
 * each arm, and the median NN clearance coupled vs uncoupled. */
static cs_status unit_pointcloud_stats(const exp_opts *o, const double *ds, size_t nd, double beta)
{
    prov pv;
    exp_prov_begin(&pv, "pointcloud", &o->rd, o->argc, o->argv);
    figstand_pc_row rows[8];
    double worst = 0.0;
    cs_status st = CS_OK;
    for (size_t a = 0; a < nd && !st; a++) st = figstand_pointcloud(o, ds[a], beta, 0, &rows[a], &worst);
    tsv_writer *w = NULL;
    char path[512];
    if (!st) st = unit_out_open(o, "pointcloud", "stats.tsv", &w, path, sizeof path);
    if (st) return st;
    pv.worst_overlap_m = worst;
    snprintf(pv.seeds, sizeof pv.seeds, "seed_derive(fig/pointcloud,d,0,stems|crowns)");
    st = prov_write(w, &pv);
    if (st) { tsv_writer_abort(w); return st; }
    tsv_writer_meta(w, "stems", "hard-core Poisson c = %.2f, L = %.0f m, one stand per spacing (the figure's)",
                    exp_fig_c(&o->rd), EXP_FIG_L);
    tsv_writer_meta(w, "dieback", "%.17g", beta);
    tsv_writer_meta(w, "contact", "interior crowns with a sector frozen on contact during coupled growth");
    tsv_writer_columns(w, "spacing_m	trees	contact_fraction	overlap_fraction_coupled	"
                          "overlap_fraction_uncoupled	k1_coupled_m	k1_uncoupled_m");
    for (size_t a = 0; a < nd; a++) {
        tsv_writer_dbl(w, ds[a]);
        tsv_writer_long(w, (long)rows[a].trees);
        tsv_writer_dbl(w, rows[a].contact);
        tsv_writer_dbl(w, rows[a].ovl_c);
        tsv_writer_dbl(w, rows[a].ovl_u);
        tsv_writer_dbl(w, rows[a].k1_c);
        tsv_writer_dbl(w, rows[a].k1_u);
        tsv_writer_endrow(w);
    }
    return unit_out_finish(w, &pv, path);
}

cs_status exp_hero_figure(const exp_opts *o)
{
    double btrain;
    cs_status st = gate_read_value(PATHS_GATE("mechanism"), "dieback_train", 0, &btrain);
    if (st) return st;
    const double ds[8] = {3.0, 3.5, 4.0, 4.5, 5.0, 5.5, 6.0, 6.5};
    double b[2] = {btrain, isnan(o->beta) ? btrain : o->beta};
    const char *rows[2] = {"beta_train", "beta_field"};
    /* beta_field comes from E5; without --beta only the train row is drawn. */
    return unit_fig_stands(o, "hero", "fig/hero", ds, 8, b, rows, isnan(o->beta) ? 1 : 2, 0);
}

cs_status exp_pointcloud_figure(const exp_opts *o)
{
    double btrain;
    cs_status st = gate_read_value(PATHS_GATE("mechanism"), "dieback_train", 0, &btrain);
    if (st) return st;
    const double ds[3] = {5.0, 4.0, 3.0};
    const char *rows[1] = {"coupled"};
    st = unit_fig_stands(o, "pointcloud", "fig/pointcloud", ds, 3, &btrain, rows, 1, 1);
    if (!st) st = unit_pointcloud_stats(o, ds, 3, btrain);
    return st;
}
