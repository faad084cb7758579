/* exp_mechanism: E1 (design.md §7 E1; reference paper §3.2), writing
 * frozen/mechanism: the beta x d sweep on the controlled lattice, the
 * ablation at 3.5 m (coupling off / abrasion off / both on) and the crowns of
 * the three figure panels (hard-core stand at 3.5 m, the same draws in all
 * three). Outputs (columns; every file starts with the provenance block):
 *  mechanism/sweep.tsv     beta spacing_m stands trees k1_m k2_m k3_m cover
 *                          worst_overlap_m pass train_row   (16 rows)
 *  mechanism/ablation.tsv  arm(coupling_off|abrasion_off|both_on) coupled beta
 *                          spacing_m stands trees k1_m k2_m k3_m cover overlap_m
 *  mechanism/figure_stats.tsv  the ablation's columns, measured on the one
 *                          hard-core figure stand (the paper's "measured on the
 *                          stand shown": the Mech* macros, design.md §7 E1);
 *                          the gate stays judged on ablation.tsv (lattice)
 *  mechanism/figure_crowns.tsv, figure_poly_<panel>_<d>.tsv (exp_common.h)
 *  mechanism/sweep_trees.tsv (--stand-rows; design.md §6.1, written before
 *                          sweep.tsv) beta spacing_m stand tree k1_m k2_m k3_m
 *                          stand_cover: the interior trees each sweep row pools,
 *                          in the order it pooled them, with their stand's cover
 * The ablation arms, the figure stand's growth and the cell statistics are
 * figstand.c's (the replicates compute the same numbers there). */
#include "exp_mechanism.h"
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

/* The rows a cell pools (--stand-rows): per interior tree its stand, its
 * index and its k = 1..3 clearances; per stand its cover. */
typedef struct { dvec stand, tree, k[3]; double *cover; } cell_rows;

static void cell_rows_free(cell_rows *c)
{
    free(c->stand.v);
    free(c->tree.v);
    for (int k = 0; k < 3; k++) free(c->k[k].v);
    free(c->cover);
}

/* One (stem process, d, params) cell over o->stands stands of key `key`;
 * rows (may be NULL) receives what it pools. */
static cs_status run_cell(const exp_opts *o, const char *key, const stems_type *kind, double d, double shape,
                          const teacher_params *p, figstand_cell *res, cell_rows *rows, double *worst)
{
    dvec g[3] = {{0}, {0}, {0}};
    double cov_sum = 0.0, ovl = 0.0;
    size_t trees = 0;
    cs_status st = CS_OK;
    if (rows) {
        memset(rows, 0, sizeof *rows);
        rows->cover = calloc((size_t)o->stands, sizeof *rows->cover);
        if (!rows->cover) st = cs_err(CS_ENOMEM, "experiments: out of memory");
    }
    for (int k = 0; k < o->stands && !st; k++) {
        stand *sd = NULL;
        st = exp_stand_alloc(&o->rd, &sd, kind, d, 12.0 * d, shape, key, (unsigned)k);
        if (st) break;
        double *r = malloc(sd->s->n * NS * sizeof *r);
        if (!r) st = cs_err(CS_ENOMEM, "experiments: out of memory");
        if (!st) st = stand_grow(sd, p, NULL, r, NULL, worst);
        double cov = 0.0, w = 0.0;
        size_t from = g[0].n;
        if (!st) st = figstand_stand_stats(sd, r, g, &cov, &w, &trees);
        if (!st && rows) {
            /* exp_stand_metrics appends the interior trees in index order */
            rows->cover[k] = cov;
            for (size_t i = 0, q = from; i < sd->s->n && !st; i++) {
                if (!stems_interior(sd->s, i)) continue;
                st = dvec_push(&rows->stand, (double)k);
                if (!st) st = dvec_push(&rows->tree, (double)i);
                for (int j = 0; j < 3 && !st; j++) st = dvec_push(&rows->k[j], g[j].v[q]);
                q++;
            }
            if (!st && rows->tree.n != g[0].n)
                st =
                    cs_err(CS_EINVARIANT, "experiments: %zu interior trees recorded, %zu pooled", rows->tree.n, g[0].n);
        }
        cov_sum += cov;
        if (w > ovl) ovl = w;
        free(r);
        stand_free(sd);
    }
    return figstand_cell_close(g, cov_sum / (double)o->stands, ovl, trees, st, res);
}

/* mechanism/sweep_trees.tsv: the trees each sweep row pools (file order
 * of sweep.tsv: spacing-major), with their stand's cover. */
static cs_status write_sweep_trees(const exp_opts *o, const prov *pv, const double *betas, size_t nb, const double *ds,
                                   size_t nd, const cell_rows *rows)
{
    tsv_writer *w = NULL;
    char path[512];
    prov rp = *pv;
    cs_status st = unit_out_open(o, "mechanism", "sweep_trees.tsv", &w, path, sizeof path);
    if (st) return st;
    if ((st = prov_write(w, &rp))) { tsv_writer_abort(w); return st; }
    unit_out_meta(w, o);
    tsv_writer_meta(w, "stems", "controlled lattice a = 0.04, L = 12 d");
    tsv_writer_meta(w, "rows",
                    "the interior trees each row of sweep.tsv pools, in the order it pooled them; stand_cover is their "
                    "stand's interior cover (design.md §6.1)");
    tsv_writer_columns(w, "beta\tspacing_m\tstand\ttree\tk1_m\tk2_m\tk3_m\tstand_cover");
    for (size_t a = 0; a < nd; a++)
        for (size_t b = 0; b < nb; b++) {
            const cell_rows *c = &rows[a * nb + b];
            for (size_t i = 0; i < c->tree.n; i++) {
                tsv_writer_dbl(w, betas[b]);
                tsv_writer_dbl(w, ds[a]);
                tsv_writer_long(w, (long)c->stand.v[i]);
                tsv_writer_long(w, (long)c->tree.v[i]);
                for (int k = 0; k < 3; k++) tsv_writer_dbl(w, c->k[k].v[i]);
                tsv_writer_dbl(w, c->cover[(size_t)c->stand.v[i]]);
                tsv_writer_endrow(w);
            }
        }
    return unit_out_finish(w, &rp, path);
}

cs_status exp_mechanism_sweep(const exp_opts *o)
{
    prov pv;
    exp_prov_begin(&pv, "mechanism", &o->rd, o->argc, o->argv);
    double betas[16], ds[16], thr[4], btrain;
    size_t nb, nd;
    cs_status st = gate_read_values(PATHS_GATE("mechanism"), "dieback_sweep", betas, 16, &nb);
    if (!st) st = gate_read_values(PATHS_GATE("mechanism"), "spacings_m", ds, 16, &nd);
    if (!st) st = gate_read_value(PATHS_GATE("mechanism"), "clearance_k1_min_m", 0, &thr[0]);
    if (!st) st = gate_read_value(PATHS_GATE("mechanism"), "clearance_k2_min_m", 0, &thr[1]);
    if (!st) st = gate_read_value(PATHS_GATE("mechanism"), "clearance_k3_min_m", 0, &thr[2]);
    if (!st) st = gate_read_value(PATHS_GATE("mechanism"), "cover_min", 0, &thr[3]);
    if (!st) st = gate_read_value(PATHS_GATE("mechanism"), "dieback_train", 0, &btrain);
    if (st) return st;
    figstand_cell *res = calloc(nb * nd, sizeof *res);
    cell_rows *rows = o->stand_rows ? calloc(nb * nd, sizeof *rows) : NULL;
    if (!res || (o->stand_rows && !rows)) {
        free(res);
        free(rows);
        return cs_err(CS_ENOMEM, "experiments: out of memory");
    }
    double worst = 0.0;
    for (size_t a = 0; a < nd && !st; a++)
        for (size_t b = 0; b < nb && !st; b++) {
            teacher_params p;
            EXP_TEACHER_PARAMS(&o->rd, &p);
            p.beta = betas[b];
            st = run_cell(o, "mechanism", stems_lattice, ds[a], 0.04, &p, &res[a * nb + b],
                          rows ? &rows[a * nb + b] : NULL, &worst);
            if (!st) fprintf(stderr, "mechanism sweep: d=%.1f beta=%.2f k1=%+.3f k2=%+.3f k3=%+.3f cover=%.3f\n",
                             ds[a], betas[b], res[a * nb + b].k[0], res[a * nb + b].k[1],
                             res[a * nb + b].k[2], res[a * nb + b].cover);
        }
    tsv_writer *w = NULL;
    char path[512];
    pv.worst_overlap_m = worst;
    snprintf(pv.seeds, sizeof pv.seeds, "seed_derive(mechanism,d,k,stems|crowns) k=0..%d", o->stands - 1);
    if (!st && rows) st = write_sweep_trees(o, &pv, betas, nb, ds, nd, rows);
    for (size_t i = 0; rows && i < nb * nd; i++) cell_rows_free(&rows[i]);
    free(rows);
    if (!st) st = unit_out_open(o, "mechanism", "sweep.tsv", &w, path, sizeof path);
    if (st) { free(res); return st; }
    st = prov_write(w, &pv);
    if (st) { tsv_writer_abort(w); free(res); return st; }
    unit_out_meta(w, o);
    tsv_writer_meta(w, "stems", "controlled lattice a = 0.04, L = 12 d");
    tsv_writer_meta(w, "statistic",
                    "k-th NN clearance: median over interior trees pooled over stands; cover: mean over stands");
    tsv_writer_columns(w, "beta\tspacing_m\tstands\ttrees\tk1_m\tk2_m\tk3_m\tcover\tworst_overlap_m\tpass\ttrain_row");
    for (size_t a = 0; a < nd; a++)
        for (size_t b = 0; b < nb; b++) {
            const figstand_cell *c = &res[a * nb + b];
            int pass = c->k[0] >= thr[0] && c->k[1] >= thr[1] && c->k[2] >= thr[2] && c->cover >= thr[3];
            tsv_writer_dbl(w, betas[b]);
            tsv_writer_dbl(w, ds[a]);
            tsv_writer_long(w, o->stands);
            tsv_writer_long(w, (long)c->trees);
            for (int k = 0; k < 3; k++) tsv_writer_dbl(w, c->k[k]);
            tsv_writer_dbl(w, c->cover);
            tsv_writer_dbl(w, c->overlap);
            tsv_writer_long(w, pass);
            tsv_writer_long(w, betas[b] == btrain);
            tsv_writer_endrow(w);
        }
    free(res);
    return unit_out_finish(w, &pv, path);
}

/* One row per arm (the ablation's columns), for ablation.tsv (lattice) and
 * figure_stats.tsv (the figure stand). */
static cs_status write_ablation(const exp_opts *o, prov *pv, const char *file, const char *stems, double d,
                                const double beta[3], int stands, const figstand_cell res[3])
{
    tsv_writer *w = NULL;
    char path[512];
    cs_status st = unit_out_open(o, "mechanism", file, &w, path, sizeof path);
    if (st) return st;
    st = prov_write(w, pv);
    if (st) { tsv_writer_abort(w); return st; }
    unit_out_meta(w, o);
    tsv_writer_meta(w, "stems", "%s", stems);
    tsv_writer_meta(w, "statistic",
                    "k-th NN clearance: median over interior trees pooled over stands; cover: mean over stands of the "
                    "interior-square cover");
    tsv_writer_meta(w, "overlap", "worst overlap of the final crowns (teacher self-check measure), m");
    tsv_writer_columns(w, "arm\tcoupled\tbeta\tspacing_m\tstands\ttrees\tk1_m\tk2_m\tk3_m\tcover\toverlap_m");
    for (int a = 0; a < 3; a++) {
        tsv_writer_str(w, figstand_ablation_arms[a]);
        tsv_writer_long(w, figstand_ablation_coupled[a]);
        tsv_writer_dbl(w, beta[a]);
        tsv_writer_dbl(w, d);
        tsv_writer_long(w, stands);
        tsv_writer_long(w, (long)res[a].trees);
        for (int k = 0; k < 3; k++) tsv_writer_dbl(w, res[a].k[k]);
        tsv_writer_dbl(w, res[a].cover);
        tsv_writer_dbl(w, res[a].overlap);
        tsv_writer_endrow(w);
    }
    return unit_out_finish(w, pv, path);
}

cs_status exp_mechanism_ablation(const exp_opts *o)
{
    prov pv;
    exp_prov_begin(&pv, "mechanism", &o->rd, o->argc, o->argv);
    double d, beta[3];
    cs_status st = figstand_ablation_gate(&d, beta);
    if (st) return st;
    const char *const *arms = figstand_ablation_arms;
    const int *coupled = figstand_ablation_coupled;
    figstand_cell res[3];
    double worst = 0.0;
    for (int a = 0; a < 3 && !st; a++) {
        teacher_params p;
        EXP_TEACHER_PARAMS(&o->rd, &p);
        p.coupled = coupled[a];
        p.beta = beta[a];
        st = run_cell(o, "mechanism", stems_lattice, d, 0.04, &p, &res[a], NULL, &worst);
        if (!st) fprintf(stderr, "mechanism ablation: %s k1=%+.3f k2=%+.3f k3=%+.3f cover=%.3f overlap=%.3g\n",
                         arms[a], res[a].k[0], res[a].k[1], res[a].k[2], res[a].cover, res[a].overlap);
    }
    if (st) return st;
    pv.worst_overlap_m = worst;
    snprintf(pv.seeds, sizeof pv.seeds, "seed_derive(mechanism,%.1f,k,stems|crowns) k=0..%d (the sweep's stands)",
             d, o->stands - 1);
    return write_ablation(o, &pv, "ablation.tsv",
                          "controlled lattice a = 0.04, L = 12 d; identical stems and crown draws in all arms", d, beta,
                          o->stands, res);
}

cs_status exp_mechanism_figure(const exp_opts *o)
{
    prov pv;
    exp_prov_begin(&pv, "mechanism", &o->rd, o->argc, o->argv);
    double d, beta[3];
    cs_status st = figstand_ablation_gate(&d, beta);
    if (st) return st;
    stand *sd = NULL;
    double *r = NULL, worst = 0.0;
    figstand_cell fres[3];
    st = figstand_mechanism_grow(o, 0, d, beta, &sd, &r, &worst, fres);
    if (st) { free(r); stand_free(sd); return st; }
    size_t n = sd->s->n;
    const char *const *arms = figstand_ablation_arms;
    /* The ablation numbers on the stand shown (figure_stats.tsv), written
     * before the crowns table that make counts as the unit's target. */
    if (!st) {
        prov sp = pv;
        sp.worst_overlap_m = worst;
        snprintf(sp.seeds, sizeof sp.seeds, "seed_derive(fig/mechanism,%.1f,0,stems|crowns) (the figure stand)", d);
        char stems[256];
        snprintf(stems, sizeof stems,
                 "hard-core Poisson c = %.2f, d = %.2f m, L = %.0f m: the one figure stand, identical in all arms",
                 exp_fig_c(&o->rd), d, EXP_FIG_L);
        exp_opts o1 = *o;
        o1.stands = 1;
        st = write_ablation(&o1, &sp, "figure_stats.tsv", stems, d, beta, 1, fres);
    }
    tsv_writer *w = NULL;
    char path[512];
    if (!st) st = unit_out_open(o, "mechanism", "figure_crowns.tsv", &w, path, sizeof path);
    if (!st) {
        pv.worst_overlap_m = worst;
        snprintf(pv.seeds, sizeof pv.seeds, "seed_derive(fig/mechanism,%.1f,0,stems|crowns)", d);
        st = prov_write(w, &pv);
        if (st) tsv_writer_abort(w);
    }
    if (!st) {
        tsv_writer_meta(w, "stems",
                        "hard-core Poisson c = %.2f, d = %.2f m, L = %.0f m; one stand, identical in all panels",
                        exp_fig_c(&o->rd), d, EXP_FIG_L);
        /* NN clearance on the stand shown (interior trees), for the panel captions. */
        for (int a = 0; a < 3; a++)
            tsv_writer_meta(w, arms[a], "median k1 clearance %.3f m", exp_stand_k1(sd, r + (size_t)a * n * NS));
        unit_out_crown_columns(w);
        for (int a = 0; a < 3; a++) unit_out_crowns(w, arms[a], d, sd, r + (size_t)a * n * NS);
        for (int a = 0; a < 3 && !st; a++)
            st = unit_out_polygons(o, &pv, "mechanism", arms[a], d, sd, r + (size_t)a * n * NS,
                                exp_stand_k1(sd, r + (size_t)a * n * NS));
        if (st) tsv_writer_abort(w);
        else st = unit_out_finish(w, &pv, path);
    }
    free(r);
    stand_free(sd);
    return st;
}

