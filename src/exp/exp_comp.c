/* exp_comp: E7 comparison patch and dart probe (see exp_comp.h).
 * Models come from the E3 checkpoints of seed 1; the patch and the probe
 * stands have their own seeds (seed_derive("comparison", d, k, ·)), disjoint
 * from training. Clearances use the pinned estimator (est_clearance,
 * est_knn_clearance) on the patch trees. */
#include "exp_comp.h"
#include "design.h"
#include "estimator.h"
#include "figdata.h"
#include "gate.h"
#include "paths.h"
#include "model.h"
#include "opts.h"
#include "patch.h"
#include "prov.h"
#include "seed.h"
#include "stand.h"
#include "stats.h"
#include "stems.h"
#include "stand_grow.h"
#include "train.h"
#include "tsv.h"
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define COMP_HARDCORE_C 0.5  /* the figures' hard-core level (design.md §7 E8/E9) */
#define COMP_DART_STANDS 4

static cs_status grow(stand *sd, double beta, double *r)
{
    teacher_params tp;
    teacher_params_default(&tp);
    tp.beta = beta;
    return stand_grow(sd, &tp, NULL, r, NULL, NULL);
}

/* Median NN clearance over the T patch trees and the count of trees with a
 * negative clearance toward any other patch tree. */
static cs_status patch_stats(const double *x, const double *y, const double *r, double *med, int *overlap, int *flag)
{
    double g[PATCH_T];
    *overlap = 0;
    for (int i = 0; i < PATCH_T; i++) {
        cs_status st = est_knn_clearance(x, y, r, PATCH_T, (size_t)i, 1, &g[i]);
        if (st) return st;
        flag[i] = 0;
        for (int j = 0; j < PATCH_T && !flag[i]; j++)
            if (j != i && est_clearance(x[i], y[i], r + (size_t)i * CROWN_NSEC, x[j], y[j], r + (size_t)j * CROWN_NSEC) < 0) flag[i] = 1;
        *overlap += flag[i];
    }
    return stats_median(g, PATCH_T, med);
}

/* Generate the crowns (radii, m) of the patches of ps with model m. */
static cs_status gen_radii(model *m, const patch_set *ps, int Bmax, uint64_t seed, double *r)
{
    gsl_rng *g = gsl_rng_alloc(gsl_rng_mt19937);
    if (!g) return cs_err(CS_ENOMEM, "out of memory");
    gsl_rng_set(g, (unsigned long)seed);
    cs_status st = model_sample_radii(m, Bmax, ps, ps->n, 100, g, NULL, r);
    gsl_rng_free(g);
    return st;
}

cs_status exp_comp_run(const exp_comp_args *a)
{
    const char *cj = a->joint, *ci = a->indep, *dir = a->out;
    const int argc = a->argc;
    char **argv = a->argv;
    prov pv;
    prov_begin(&pv, "comparison", argc, argv);
    double beta = 0, jitter = 0;
    cs_status st = gate_read_value(PATHS_GATE("mechanism"), "dieback_train", 0, &beta);
    if (!st) st = gate_read_value(PATHS_GATE("anisotropy"), "canonical_jitter", 0, &jitter);
    model *mj = NULL, *mi = NULL;
    double sj = 0, si = 0;
    if (!st) st = train_load_model(cj, &mj, 64, &sj);
    if (!st) st = train_load_model(ci, &mi, 64, &si);
    if (!st && (!mj->cfg.joint || mi->cfg.joint)) st = cs_err(CS_EINPUT, "%s must be a joint-arm and %s an independent-arm checkpoint", cj, ci);
    if (!st && sj != si) st = cs_err(CS_EINPUT, "%s and %s were trained with different deviation scales", cj, ci);
    if (!st && mj->cfg.pair != mi->cfg.pair) st = cs_err(CS_EINPUT, "%s and %s are different models (pair %d vs %d)", cj, ci, mj->cfg.pair, mi->cfg.pair);
    if (st) { model_free(mj); model_free(mi); return st; }

    /* ---- the comparison patch ---- */
    const double d = DESIGN_GENCOMP_SPACING_M;
    stand *sd = NULL;
    patch_set *ps = NULL;
    double *rt = NULL, *rg = malloc(3 * PATCH_T * PATCH_P * sizeof *rg);
    double px[PATCH_T], py[PATCH_T], ph[PATCH_T], med[3];
    int ovl[3], flag[3][PATCH_T];
    if (!rg) st = cs_err(CS_ENOMEM, "out of memory");
    if (!st) st = stand_alloc(&sd, stems_lattice, d, 12.0 * d, jitter, "comparison", 0);
    if (!st && !(rt = malloc(sd->s->n * CROWN_NSEC * sizeof *rt))) st = cs_err(CS_ENOMEM, "out of memory");
    if (!st) st = grow(sd, beta, rt);
    patch_stand pst;
    patch p;
    if (!st) st = patch_stand_init(&pst, (int)sd->s->n, sd->s->x, sd->s->y, rt, sd->h, d);
    if (!st) {
        size_t focal = 0;
        st = stems_focal(sd->s, &focal);
        if (!st) st = patch_build(&pst, (int)focal, &p);
    }
    if (!st) st = patch_set_alloc(&ps, 1);
    if (!st) st = patch_set_add(ps, &p);
    if (!st) st = patch_set_standardise(ps, sj);
    if (!st) {
        for (int k = 0; k < PATCH_T; k++) {
            px[k] = p.px[k]; py[k] = p.py[k]; ph[k] = sd->h[p.idx[k]];
            memcpy(rg + (size_t)k * PATCH_P, rt + (size_t)p.idx[k] * CROWN_NSEC, PATCH_P * sizeof *rg);
        }
        st = gen_radii(mj, ps, 64, seed_derive("comparison", d, 0, "joint"), rg + PATCH_T * PATCH_P);
    }
    if (!st) st = gen_radii(mi, ps, 64, seed_derive("comparison", d, 0, "indep"), rg + 2 * PATCH_T * PATCH_P);
    for (int a = 0; a < 3 && !st; a++) st = patch_stats(px, py, rg + (size_t)a * PATCH_T * PATCH_P, &med[a], &ovl[a], flag[a]);

    /* ---- the dart probe: hard-core stems, every interior stem a focal tree ---- */
    double dmed[2] = {0, 0};
    int ndart = 0;
    patch_set *dp = NULL;
    if (!st) st = patch_set_alloc(&dp, 400);
    for (unsigned k = 0; k < COMP_DART_STANDS && !st; k++) {
        stand *hs;
        st = stand_alloc(&hs, stems_hardcore, d, 12.0 * d, COMP_HARDCORE_C, "comparison-dart", k);
        double *rh = st ? NULL : malloc(hs->s->n * CROWN_NSEC * sizeof *rh);
        if (!st && !rh) st = cs_err(CS_ENOMEM, "out of memory");
        if (!st) st = grow(hs, beta, rh);
        patch_stand hp;
        if (!st) st = patch_stand_init(&hp, (int)hs->s->n, hs->s->x, hs->s->y, rh, hs->h, d);
        for (size_t i = 0; i < hs->s->n && !st; i++) {
            if (!stems_interior(hs->s, i)) continue;
            patch q;
            st = patch_build(&hp, (int)i, &q);
            if (!st) st = patch_set_add(dp, &q);
        }
        free(rh);
        if (hs) stand_free(hs);
    }
    if (!st) st = patch_set_standardise(dp, sj);
    double *rr = NULL, *gt_ = NULL, *gg = NULL;
    if (!st) {
        ndart = dp->n;
        rr = malloc((size_t)ndart * PATCH_T * PATCH_P * sizeof *rr);
        gt_ = malloc((size_t)ndart * sizeof *gt_);
        gg = malloc((size_t)ndart * sizeof *gg);
        if (!rr || !gt_ || !gg) st = cs_err(CS_ENOMEM, "out of memory");
    }
    if (!st) {
        for (int k = 0; k < ndart; k++) patch_set_radii(dp, k, dp->x1 + (size_t)k * PATCH_T * PATCH_P, rr + (size_t)k * PATCH_T * PATCH_P);
        st = patch_focal_clearances(dp->px, dp->py, rr, ndart, 1, gt_);
    }
    if (!st) st = gen_radii(mj, dp, 64, seed_derive("comparison-dart", d, 0, "joint"), rr);
    if (!st) st = patch_focal_clearances(dp->px, dp->py, rr, ndart, 1, gg);
    if (!st) st = stats_median(gt_, (size_t)ndart, &dmed[0]);
    if (!st) st = stats_median(gg, (size_t)ndart, &dmed[1]);

    /* ---- write ---- */
    static const char *src[3] = {"teacher", "joint", "indep"};
    char path[1024];
    snprintf(pv.seeds, sizeof pv.seeds, "patch seed_derive(comparison, 5.0, 0, stems|crowns); probe seed_derive(comparison-dart, 5.0, 0..%d, ·); models: E3 seed 1",
             COMP_DART_STANDS - 1);
    for (int file = 0; file < 3 && !st; file++) {
        static const char *names[3] = {"patch.tsv", "patch_crowns.tsv", "dart_probe.tsv"};
        snprintf(path, sizeof path, "%s/comparison/%s", dir, names[file]);
        tsv_writer *w;
        if ((st = tsv_writer_open(&w, path))) break;
        if ((st = prov_write(w, &pv))) { tsv_writer_abort(w); break; }
        tsv_writer_meta(w, "models", "joint %s, independent %s (E3 seed 1; %s)", cj, ci,
                        mj->cfg.pair ? "pair-aware model, design.md §8.1" : "model without pair terms, design.md §8");
        if (file == 0) {
            tsv_writer_meta(w, "statistic", "median over the %d patch trees of the clearance toward the nearest patch tree; overlap = trees with a negative clearance toward any patch tree", PATCH_T);
            tsv_writer_columns(w, "source\tspacing_m\ttrees\tmedian_nn_clearance_m\toverlapping");
            for (int a = 0; a < 3; a++) {
                tsv_writer_str(w, src[a]); tsv_writer_dbl(w, d); tsv_writer_long(w, PATCH_T);
                tsv_writer_dbl(w, med[a]); tsv_writer_long(w, ovl[a]);
                tsv_writer_endrow(w);
            }
        } else if (file == 1) {
            tsv_writer_meta(w, "what", "crown outlines for the teaser panels b-d; positions relative to the focal stem; %d rows per tree per source", FIGDATA_ROWS);
            double X[3 * PATCH_T], Y[3 * PATCH_T], H[3 * PATCH_T];
            int fl[3 * PATCH_T];
            for (int a = 0; a < 3; a++)
                for (int k = 0; k < PATCH_T; k++) {
                    /* panels side by side: source a is shifted by a * 40 m in x */
                    X[a * PATCH_T + k] = px[k] + 40.0 * a; Y[a * PATCH_T + k] = py[k];
                    H[a * PATCH_T + k] = ph[k]; fl[a * PATCH_T + k] = flag[a][k];
                }
            tsv_writer_meta(w, "layout", "teacher at x offset 0, joint at 40 m, independent at 80 m");
            st = figdata_write_polygons(w, 3 * PATCH_T, X, Y, H, rg, fl, "overlapping");
        } else {
            tsv_writer_meta(w, "stems", "hard-core Poisson c = %.2f at %.1f m, %d stands, every interior stem a focal tree", COMP_HARDCORE_C, d, COMP_DART_STANDS);
            tsv_writer_columns(w, "source\tspacing_m\tpatches\tmedian_focal_nn_clearance_m");
            for (int a = 0; a < 2; a++) {
                tsv_writer_str(w, src[a]); tsv_writer_dbl(w, d); tsv_writer_long(w, ndart); tsv_writer_dbl(w, dmed[a]);
                tsv_writer_endrow(w);
            }
        }
        if (st) tsv_writer_abort(w);
        else st = tsv_writer_commit(w);
    }
    free(rr); free(gt_); free(gg); free(rt); free(rg);
    if (dp) patch_set_free(dp);
    if (ps) patch_set_free(ps);
    if (sd) stand_free(sd);
    model_free(mj); model_free(mi);
    return st;
}
