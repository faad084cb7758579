/* interval_src: the replicate units of each family of claims, read from
 * frozen/ (design.md §6.1): seeds of the E3/E4 run tables, unseen spacings of
 * the baselines, stands of the E5/E6 per-tree tables, patches of the E7
 * distribution, replicate stands of the figure stands (and, in
 * interval_field.c the stands of the E5/E6 per-tree tables, in
 * interval_stands.c and interval_irred.c the stands of the pooled E1 sweep
 * and E2 tables). Each extractor hands
 * back units and the claim's statistic over them; interval.c checks that the
 * frozen units give the claim's own value. */
#include "interval.h"
#include "interval_field.h"
#include "interval_stands.h"
#include "mainruns.h"
#include "design.h"
#include "estimator.h"
#include "fieldsim.h"
#include "gate.h"
#include "paths.h"
#include "stats.h"
#include "tsv.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAXSEED 64

static cs_status alloc_x(iv_data *d, size_t n, size_t m)
{
    d->x = calloc(n * m > 0 ? n * m : 1, sizeof *d->x);
    d->n = n;
    d->m = m;
    return d->x ? CS_OK : cs_err(CS_ENOMEM, "interval: out of memory");
}

/* ---- E3: seeds of runs.tsv; columns as claim_main.c's kinds ---- */

static int run_col(const char *arm, const char *probe)
{
    int a = !strcmp(arm, "joint") ? 0 : !strcmp(arm, "indep") ? 1 : -1;
    int q = !strcmp(probe, "generated") ? 0 : !strcmp(probe, "shuffled") ? 1 : !strcmp(probe, "rotated") ? 2 : -1;
    return a < 0 || q < 0 ? -1 : 2 * q + a; /* 0 joint, 1 indep, 2 joint shuffled, 3 indep shuffled, 4/5 rotated */
}

/* Every unit of a reading's unit set, or an error: a claim still pending has
 * no interval, so an incomplete set here is an inconsistency. */
static cs_status unit_set_load(const claim_row *row, const char *dir, const mainruns **out)
{
    static mainruns m;
    int want;
    cs_status st = claim_param_seeds(row, &want);
    if (!st) st = mainruns_load(dir, want, &m);
    if (st) return st;
    if (m.complete != want)
        return cs_err(CS_EINVARIANT, "%s: %d of %d seeds frozen: no interval before the set is complete", dir,
                      m.complete, want);
    *out = &m;
    return CS_OK;
}

/* A reading's unit set (<dir>/run_s*_*.tsv): the per-seed errors as
 * mainruns gathers them for the claims (main-summary's reduction); only
 * asked for once every unit is frozen (a pending claim has no interval). */
static cs_status unit_set_seeds(const claim_row *row, const char *dir, double v[MAXSEED][6], int *maxs)
{
    const mainruns *m;
    cs_status st = unit_set_load(row, dir, &m);
    if (st) return st;
    const int want = m->want;
    for (int s = 0; s < want && s < MAXSEED; s++)
        for (int q = 0; q < 3; q++)
            for (int a = 0; a < 2; a++) v[s][2 * q + a] = m->has[a][q] ? m->err[a][q][s] : NAN;
    *maxs = want;
    return CS_OK;
}

/* The statistic of an E3 claim over the per-seed columns (run_col), by its
 * function and the row's arm, probe, bound and stat, as claim_main.c
 * computes it. */
static cs_status main_stat(const claim_row *row, iv_data *d)
{
    const char *f = row->function;
    const claim_params *p = &row->param;
    if (!strcmp(f, "claim_main_rel")) { d->stat = (iv_stat){IV_REL, 0, 1, NULL, NULL}; return CS_OK; }
    if (!strcmp(f, "claim_main_p")) { d->stat = (iv_stat){IV_WILCOXON, 0, 1, NULL, NULL}; return CS_OK; }
    if (!strcmp(f, "claim_main_geom_ratio")) { d->stat = (iv_stat){IV_RATIO, 2, 0, NULL, NULL}; return CS_OK; }
    int k;
    cs_status st = claim_param_seed_column(row, &k);
    if (st) return st;
    if (!strcmp(f, "claim_main_median")) d->stat = (iv_stat){IV_MEDIAN, (size_t)k, 0, NULL, NULL};
    else if (!strcmp(f, "claim_main_range")) {
        if ((st = claim_param_need(row, PARAM_BOUND))) return st;
        d->stat = (iv_stat){p->bound == BOUND_HI ? IV_MAX : IV_MIN, (size_t)k, 0, NULL, NULL};
    } else if (!strcmp(f, "claim_main_probe")) {
        if ((st = claim_param_need(row, PARAM_PROBE | PARAM_STAT))) return st;
        /* the ratio of the probe's median to the arm's own (its column k % 2) */
        d->stat = p->stat == STAT_RATIO ? (iv_stat){IV_RATIO, (size_t)k, (size_t)(k % 2), NULL, NULL}
                                        : (iv_stat){IV_MEDIAN, (size_t)k, 0, NULL, NULL};
    } else
        return cs_err(CS_EINVARIANT, "interval: no seed statistic for %s (%s)", row->macro, f);
    return CS_OK;
}

static cs_status main_seeds(const claim_row *row, const claim_result *res, const interval_spec *sp, iv_data *d)
{
    (void)res; (void)sp;
    double v[MAXSEED][6];
    int maxs = 0;
    for (int i = 0; i < MAXSEED; i++) for (int k = 0; k < 6; k++) v[i][k] = NAN;
    char dir[300];
    tsv *t = NULL;
    cs_status st = mainruns_unit_set(row->source, dir, sizeof dir) ? unit_set_seeds(row, dir, v, &maxs)
                                                                   : tsv_read(row->source, &t);
    if (st) return st;
    for (size_t r = 0; t && r < tsv_nrows(t) && !st; r++) {
        long s;
        double e;
        const char *arm = tsv_str(t, r, "arm"), *probe = tsv_str(t, r, "probe");
        if ((st = tsv_long(t, r, "seed", &s)) || (st = tsv_double(t, r, "error", &e))) break;
        int k = arm && probe ? run_col(arm, probe) : -1;
        if (s < 1 || s > MAXSEED || k < 0) {
            st = cs_err(CS_EINPUT, "%s:%d: field 'seed'/'arm'/'probe': unexpected row", row->source, tsv_line(t, r));
            break;
        }
        v[s - 1][k] = e;
        if (s > maxs) maxs = (int)s;
    }
    tsv_free(t);
    if (!st) st = alloc_x(d, (size_t)maxs, 6);
    if (st) return st;
    for (int i = 0; i < maxs; i++) memcpy(d->x + (size_t)i * 6, v[i], sizeof v[i]);
    d->unit = "seed";
    d->method = "bootstrap";
    snprintf(d->from, sizeof d->from, "%s (%d seeds)", row->source, maxs);
    return main_stat(row, d);
}

/* ---- E3 baselines: the unseen spacings, mean over them ---- */

static cs_status main_spacings(const claim_row *row, const claim_result *res, const interval_spec *sp, iv_data *d)
{
    (void)res; (void)sp;
    char path[256];
    const char *src = row->source, *leaf = "baselines.tsv";
    size_t ls = strlen(src), lb = strlen(leaf);
    if (ls >= lb && !strcmp(src + ls - lb, leaf)) snprintf(path, sizeof path, "%s", src);
    else {
        const char *cut = NULL;
        for (const char *q = src; (q = strstr(q, "/main/")); q++) cut = q;
        for (const char *q = src; (q = strstr(q, "/extrapolation/")); q++) if (!cut || q > cut) cut = q;
        snprintf(path, sizeof path, "%.*s/main/%s", cut ? (int)(cut - src) : 6, cut ? src : "frozen", leaf);
    }
    /* the noise floor, or the teacher's own crowns under the row's probe */
    char col[40] = "noise_floor_w1";
    cs_status st = CS_OK;
    if (strcmp(row->function, "claim_main_noise")) {
        if ((st = claim_param_need(row, PARAM_PROBE))) return st;
        snprintf(col, sizeof col, "teacher_%s_w1", param_probe_name(row->param.probe));
    }
    tsv *t;
    if ((st = tsv_read(path, &t))) return st;
    if (!(st = alloc_x(d, tsv_nrows(t), 1))) {
        size_t n = 0;
        for (size_t r = 0; r < tsv_nrows(t) && !st; r++) {
            const char *split = tsv_str(t, r, "split");
            if (!split || strcmp(split, "unseen")) continue;
            st = tsv_double(t, r, col, &d->x[n++]);
        }
        d->n = n;
    }
    tsv_free(t);
    d->unit = "spacing";
    d->method = "bootstrap";
    d->stat = (iv_stat){IV_MEAN, 0, 0, NULL, NULL};
    snprintf(d->from, sizeof d->from, "%s (%s, %zu unseen spacings)", path, col, d->n);
    return st;
}

/* ---- E4: seeds of extrapolation/runs.tsv ---- */

/* The extrapolation rows of a reading's unit set, as mainruns gathers them. */
static cs_status unit_set_extrap(const claim_row *row, const char *dir, double dd[4], double w[MAXSEED][4][2], int *nd,
                                 int *maxs)
{
    const mainruns *m;
    cs_status st = unit_set_load(row, dir, &m);
    if (st) return st;
    const int want = m->want;
    *nd = m->nex < 4 ? m->nex : 4;
    for (int k = 0; k < *nd; k++) {
        dd[k] = m->exd[k];
        for (int s = 0; s < want && s < MAXSEED; s++) { w[s][k][0] = m->ex[0][k][s]; w[s][k][1] = m->ex[1][k][s]; }
    }
    *maxs = want;
    return CS_OK;
}

static cs_status extrap_seeds(const claim_row *row, const claim_result *res, const interval_spec *sp, iv_data *d)
{
    (void)res; (void)sp;
    /* per seed: joint and indep W1 at each of up to 4 spacings (file order) */
    double dd[4], w[MAXSEED][4][2];
    int nd = 0, maxs = 0;
    char dir[300];
    tsv *t = NULL;
    cs_status st = mainruns_unit_set(row->source, dir, sizeof dir) ? unit_set_extrap(row, dir, dd, w, &nd, &maxs)
                                                                   : tsv_read(row->source, &t);
    if (st) return st;
    for (size_t r = 0; t && r < tsv_nrows(t) && !st; r++) {
        long s;
        double sp_m, w1;
        const char *arm = tsv_str(t, r, "arm");
        if ((st = tsv_long(t, r, "seed", &s)) || (st = tsv_double(t, r, "spacing", &sp_m)) ||
            (st = tsv_double(t, r, "w1", &w1)))
            break;
        int k = 0;
        while (k < nd && fabs(dd[k] - sp_m) > 1e-9) k++;
        if (k == nd && nd < 4) dd[nd++] = sp_m;
        int a = arm && !strcmp(arm, "joint") ? 0 : arm && !strcmp(arm, "indep") ? 1 : -1;
        if (k == 4 || a < 0 || s < 1 || s > MAXSEED) {
            st = cs_err(CS_EINPUT, "%s:%d: unexpected row", row->source, tsv_line(t, r));
            break;
        }
        w[s - 1][k][a] = w1;
        if (s > maxs) maxs = (int)s;
    }
    tsv_free(t);
    if (st) return st;
    d->unit = "seed";
    d->method = "bootstrap";
    snprintf(d->from, sizeof d->from, "%s (%d seeds)", row->source, maxs);
    if (!strcmp(row->function, "claim_extrap_p")) {
        /* claim_extrap_p: per seed, the mean over the spacings of each arm */
        if ((st = alloc_x(d, (size_t)maxs, 2))) return st;
        for (int i = 0; i < maxs; i++) {
            double a = 0, b = 0;
            for (int k = 0; k < nd; k++) { a += w[i][k][1] / nd; b += w[i][k][0] / nd; }
            d->x[2 * i] = b;
            d->x[2 * i + 1] = a;
        }
        d->stat = (iv_stat){IV_WILCOXON, 0, 1, NULL, NULL};
        return CS_OK;
    }
    /* bound=lo: the lowest spacing, bound=hi: the highest */
    if ((st = claim_param_need(row, PARAM_BOUND))) return st;
    int lowk = 0, highk = 0;
    for (int k = 1; k < nd; k++) { if (dd[k] < dd[lowk]) lowk = k; if (dd[k] > dd[highk]) highk = k; }
    int k = row->param.bound == BOUND_LO ? lowk : highk;
    if ((st = alloc_x(d, (size_t)maxs, 2))) return st;
    for (int i = 0; i < maxs; i++) { d->x[2 * i] = w[i][k][0]; d->x[2 * i + 1] = w[i][k][1]; }
    d->stat = (iv_stat){IV_REL, 0, 1, NULL, NULL};
    return CS_OK;
}

/* ---- E7: patches of a distribution table drawn from the same models ---- */

/* "--joint X --indep Y" of a table's command line. */
static int models_of(const tsv *t, char *buf, size_t n)
{
    const char *c = tsv_meta(t, "command"), *j = c ? strstr(c, "--joint ") : NULL,
               *i = c ? strstr(c, "--indep ") : NULL;
    if (!j || !i) return 0;
    snprintf(buf, n, "%.*s|%.*s", (int)strcspn(j + 8, " "), j + 8, (int)strcspn(i + 8, " "), i + 8);
    return 1;
}

/* E7 (design.md §7 E7): the claims are statistics over the patches of
 * dist_patches.tsv beside their dist_summary.tsv (the median; with
 * stat=range the value is the 5 % quantile; the share of patches without an
 * overlapping crown), bootstrapped over the patches. */
static cs_status comp_patches(const claim_row *row, const claim_result *res, const interval_spec *sp, iv_data *d)
{
    (void)res; (void)sp;
    d->unit = "patch";
    /* the reference paper's E7 values are one patch each: they are compared
     * with the range of one patch over the fresh patches, not with the
     * sampling interval of a median over them (design.md §6.1); the share of
     * patches without an overlap has no one-patch counterpart */
    d->method = strcmp(row->function, "claim_comp_no_overlap") ? "range" : "bootstrap";
    tsv *src;
    cs_status st = tsv_read(row->source, &src);
    if (st) return st;
    char want[280], got[280], path[520];
    int ok = models_of(src, want, sizeof want);
    tsv_free(src);
    if (!ok) return cs_err(CS_EINPUT, "%s: header '# command:' names no --joint/--indep models", row->source);
    const char *slash = strrchr(row->source, '/');
    snprintf(path, sizeof path, "%.*sdist_patches.tsv", slash ? (int)(slash - row->source + 1) : 0, row->source);
    tsv *t;
    if ((st = tsv_read(path, &t))) return st;
    if (!models_of(t, got, sizeof got) || strcmp(got, want)) {
        tsv_free(t);
        return cs_err(CS_EINVARIANT, "%s: drawn from models %s, its summary %s from %s", path, got, row->source, want);
    }
    const char *f = row->function;
    const int no_overlap = !strcmp(f, "claim_comp_no_overlap");
    /* the share without an overlap is the joint arm's; the others name their arm and statistic */
    if (!no_overlap && (st = claim_param_need(row, PARAM_ARM | PARAM_STAT))) { tsv_free(t); return st; }
    const char *probe = !strcmp(f, "claim_comp_dart") ? "dart" : "comparison";
    const char *s = no_overlap ? "joint" : param_arm_name(row->param.arm);
    const char *col = !strcmp(f, "claim_comp_overlap") || no_overlap ? "overlapping" : "median_nn_clearance_m";
    int range = !no_overlap && row->param.stat == STAT_RANGE;
    d->stat = (iv_stat){no_overlap ? IV_ZERO_PCT : IV_QUANTILE, 0, 0, NULL, NULL, range ? 0.05 : 0.5};
    if (!(st = alloc_x(d, tsv_nrows(t), 1))) {
        size_t n = 0;
        for (size_t r = 0; r < tsv_nrows(t) && !st; r++) {
            const char *pr = tsv_str(t, r, "probe"), *so = tsv_str(t, r, "source");
            if (!pr || !so || strcmp(pr, probe) || strcmp(so, s)) continue;
            st = tsv_double(t, r, col, &d->x[n++]);
        }
        d->n = n;
        if (!st && n == 0) st = cs_err(CS_EINPUT, "%s: no %s rows of source %s", path, probe, s);
    }
    snprintf(d->from, sizeof d->from, "%s (%s, %s, %s; %zu patches)", path, probe, s, col, d->n);
    tsv_free(t);
    return st;
}

/* ---- one-stand claims: the replicate stands of the same family ---- */

/* The replicate table's family, arm, spacing and column for a figure-stand
 * claim, from its function and params; 0 when it has none, CS_EINPUT (as
 * *st) when the row lacks a parameter. */
static int figure_column(const claim_row *row, char *family, size_t fn, char *arm, size_t an, double *d,
                         const char **col, cs_status *st)
{
    const char *f = row->function;
    const claim_params *p = &row->param;
    *st = CS_OK;
    if (!strcmp(f, "claim_mech_ablation_k") || !strcmp(f, "claim_mech_cover") || !strcmp(f, "claim_mech_overlap")) {
        const int ablation = !strcmp(f, "claim_mech_ablation_k");
        if (ablation && (*st = claim_param_need(row, PARAM_ARM | PARAM_COLUMN))) return 1;
        snprintf(family, fn, "mechanism");
        snprintf(arm, an, "%s", ablation ? param_arm_name(p->arm) : "both_on");
        *d = 3.5;
        *col = !strcmp(f, "claim_mech_cover") ? "cover" : !strcmp(f, "claim_mech_overlap") ? "overlap_m" : p->column;
        return 1;
    }
    if (!strcmp(f, "claim_hero_stems")) {
        if ((*st = claim_param_need(row, PARAM_SPACING))) return 1;
        snprintf(family, fn, "hero");
        snprintf(arm, an, "beta_train");
        *d = p->spacing;
        *col = "stems";
        return 1;
    }
    if (!strcmp(f, "claim_pc_stand") || !strcmp(f, "claim_pc_clearance")) {
        const int clearance = !strcmp(f, "claim_pc_clearance");
        if (clearance) {
            /* the clearance is the shown stand's, of the row's arm */
            if ((*st = claim_param_need(row, PARAM_ARM))) return 1;
            *d = DESIGN_PC_SPACING_M;
        } else if ((*st = claim_param_need(row, PARAM_QUANTITY)) || (*st = claim_param_stand_spacing(row, d)))
            return 1;
        snprintf(family, fn, "pointcloud");
        snprintf(arm, an, "%s", clearance ? param_arm_name(p->arm) : "coupled");
        *col = clearance ? "k1_m" : !strcmp(p->quantity, "stems") ? "stems" : "contact_pct";
        return 1;
    }
    return 0;
}

static cs_status figure_stands(const claim_row *row, const claim_result *res, const interval_spec *sp, iv_data *d)
{
    (void)res;
    d->unit = "stand";
    d->method = "range";
    char family[32], arm[32];
    double dd;
    const char *col;
    cs_status st;
    if (!figure_column(row, family, sizeof family, arm, sizeof arm, &dd, &col, &st))
        return cs_err(CS_EINVARIANT, "interval: no replicate stands for %s", row->macro);
    if (st) return st;
    tsv *t;
    if ((st = tsv_read(sp->replicates, &t))) return st;
    if (!(st = alloc_x(d, tsv_nrows(t), 1))) {
        size_t n = 0;
        for (size_t r = 0; r < tsv_nrows(t) && !st; r++) {
            const char *fa = tsv_str(t, r, "family"), *a = tsv_str(t, r, "arm");
            double sd;
            long stand;
            if ((st = tsv_double(t, r, "spacing_m", &sd)) || (st = tsv_long(t, r, "stand", &stand))) break;
            if (!fa || !a || strcmp(fa, family) || strcmp(a, arm) || fabs(sd - dd) > 1e-9) continue;
            if (stand == 0) d->own = (int)n; /* the figure stand itself */
            st = tsv_double(t, r, col, &d->x[n++]);
        }
        d->n = n;
        if (!st && n < 2)
            st = cs_err(CS_EINPUT, "%s: %zu replicate stands of %s/%s at %.1f m", sp->replicates, n, family, arm, dd);
    }
    snprintf(d->from, sizeof d->from, "%s (%s, %s at %.1f m, %s; %zu stands)", sp->replicates, family, arm, dd, col,
             d->n);
    tsv_free(t);
    return st;
}

/* ---- dispatch ---- */

static const struct { const char *function; iv_extract ex; } extractors[] = {
    {"claim_main_median", main_seeds}, {"claim_main_range", main_seeds}, {"claim_main_rel", main_seeds},
    {"claim_main_p", main_seeds}, {"claim_main_geom_ratio", main_seeds}, {"claim_main_probe", main_seeds},
    {"claim_main_noise", main_spacings}, {"claim_main_iso", iv_blind_stands}, {"claim_main_teach_probe", main_spacings},
    {"claim_extrap_rel", extrap_seeds}, {"claim_extrap_p", extrap_seeds},
    {"claim_field_elong", interval_field_stands}, {"claim_aniso_lattice", interval_field_stands}, {"claim_aniso_lattice_counts", interval_field_stands},
    {"claim_jitter_heldout", interval_field_stands}, {"claim_aniso_rho", interval_field_stands}, {"claim_aniso_hardcore_overshoot", interval_field_stands},
    {"claim_field_calib_dieback", interval_field_stands}, {"claim_jitter_star", interval_field_stands},
    {"claim_comp_k", comp_patches}, {"claim_comp_overlap", comp_patches}, {"claim_comp_dart", comp_patches},
    {"claim_comp_no_overlap", comp_patches},
    {"claim_mech_ablation_k", figure_stands}, {"claim_mech_cover", figure_stands}, {"claim_mech_overlap", figure_stands},
    {"claim_hero_stems", figure_stands}, {"claim_pc_stand", figure_stands}, {"claim_pc_clearance", figure_stands},
    {"claim_mech_hits", iv_sweep_stands}, {"claim_irred_resp_lo", iv_perturb_stands}, {"claim_irred_resp_hi", iv_perturb_stands},
    {"claim_irred_resp_shrink", iv_refine_stands}, {"claim_irred_step_shrink", iv_refine_stands},
    {"claim_irred_steps", iv_reduction_stands}, {"claim_irred_miss", iv_reduction_stands},
};

iv_extract interval_extractor(const char *function)
{
    for (size_t i = 0; i < sizeof extractors / sizeof *extractors; i++)
        if (!strcmp(extractors[i].function, function)) return extractors[i].ex;
    return NULL;
}
