/* exp_compdist: E7 and the dart probe over many fresh patches (see
 * exp_compdist.h). Clearances use the pinned estimator (est_knn_clearance,
 * est_clearance) on the patch trees, as exp_comp does. */
#include "exp_compdist.h"
#include "design.h"
#include "estimator.h"
#include "figdata.h"
#include "gate.h"
#include "model.h"
#include "patch.h"
#include "paths.h"
#include "prov.h"
#include "seed.h"
#include "stand.h"
#include "stand_grow.h"
#include "stats.h"
#include "stems.h"
#include "train.h"
#include "tsv.h"
#include "afile.h"
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define CD_HARDCORE_C 0.5 /* the figures' hard-core level (design.md §7 E8/E9) */
enum { CD_TEACH = 0, CD_JOINT = 1, CD_INDEP = 2, CD_NSRC = 3 };
static const char *const CD_SRC[CD_NSRC] = {"teacher", "joint", "indep"};

/* Median NN clearance over the patch trees and the trees overlapping any patch tree. */
static cs_status patch_stats(const double *x, const double *y, const double *r, double *med, int *overlap)
{
    double g[PATCH_T];
    *overlap = 0;
    for (int i = 0; i < PATCH_T; i++) {
        cs_status st = est_knn_clearance(x, y, r, PATCH_T, (size_t)i, 1, &g[i]);
        if (st) return st;
        int hit = 0;
        for (int j = 0; j < PATCH_T && !hit; j++)
            if (j != i &&
                est_clearance(x[i], y[i], r + (size_t)i * CROWN_NSEC, x[j], y[j], r + (size_t)j * CROWN_NSEC) < 0)
                hit = 1;
        *overlap += hit;
    }
    return stats_median(g, PATCH_T, med);
}

/* The central-stem patch of stand k of `key` (lattice or hard-core) into ps. */
static cs_status add_patch(const char *key, const stems_type *kind, double shape, double d, double beta, unsigned k,
                           patch_set *ps, double *h /* [PATCH_T] heights of the patch trees, or NULL */)
{
    stand *sd;
    cs_status st = stand_alloc(&sd, kind, d, 12.0 * d, shape, key, k);
    if (st) return st;
    double *r = malloc(sd->s->n * CROWN_NSEC * sizeof *r);
    if (!r) { stand_free(sd); return cs_err(CS_ENOMEM, "out of memory"); }
    teacher_params tp;
    teacher_params_default(&tp);
    tp.beta = beta;
    st = stand_grow(sd, &tp, NULL, r, NULL, NULL);
    patch_stand pst;
    patch p;
    size_t focal = 0;
    if (!st) st = patch_stand_init(&pst, (int)sd->s->n, sd->s->x, sd->s->y, r, sd->h, d);
    if (!st) st = stems_focal(sd->s, &focal);
    if (!st) st = patch_build(&pst, (int)focal, &p);
    for (int i = 0; i < PATCH_T && !st && h; i++) h[i] = sd->h[p.idx[i]];
    if (!st) st = patch_set_add(ps, &p);
    free(r);
    stand_free(sd);
    return st;
}

/* Per patch and source (nsrc sources: teacher, then the models m[0..nm)):
 * med[s * n + k], ovl[s * n + k]. */
static cs_status measure(const patch_set *ps, model *const *m, int nm, const char *key, double d, double *med, int *ovl,
                         double *keep /* [(nm + 1) * n * T * P] every source's radii, or NULL */)
{
    const int n = ps->n;
    const size_t tp = (size_t)PATCH_T * PATCH_P;
    double *own = keep ? NULL : malloc((size_t)n * tp * sizeof *own);
    cs_status st = keep || own ? CS_OK : cs_err(CS_ENOMEM, "out of memory");
    for (int s = 0; s <= nm && !st; s++) {
        double *r = keep ? keep + (size_t)s * n * tp : own;
        if (s == 0)
            for (int k = 0; k < n; k++) patch_set_radii(ps, k, ps->x1 + (size_t)k * tp, r + (size_t)k * tp);
        else {
            gsl_rng *g = gsl_rng_alloc(gsl_rng_mt19937);
            if (!g) { st = cs_err(CS_ENOMEM, "out of memory"); break; }
            gsl_rng_set(g, (unsigned long)seed_derive(key, d, 0, CD_SRC[s]));
            st = model_sample_radii(m[s - 1], 64, ps, n, 100, g, NULL, r);
            gsl_rng_free(g);
        }
        for (int k = 0; k < n && !st; k++)
            st = patch_stats(ps->px + (size_t)k * PATCH_T, ps->py + (size_t)k * PATCH_T, r + (size_t)k * tp,
                             &med[(size_t)s * n + k], &ovl[(size_t)s * n + k]);
    }
    free(own);
    return st;
}

/* The figure patch's crowns for the teaser panels: every source side by side
 * (source s shifted by 40 m in x), each tree flagged when its crown runs into
 * another patch tree's (as patch_stats counts them). r: every source's radii. */
static cs_status write_figure(const char *dir, prov *pv, const char *cj, const char *ci, const patch_set *ps,
                              const double *r, const double *h, int fig)
{
    const size_t tp = (size_t)PATCH_T * PATCH_P;
    const int n = ps->n;
    double X[CD_NSRC * PATCH_T], Y[CD_NSRC * PATCH_T], H[CD_NSRC * PATCH_T], R[CD_NSRC * PATCH_T * PATCH_P];
    int fl[CD_NSRC * PATCH_T];
    const double *px = ps->px + (size_t)fig * PATCH_T, *py = ps->py + (size_t)fig * PATCH_T;
    for (int s = 0; s < CD_NSRC; s++) {
        const double *rs = r + ((size_t)s * n + fig) * tp;
        memcpy(R + (size_t)s * tp, rs, tp * sizeof *R);
        for (int i = 0; i < PATCH_T; i++) {
            int hit = 0;
            for (int j = 0; j < PATCH_T && !hit; j++)
                if (j != i && est_clearance(px[i], py[i], rs + (size_t)i * CROWN_NSEC, px[j], py[j],
                                            rs + (size_t)j * CROWN_NSEC) < 0)
                    hit = 1;
            X[s * PATCH_T + i] = px[i] + 40.0 * s;
            Y[s * PATCH_T + i] = py[i];
            H[s * PATCH_T + i] = h[(size_t)fig * PATCH_T + i];
            fl[s * PATCH_T + i] = hit;
        }
    }
    char path[1024];
    snprintf(path, sizeof path, "%s/comparison/figure_crowns.tsv", dir);
    tsv_writer *w;
    cs_status st = tsv_writer_open(&w, path);
    if (st) return st;
    if ((st = prov_write(w, pv))) { tsv_writer_abort(w); return st; }
    tsv_writer_meta(w, "models", "joint %s, independent %s", cj, ci);
    tsv_writer_meta(w, "figure_patch",
                    "%d: the rule fixed before the run, the lower median of the joint arm's per-patch medians (rank "
                    "floor((N - 1) / 2), ties by patch index)",
                    fig);
    tsv_writer_meta(w, "what",
                    "crown outlines of the figure patch (probe comparison) for the teaser panels; positions relative "
                    "to the focal stem; %d rows per tree per source",
                    FIGDATA_ROWS);
    tsv_writer_meta(w, "layout",
                    "teacher at x offset 0, joint at 40 m, independent at 80 m; tree = source x %d + patch tree",
                    PATCH_T);
    st = figdata_write_polygons(w, CD_NSRC * PATCH_T, X, Y, H, R, fl, "overlapping");
    if (st) { tsv_writer_abort(w); return st; }
    return tsv_writer_commit(w);
}

/* Quantiles 0.05, 0.5, 0.95 of x[n] and the fraction of zeros of o[n]. */
static cs_status summarise(const double *x, const int *o, int n, double q[3], double ovq[3], double *zero)
{
    static const double qs[3] = {0.05, 0.5, 0.95};
    double *ov = malloc((size_t)n * sizeof *ov);
    if (!ov) return cs_err(CS_ENOMEM, "out of memory");
    int z = 0;
    for (int k = 0; k < n; k++) { ov[k] = o[k]; z += o[k] == 0; }
    cs_status st = CS_OK;
    for (int i = 0; i < 3 && !st; i++) {
        st = stats_quantile(x, (size_t)n, qs[i], &q[i]);
        if (!st) st = stats_quantile(ov, (size_t)n, qs[i], &ovq[i]);
    }
    *zero = (double)z / n;
    free(ov);
    return st;
}

/* The figure patch: lower median of the joint arm's per-patch medians. */
static int figure_patch(const double *x, int n)
{
    int *idx = malloc((size_t)n * sizeof *idx), pick = 0;
    if (!idx) return 0;
    for (int k = 0; k < n; k++) idx[k] = k;
    for (int a = 1; a < n; a++) /* insertion sort by (value, index) */
        for (int b = a; b > 0 && (x[idx[b]] < x[idx[b - 1]] || (x[idx[b]] == x[idx[b - 1]] && idx[b] < idx[b - 1]));
             b--) {
            int t = idx[b]; idx[b] = idx[b - 1]; idx[b - 1] = t;
        }
    pick = idx[(n - 1) / 2];
    free(idx);
    return pick;
}

static cs_status write_tables(const char *dir, prov *pv, const char *cj, const char *ci, int n, int nd,
                              const double *med, const int *ovl, const double *dmed, const int *dovl, int fig)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/comparison/dist_patches.tsv", dir);
    cs_status st = afile_mkdir_parents(path);
    tsv_writer *w = NULL;
    if (!st) st = tsv_writer_open(&w, path);
    if (!st && (st = prov_write(w, pv))) { tsv_writer_abort(w); return st; }
    if (st) return st;
    tsv_writer_meta(w, "models", "joint %s, independent %s", cj, ci);
    tsv_writer_meta(w, "what",
                    "per patch and source: median over the %d patch trees of the clearance toward the nearest patch "
                    "tree (m), trees with a negative clearance toward any patch tree; probe comparison = lattice "
                    "patches at 5.0 m, dart = hard-core stems c = %.2f",
                    PATCH_T, CD_HARDCORE_C);
    tsv_writer_columns(w, "probe\tpatch\tsource\tmedian_nn_clearance_m\toverlapping");
    for (int pr = 0; pr < 2; pr++)
        for (int s = 0; s < (pr ? 2 : CD_NSRC); s++)
            for (int k = 0; k < (pr ? nd : n); k++) {
                tsv_writer_str(w, pr ? "dart" : "comparison"); tsv_writer_long(w, k); tsv_writer_str(w, CD_SRC[s]);
                tsv_writer_dbl(w, pr ? dmed[(size_t)s * nd + k] : med[(size_t)s * n + k]);
                tsv_writer_long(w, pr ? dovl[(size_t)s * nd + k] : ovl[(size_t)s * n + k]);
                tsv_writer_endrow(w);
            }
    if ((st = tsv_writer_commit(w))) return st;
    snprintf(path, sizeof path, "%s/comparison/dist_summary.tsv", dir);
    if ((st = tsv_writer_open(&w, path))) return st;
    if ((st = prov_write(w, pv))) { tsv_writer_abort(w); return st; }
    tsv_writer_meta(w, "models", "joint %s, independent %s", cj, ci);
    tsv_writer_meta(
        w, "what",
        "per probe and source over the patches of dist_patches.tsv: 5 %%, 50 %% and 95 %% quantiles of the per-patch "
        "median NN clearance and of the overlapping count, and the fraction of patches with no overlapping crown");
    tsv_writer_meta(w, "figure_patch",
                    "%d: the rule fixed before the run, the lower median of the joint arm's per-patch medians (rank "
                    "floor((N - 1) / 2), ties by patch index)",
                    fig);
    tsv_writer_columns(w, "probe\tsource\tpatches\tmedian_nn_q05\tmedian_nn_q50\tmedian_nn_q95\toverlapping_"
                          "q05\toverlapping_q50\toverlapping_q95\tno_overlap_fraction");
    for (int pr = 0; pr < 2 && !st; pr++)
        for (int s = 0; s < (pr ? 2 : CD_NSRC) && !st; s++) {
            const int m = pr ? nd : n;
            double q[3], oq[3], z = 0;
            st = summarise(pr ? dmed + (size_t)s * nd : med + (size_t)s * n,
                           pr ? dovl + (size_t)s * nd : ovl + (size_t)s * n, m, q, oq, &z);
            if (st) break;
            tsv_writer_str(w, pr ? "dart" : "comparison"); tsv_writer_str(w, CD_SRC[s]); tsv_writer_long(w, m);
            for (int i = 0; i < 3; i++) tsv_writer_dbl(w, q[i]);
            for (int i = 0; i < 3; i++) tsv_writer_dbl(w, oq[i]);
            tsv_writer_dbl(w, z);
            tsv_writer_endrow(w);
        }
    if (st) { tsv_writer_abort(w); return st; }
    return tsv_writer_commit(w);
}

cs_status exp_compdist_run(const exp_compdist_args *a)
{
    const char *cj = a->joint, *ci = a->indep, *dir = a->out;
    const long np = a->patches > 0 ? a->patches : 256;
    if (!cj || !ci || !dir) return cs_err(CS_EUSAGE, "comparison-dist: --joint, --indep and --out are required");
    prov pv;
    prov_begin(&pv, "comparison", a->argc, a->argv);
    double beta = 0, jitter = 0, sj = 0, si = 0;
    model *m[2] = {NULL, NULL};
    cs_status st = gate_read_value(PATHS_GATE("mechanism"), "dieback_train", 0, &beta);
    if (!st) st = gate_read_value(PATHS_GATE("anisotropy"), "canonical_jitter", 0, &jitter);
    if (!st) st = train_load_model(cj, &m[0], 64, &sj);
    if (!st) st = train_load_model(ci, &m[1], 64, &si);
    if (!st && (!m[0]->cfg.joint || m[1]->cfg.joint))
        st = cs_err(CS_EINPUT, "%s must be a joint-arm and %s an independent-arm model", cj, ci);
    if (!st && (sj != si || model_cfg_reading(&m[0]->cfg) != model_cfg_reading(&m[1]->cfg)))
        st = cs_err(CS_EINPUT, "%s and %s are not the two arms of one reading and seed", cj, ci);
    const double d = DESIGN_GENCOMP_SPACING_M;
    const int n = (int)np;
    patch_set *ps = NULL, *dp = NULL;
    double *med = malloc((size_t)CD_NSRC * n * sizeof *med), *dmed = malloc((size_t)2 * n * sizeof *dmed);
    int *ovl = malloc((size_t)CD_NSRC * n * sizeof *ovl), *dovl = malloc((size_t)2 * n * sizeof *dovl);
    if (!st && (!med || !dmed || !ovl || !dovl)) st = cs_err(CS_ENOMEM, "out of memory");
    double *keep = malloc((size_t)CD_NSRC * n * PATCH_T * PATCH_P * sizeof *keep),
           *hts = malloc((size_t)n * PATCH_T * sizeof *hts);
    if (!st && (!keep || !hts)) st = cs_err(CS_ENOMEM, "out of memory");
    if (!st) st = patch_set_alloc(&ps, n);
    if (!st) st = patch_set_alloc(&dp, n);
    for (int k = 0; k < n && !st; k++) {
        st = add_patch("comparison-dist", stems_lattice, jitter, d, beta, (unsigned)k, ps, hts + (size_t)k * PATCH_T);
        if (!st) st = add_patch("comparison-dist-dart", stems_hardcore, CD_HARDCORE_C, d, beta, (unsigned)k, dp, NULL);
    }
    if (!st) st = patch_set_standardise(ps, sj);
    if (!st) st = patch_set_standardise(dp, sj);
    if (!st) st = measure(ps, m, 2, "comparison-dist", d, med, ovl, keep);
    if (!st) st = measure(dp, m, 1, "comparison-dist-dart", d, dmed, dovl, NULL);
    snprintf(pv.seeds, sizeof pv.seeds,
             "patches seed_derive(comparison-dist[-dart], 5.0, 0..%d, stems|crowns); sampling "
             "seed_derive(comparison-dist[-dart], 5.0, 0, joint|indep)",
             n - 1);
    pv.worst_overlap_m = -1;
    const int fig = st ? 0 : figure_patch(med + (size_t)CD_JOINT * n, n);
    if (!st) st = write_tables(dir, &pv, cj, ci, n, n, med, ovl, dmed, dovl, fig);
    if (!st) st = write_figure(dir, &pv, cj, ci, ps, keep, hts, fig);
    free(med); free(dmed); free(ovl); free(dovl); free(keep); free(hts);
    patch_set_free(ps); patch_set_free(dp);
    model_free(m[0]); model_free(m[1]);
    return st;
}
