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
            if (j != i &&
                est_clearance(x[i], y[i], r + (size_t)i * CROWN_NSEC, x[j], y[j], r + (size_t)j * CROWN_NSEC) < 0)
                flag[i] = 1;
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

/* The two checkpoints of one reading and seed, the die-back and jitter of the
 * teacher they were trained on. */
typedef struct { model *mj, *mi; double sj, beta, jitter; } comp_models;

static void comp_models_free(comp_models *m) { model_free(m->mj); model_free(m->mi); }

static cs_status comp_models_load(const char *cj, const char *ci, comp_models *m)
{
    double si = 0;
    memset(m, 0, sizeof *m);
    cs_status st = gate_read_value(PATHS_GATE("mechanism"), "dieback_train", 0, &m->beta);
    if (!st) st = gate_read_value(PATHS_GATE("anisotropy"), "canonical_jitter", 0, &m->jitter);
    if (!st) st = train_load_model(cj, &m->mj, 64, &m->sj);
    if (!st) st = train_load_model(ci, &m->mi, 64, &si);
    if (!st && (!m->mj->cfg.joint || m->mi->cfg.joint))
        st = cs_err(CS_EINPUT, "%s must be a joint-arm and %s an independent-arm checkpoint", cj, ci);
    if (!st && m->sj != si) st = cs_err(CS_EINPUT, "%s and %s were trained with different deviation scales", cj, ci);
    if (!st && m->mj->cfg.pair != m->mi->cfg.pair)
        st = cs_err(CS_EINPUT, "%s and %s are different models (pair %d vs %d)", cj, ci, m->mj->cfg.pair,
                    m->mi->cfg.pair);
    if (st) comp_models_free(m);
    return st;
}

/* The comparison patch: its trees' positions and heights, the crowns of the
 * teacher, the joint and the independent model (rg: [3][PATCH_T][PATCH_P]),
 * and per source the median clearance, the overlap count and which trees overlap. */
typedef struct {
    double px[PATCH_T], py[PATCH_T], ph[PATCH_T], med[3];
    int ovl[3], flag[3][PATCH_T];
    double *rg;
} comp_patch;

static cs_status comp_patch_draw(const comp_models *m, double d, comp_patch *cp)
{
    stand *sd = NULL;
    patch_set *ps = NULL;
    double *rt = NULL;
    cs_status st = CS_OK;
    if (!(cp->rg = malloc(3 * PATCH_T * PATCH_P * sizeof *cp->rg))) st = cs_err(CS_ENOMEM, "out of memory");
    if (!st) st = stand_alloc(&sd, stems_lattice, d, 12.0 * d, m->jitter, "comparison", 0);
    if (!st && !(rt = malloc(sd->s->n * CROWN_NSEC * sizeof *rt))) st = cs_err(CS_ENOMEM, "out of memory");
    if (!st) st = grow(sd, m->beta, rt);
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
    if (!st) st = patch_set_standardise(ps, m->sj);
    if (!st) {
        for (int k = 0; k < PATCH_T; k++) {
            cp->px[k] = p.px[k]; cp->py[k] = p.py[k]; cp->ph[k] = sd->h[p.idx[k]];
            memcpy(cp->rg + (size_t)k * PATCH_P, rt + (size_t)p.idx[k] * CROWN_NSEC, PATCH_P * sizeof *cp->rg);
        }
        st = gen_radii(m->mj, ps, 64, seed_derive("comparison", d, 0, "joint"), cp->rg + PATCH_T * PATCH_P);
    }
    if (!st) st = gen_radii(m->mi, ps, 64, seed_derive("comparison", d, 0, "indep"), cp->rg + 2 * PATCH_T * PATCH_P);
    for (int a = 0; a < 3 && !st; a++)
        st = patch_stats(cp->px, cp->py, cp->rg + (size_t)a * PATCH_T * PATCH_P, &cp->med[a], &cp->ovl[a], cp->flag[a]);
    free(rt);
    if (ps) patch_set_free(ps);
    if (sd) stand_free(sd);
    return st;
}

/* The dart probe: hard-core stems, every interior stem a focal tree; the
 * median focal clearance of the teacher (dmed[0]) and the joint model (dmed[1]). */
static cs_status comp_dart(const comp_models *m, double d, double dmed[2], int *ndart)
{
    patch_set *dp = NULL;
    cs_status st = patch_set_alloc(&dp, 400);
    for (unsigned k = 0; k < COMP_DART_STANDS && !st; k++) {
        stand *hs;
        st = stand_alloc(&hs, stems_hardcore, d, 12.0 * d, COMP_HARDCORE_C, "comparison-dart", k);
        double *rh = st ? NULL : malloc(hs->s->n * CROWN_NSEC * sizeof *rh);
        if (!st && !rh) st = cs_err(CS_ENOMEM, "out of memory");
        if (!st) st = grow(hs, m->beta, rh);
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
    if (!st) st = patch_set_standardise(dp, m->sj);
    double *rr = NULL, *gt_ = NULL, *gg = NULL;
    if (!st) {
        *ndart = dp->n;
        rr = malloc((size_t)*ndart * PATCH_T * PATCH_P * sizeof *rr);
        gt_ = malloc((size_t)*ndart * sizeof *gt_);
        gg = malloc((size_t)*ndart * sizeof *gg);
        if (!rr || !gt_ || !gg) st = cs_err(CS_ENOMEM, "out of memory");
    }
    if (!st) {
        for (int k = 0; k < *ndart; k++)
            patch_set_radii(dp, k, dp->x1 + (size_t)k * PATCH_T * PATCH_P, rr + (size_t)k * PATCH_T * PATCH_P);
        st = patch_focal_clearances(dp->px, dp->py, rr, *ndart, 1, gt_);
    }
    if (!st) st = gen_radii(m->mj, dp, 64, seed_derive("comparison-dart", d, 0, "joint"), rr);
    if (!st) st = patch_focal_clearances(dp->px, dp->py, rr, *ndart, 1, gg);
    if (!st) st = stats_median(gt_, (size_t)*ndart, &dmed[0]);
    if (!st) st = stats_median(gg, (size_t)*ndart, &dmed[1]);
    free(rr); free(gt_); free(gg);
    if (dp) patch_set_free(dp);
    return st;
}

/* One of the three tables (0 patch.tsv, 1 patch_crowns.tsv, 2 dart_probe.tsv), its body. */
static cs_status comp_table(tsv_writer *w, int file, double d, const comp_patch *cp, const double dmed[2], int ndart)
{
    static const char *src[3] = {"teacher", "joint", "indep"};
    if (file == 0) {
        tsv_writer_meta(w, "statistic",
                        "median over the %d patch trees of the clearance toward the nearest patch tree; overlap = "
                        "trees with a negative clearance toward any patch tree",
                        PATCH_T);
        tsv_writer_columns(w, "source\tspacing_m\ttrees\tmedian_nn_clearance_m\toverlapping");
        for (int a = 0; a < 3; a++) {
            tsv_writer_str(w, src[a]); tsv_writer_dbl(w, d); tsv_writer_long(w, PATCH_T);
            tsv_writer_dbl(w, cp->med[a]); tsv_writer_long(w, cp->ovl[a]);
            tsv_writer_endrow(w);
        }
        return CS_OK;
    }
    if (file == 1) {
        tsv_writer_meta(w, "what",
                        "crown outlines for the teaser panels b-d; positions relative to the focal stem; %d rows per "
                        "tree per source",
                        FIGDATA_ROWS);
        double X[3 * PATCH_T], Y[3 * PATCH_T], H[3 * PATCH_T];
        int fl[3 * PATCH_T];
        for (int a = 0; a < 3; a++)
            for (int k = 0; k < PATCH_T; k++) {
                /* panels side by side: source a is shifted by a * 40 m in x */
                X[a * PATCH_T + k] = cp->px[k] + 40.0 * a; Y[a * PATCH_T + k] = cp->py[k];
                H[a * PATCH_T + k] = cp->ph[k]; fl[a * PATCH_T + k] = cp->flag[a][k];
            }
        tsv_writer_meta(w, "layout", "teacher at x offset 0, joint at 40 m, independent at 80 m");
        return figdata_write_polygons(w, 3 * PATCH_T, X, Y, H, cp->rg, fl, "overlapping");
    }
    tsv_writer_meta(w, "stems", "hard-core Poisson c = %.2f at %.1f m, %d stands, every interior stem a focal tree",
                    COMP_HARDCORE_C, d, COMP_DART_STANDS);
    tsv_writer_columns(w, "source\tspacing_m\tpatches\tmedian_focal_nn_clearance_m");
    for (int a = 0; a < 2; a++) {
        tsv_writer_str(w, src[a]); tsv_writer_dbl(w, d); tsv_writer_long(w, ndart); tsv_writer_dbl(w, dmed[a]);
        tsv_writer_endrow(w);
    }
    return CS_OK;
}

cs_status exp_comp_run(const exp_comp_args *a)
{
    const char *cj = a->joint, *ci = a->indep, *dir = a->out;
    prov pv;
    prov_begin(&pv, "comparison", a->argc, a->argv);
    comp_models m;
    cs_status st = comp_models_load(cj, ci, &m);
    if (st) return st;
    const double d = DESIGN_GENCOMP_SPACING_M;
    comp_patch cp = {0};
    double dmed[2] = {0, 0};
    int ndart = 0;
    st = comp_patch_draw(&m, d, &cp);
    if (!st) st = comp_dart(&m, d, dmed, &ndart);
    char path[1024];
    snprintf(pv.seeds, sizeof pv.seeds,
             "patch seed_derive(comparison, 5.0, 0, stems|crowns); probe seed_derive(comparison-dart, 5.0, 0..%d, ·); "
             "models: E3 seed 1",
             COMP_DART_STANDS - 1);
    for (int file = 0; file < 3 && !st; file++) {
        static const char *names[3] = {"patch.tsv", "patch_crowns.tsv", "dart_probe.tsv"};
        snprintf(path, sizeof path, "%s/comparison/%s", dir, names[file]);
        tsv_writer *w;
        if ((st = tsv_writer_open(&w, path))) break;
        if ((st = prov_write(w, &pv))) { tsv_writer_abort(w); break; }
        const char *kind =
            m.mj->cfg.pair ? "pair-aware model, design.md §8.1" : "model without pair terms, design.md §8";
        tsv_writer_meta(w, "models", "joint %s, independent %s (E3 seed 1; %s)", cj, ci, kind);
        st = comp_table(w, file, d, &cp, dmed, ndart);
        if (st) tsv_writer_abort(w);
        else st = tsv_writer_commit(w);
    }
    free(cp.rg);
    comp_models_free(&m);
    return st;
}
