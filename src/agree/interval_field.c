/* interval_field: the stand units of the E5/E6 per-tree tables (design.md
 * §6.1). A field or anisotropy claim is a median over the coupled trees of one
 * or more levels (or a curve through them: Spearman's rho, the calibrated
 * die-back and jitter); its unit is the stand, so the bootstrap draws stands
 * and regroups their trees as fs_group does. Limit: at most 32 coupled levels. */
#include "interval_field.h"
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

typedef enum {
    FS_ELONG,
    FS_ANISO,
    FS_ANISO_TREES,
    FS_STANDS,
    FS_RHO,
    FS_OVERSHOOT,
    FS_CAL_BETA,
    FS_CAL_JITTER
} fs_kind;
typedef struct {
    fs_trees t;
    fs_kind kind;
    double level[32];  /* coupled buildable levels, file order */
    size_t nlevel;
    unsigned nstand;   /* stand ids 0..nstand-1 */
    size_t **of;       /* of[s]: tree indices of stand s, count in cnt[s] */
    size_t *cnt;
    double *an;        /* per tree: est_anisotropy, where an_ok */
    int *an_ok;
    double *buf;       /* scratch: one value per tree of a draw */
    double target, step, scale; /* the calibrations: fs_beta_field, fs_jitter_star */
} fs_ctx;

static void fs_ctx_free(void *p)
{
    fs_ctx *c = p;
    if (!c) return;
    for (unsigned s = 0; c->of && s < c->nstand; s++) free(c->of[s]);
    free(c->of);
    free(c->cnt);
    free(c->an);
    free(c->an_ok);
    free(c->buf);
    fs_trees_free(&c->t);
    free(c);
}

/* The group statistics of the drawn stands (draw b is a stand of its own):
 * the medians fs_group takes (est_median of the trees' elongation; of the
 * anisotropy of the trees est_anisotropy defines, as field_summarize), from
 * per-tree values computed once. */
static cs_status fs_level_stat(const fs_ctx *c, const double *x, size_t n, double level, double *buf, double *out)
{
    size_t m = 0, stands = 0;
    for (size_t b = 0; b < n; b++) {
        unsigned s = (unsigned)x[b];
        size_t any = 0;
        for (size_t q = 0; q < c->cnt[s]; q++) {
            size_t k = c->of[s][q];
            if (!c->t.coupled[k] || c->t.level[k] != level) continue;
            any = 1;
            if (c->kind == FS_ELONG) buf[m++] = c->t.elong[k];
            else if (c->kind == FS_CAL_BETA)
                buf[m++] = est_tree_mean(c->t.gap[k]); /* tree_mean_median, as field_summarize */
            else if (c->an_ok[k]) buf[m++] = c->an[k];
        }
        stands += any;
    }
    if (c->kind == FS_STANDS) { *out = (double)stands; return CS_OK; }
    if (c->kind == FS_ANISO_TREES) { *out = (double)m; return CS_OK; }
    if (m == 0) { *out = NAN; return CS_OK; }
    return est_median(buf, m, out);
}

static cs_status fs_stat(const double *x, size_t n, size_t m, const void *ctx, double *out)
{
    (void)m;
    const fs_ctx *c = ctx;
    double an[32];
    cs_status st = CS_OK;
    size_t nl =
        c->kind == FS_ELONG || c->kind == FS_ANISO || c->kind == FS_ANISO_TREES || c->kind == FS_STANDS ? 1 : c->nlevel;
    for (size_t l = 0; l < nl && !st; l++) st = fs_level_stat(c, x, n, c->level[l], c->buf, &an[l]);
    if (st) return st;
    if (c->kind == FS_CAL_BETA || c->kind == FS_CAL_JITTER) {
        /* the calibrated grid value: the curve interpolated to the target, rounded to the step */
        double interp;
        int bracketed;
        if ((st = fs_interp_target(c->level, an, c->nlevel, c->target, &interp, &bracketed))) return st;
        *out = c->scale * fs_round_step(interp, c->step);
        return CS_OK;
    }
    if (c->kind == FS_RHO) return stats_spearman(c->level, an, c->nlevel, out);
    if (c->kind == FS_OVERSHOOT) {
        size_t k = 0;
        for (size_t l = 1; l < c->nlevel; l++) if (c->level[l] > c->level[k]) k = l;
        *out = an[k];
        return CS_OK;
    }
    *out = an[0];
    return CS_OK;
}

/* Coupled levels with trees, in the order of the summary table. */
static cs_status fs_levels(const char *summary, fs_ctx *c, int first_only)
{
    tsv *t;
    cs_status st = tsv_read(summary, &t);
    if (st) return st;
    for (size_t r = 0; r < tsv_nrows(t) && !st; r++) {
        const char *arm = tsv_col(t, "arm") >= 0 ? tsv_str(t, r, "arm") : "coupled";
        long trees;
        double lv;
        if (!arm || strcmp(arm, "coupled")) continue;
        if ((st = tsv_long(t, r, tsv_col(t, "trees") >= 0 ? "trees" : "aniso_trees", &trees)) ||
            (st = tsv_double(t, r, "level", &lv)))
            break;
        if (trees == 0) continue;
        if (c->nlevel == 32) { st = cs_err(CS_EINPUT, "%s: more than 32 levels", summary); break; }
        c->level[c->nlevel++] = lv;
        if (first_only) break;
    }
    tsv_free(t);
    return st;
}

cs_status interval_field_stands(const claim_row *row, const claim_result *res, const interval_spec *sp, iv_data *d)
{
    (void)res; (void)sp;
    fs_ctx *c = calloc(1, sizeof *c);
    if (!c) return cs_err(CS_ENOMEM, "interval: out of memory");
    d->stat = (iv_stat){IV_CALLBACK, 0, 0, fs_stat, c};
    d->cleanup = fs_ctx_free;
    const char *f = row->function;
    cs_status st = CS_OK;
    c->kind = !strcmp(f, "claim_aniso_rho") ? FS_RHO : !strcmp(f, "claim_aniso_hardcore_overshoot") ? FS_OVERSHOOT
            : !strcmp(f, "claim_field_calib_dieback") ? FS_CAL_BETA : !strcmp(f, "claim_jitter_star") ? FS_CAL_JITTER
            : !strcmp(f, "claim_field_elong") ? FS_ELONG : FS_ANISO;
    /* the count and held-out functions read the column their row names */
    if (!strcmp(f, "claim_aniso_lattice_counts") || !strcmp(f, "claim_jitter_heldout")) {
        if ((st = claim_param_need(row, PARAM_COLUMN))) return st;
        const char *col = row->param.column;
        c->kind = !strcmp(col, "elong_median")  ? FS_ELONG
                  : !strcmp(col, "stands")      ? FS_STANDS
                  : !strcmp(col, "aniso_trees") ? FS_ANISO_TREES
                                                : FS_ANISO;
    }
    char tp[512];
    c->scale = 1.0;
    if (c->kind == FS_CAL_JITTER) {
        /* a* is calibrated on the sweep beside it (anisotropy/jitter.tsv and its trees) */
        const char *slash = strrchr(row->source, '/');
        snprintf(tp, sizeof tp, "%.*sjitter_trees.tsv", slash ? (int)(slash - row->source + 1) : 0, row->source);
        c->step = FS_JITTER_STEP;
        if (row->param.set & PARAM_SCALE) c->scale = row->param.scale;
        st = gate_read_value(PATHS_GATE("anisotropy"), "field_median", 0, &c->target);
    } else {
        fs_trees_path(row->source, tp, sizeof tp);
        if (c->kind == FS_CAL_BETA &&
            !(st = gate_read_value(PATHS_GATE("field"), "calibration_target_m", 0, &c->target)))
            st = gate_read_value(PATHS_GATE("field"), "dieback_grid", 2, &c->step);
    }
    int all_levels = c->kind == FS_RHO || c->kind == FS_OVERSHOOT || c->kind == FS_CAL_BETA || c->kind == FS_CAL_JITTER;
    if (!st) st = fs_levels(row->source, c, !all_levels);
    if (!st) st = fs_trees_read(tp, &c->t);
    for (size_t k = 0; k < c->t.n && !st; k++) if (c->t.stand[k] + 1 > c->nstand) c->nstand = c->t.stand[k] + 1;
    if (!st && (c->nstand == 0 || c->nlevel == 0))
        st = cs_err(CS_EINPUT, "%s: no stands or no buildable coupled level", tp);
    if (!st) {
        c->of = calloc(c->nstand, sizeof *c->of);
        c->cnt = calloc(c->nstand, sizeof *c->cnt);
        if (!c->of || !c->cnt) st = cs_err(CS_ENOMEM, "interval: out of memory");
    }
    for (unsigned s = 0; s < c->nstand && !st; s++) {
        c->of[s] = malloc((c->t.n ? c->t.n : 1) * sizeof **c->of);
        if (!c->of[s]) { st = cs_err(CS_ENOMEM, "interval: out of memory"); break; }
        for (size_t k = 0; k < c->t.n; k++) if (c->t.stand[k] == s) c->of[s][c->cnt[s]++] = k;
    }
    if (!st) {
        size_t nt = c->t.n ? c->t.n : 1, maxs = 0;
        for (unsigned s = 0; s < c->nstand; s++) if (c->cnt[s] > maxs) maxs = c->cnt[s];
        c->an = malloc(nt * sizeof *c->an);
        c->an_ok = malloc(nt * sizeof *c->an_ok);
        c->buf = malloc((c->nstand * maxs > 0 ? c->nstand * maxs : 1) * sizeof *c->buf);
        if (!c->an || !c->an_ok || !c->buf) st = cs_err(CS_ENOMEM, "interval: out of memory");
        for (size_t k = 0; k < c->t.n && !st; k++) c->an_ok[k] = est_anisotropy(c->t.gap[k], &c->an[k]);
    }
    if (!st && !(d->x = calloc(c->nstand, sizeof *d->x))) st = cs_err(CS_ENOMEM, "interval: out of memory");
    d->n = c->nstand;
    d->m = 1;
    for (unsigned s = 0; s < c->nstand && !st; s++) d->x[s] = s;
    d->unit = "stand";
    d->method = "bootstrap";
    snprintf(d->from, sizeof d->from, "%s (%u stands)", tp, c->nstand);
    return st;
}
