/* claim_teacher: computing functions for the teacher claims — E1 mechanism
 * (paper §3.2; gates/mechanism.gate), E2 irreducibility (§3.3;
 * gates/irreducibility.gate), the hero figure (E9) and the point-cloud figure
 * (E8) — from the frozen tables written by src/exp/exp_mechanism.c,
 * exp_irreducibility.c and exp_stands.c. Row verdicts are recomputed from the
 * clearances and the gate thresholds, never read from a stored pass column. */
#include "claims.h"
#include "paths.h"
#include "stats.h"
#include "tsv.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Row of `t` whose text column `col` equals `val`; error naming the file otherwise. */
static cs_status find_row(const tsv *t, const char *col, const char *val, size_t *row)
{
    long r = tsv_find(t, col, val);
    if (r < 0) return cs_err(CS_EINPUT, "%s: no row with %s = %s", tsv_path(t), col, val);
    *row = (size_t)r;
    return CS_OK;
}

static void where_row(claim_result *res, const tsv *t, size_t row, const char *col)
{
    snprintf(res->where, sizeof res->where, "%s:%d (%s)", tsv_path(t), tsv_line(t, row), col);
}

/* ---- E1 mechanism ---- */

/* The Mech* macros are "measured on the stand shown" (paper Fig. mechanism
 * caption; design.md §7 E1): the row's source is the figure stand's
 * mechanism/figure_stats.tsv. The gate stays judged on the lattice ablation,
 * mechanism/ablation.tsv in the same folder; both values appear in the
 * verify line. A source named ablation.tsv (the lattice reading) is value and gate. */
static void lattice_path(const char *source, char *out, size_t n)
{
    const char *slash = strrchr(source, '/');
    snprintf(out, n, "%.*sablation.tsv", slash ? (int)(slash - source + 1) : 0, source);
}

/* Value of column col in the arm's row of path (where receives file:line). */
static cs_status arm_value(const char *path, const char *arm, const char *col, double *v, char *where, size_t wn)
{
    tsv *t;
    cs_status st = tsv_read(path, &t);
    if (st) return st;
    size_t r = 0;
    if (!(st = find_row(t, "arm", arm, &r)) && !(st = tsv_double(t, r, col, v)) && where)
        snprintf(where, wn, "%s:%d (%s)", tsv_path(t), tsv_line(t, r), col);
    tsv_free(t);
    return st;
}

/* Value from the row's source (figure stand), gate on the lattice. */
static cs_status mech_figure_and_lattice(const claim_row *row, claim_result *res, const char *arm, const char *col,
                                         gate_op op)
{
    double v, lv;
    char w1[200], w2[200], lp[300];
    cs_status st = arm_value(row->source, arm, col, &v, w1, sizeof w1);
    if (st) return st;
    claim_set_value(row, res, v);
    lattice_path(row->source, lp, sizeof lp);
    int figure = strcmp(lp, row->source) != 0;
    /* the lattice table is read to judge the gate; a row without a gate (and
     * the readings' and sensitivity's rows) needs only the figure stand */
    if (!figure || !strcmp(row->gate, "-")) {
        snprintf(res->where, sizeof res->where, "%s", w1);
        if (strcmp(row->gate, "-")) claim_judge(row, res, op, v);
        return CS_OK;
    }
    if ((st = arm_value(lp, arm, col, &lv, w2, sizeof w2))) return st;
    snprintf(res->where, sizeof res->where, "figure stand %s = %.4g; lattice %s = %.4g", w1, v, w2, lv);
    if (strcmp(row->gate, "-")) {
        claim_judge(row, res, op, lv);
        size_t l = strlen(res->gate_detail);
        snprintf(res->gate_detail + l, sizeof res->gate_detail - l, " (judged on the lattice; figure stand %.4g)", v);
    }
    return CS_OK;
}

/* The clearance k1, k2 or k3 (column) of an ablation arm: with the coupling
 * or the abrasion off the gate bounds it from above, with both on from below. */
cs_status claim_mech_ablation_k(const claim_row *row, claim_result *res)
{
    cs_status st = claim_param_need(row, PARAM_ARM | PARAM_COLUMN);
    if (st) return st;
    const param_arm a = row->param.arm;
    const char *col = row->param.column;
    if (a != ARM_BOTH_ON && a != ARM_COUPLING_OFF && a != ARM_ABRASION_OFF)
        return claim_param_bad(row, "arm", "both_on, coupling_off or abrasion_off");
    if (strcmp(col, "k1_m") && strcmp(col, "k2_m") && strcmp(col, "k3_m"))
        return claim_param_bad(row, "column", "k1_m, k2_m or k3_m");
    return mech_figure_and_lattice(row, res, param_arm_name(a), col, a == ARM_BOTH_ON ? GATE_GE : GATE_LT);
}

cs_status claim_mech_cover(const claim_row *row, claim_result *res)
{
    return mech_figure_and_lattice(row, res, "both_on", "cover", GATE_GE);
}

/* Worst self-check overlap over every coupled growth of E1 (sweep and ablation). */
cs_status claim_mech_overlap(const claim_row *row, claim_result *res)
{
    double worst = 0.0;
    tsv *t;
    cs_status st = tsv_read(row->source, &t);
    if (st) return st;
    for (size_t r = 0; r < tsv_nrows(t) && !st; r++) {
        long coupled;
        double o;
        if ((st = tsv_long(t, r, "coupled", &coupled)) || (st = tsv_double(t, r, "overlap_m", &o))) break;
        if (coupled && o > worst) worst = o;
    }
    tsv_free(t);
    if (st) return st;
    char lp[300];
    lattice_path(row->source, lp, sizeof lp);
    if (strcmp(lp, row->source)) {
        if ((st = tsv_read(lp, &t))) return st;
        for (size_t r = 0; r < tsv_nrows(t) && !st; r++) {
            long coupled;
            double o;
            if ((st = tsv_long(t, r, "coupled", &coupled)) || (st = tsv_double(t, r, "overlap_m", &o))) break;
            if (coupled && o > worst) worst = o;
        }
        tsv_free(t);
        if (st) return st;
    }
    const char *sweep = "frozen/mechanism/sweep.tsv";
    if ((st = tsv_read(sweep, &t))) return st;
    for (size_t r = 0; r < tsv_nrows(t) && !st; r++) {
        double o;
        if ((st = tsv_double(t, r, "worst_overlap_m", &o))) break;
        if (o > worst) worst = o;
    }
    tsv_free(t);
    if (st) return st;
    snprintf(res->where, sizeof res->where,
             "%s (coupled arms; figure stand and lattice ablation) and %s (worst_overlap_m)", row->source, sweep);
    claim_set_value(row, res, worst);
    claim_judge(row, res, GATE_LE, worst);
    return CS_OK;
}

/* A sweep row passes when k1, k2, k3 and cover clear the gate's bars. */
static cs_status sweep_row_pass(const tsv *t, size_t r, int *pass)
{
    double k[3], cover, kmin[3], cmin;
    const char *kc[3] = {"k1_m", "k2_m", "k3_m"},
               *gk[3] = {"clearance_k1_min_m", "clearance_k2_min_m", "clearance_k3_min_m"};
    cs_status st = CS_OK;
    for (int i = 0; i < 3 && !st; i++) {
        st = tsv_double(t, r, kc[i], &k[i]);
        if (!st) st = gate_read_value(PATHS_GATE("mechanism"), gk[i], 0, &kmin[i]);
    }
    if (!st) st = tsv_double(t, r, "cover", &cover);
    if (!st) st = gate_read_value(PATHS_GATE("mechanism"), "cover_min", 0, &cmin);
    if (st) return st;
    *pass = k[0] >= kmin[0] && k[1] >= kmin[1] && k[2] >= kmin[2] && cover >= cmin;
    return CS_OK;
}

cs_status claim_mech_hits(const claim_row *row, claim_result *res)
{
    tsv *t;
    cs_status st = tsv_read(row->source, &t);
    if (st) return st;
    int hits = 0;
    for (size_t r = 0; r < tsv_nrows(t) && !st; r++) {
        int p;
        if (!(st = sweep_row_pass(t, r, &p))) hits += p;
    }
    snprintf(res->where, sizeof res->where, "%s (%zu rows, verdicts recomputed from gates/mechanism.gate)", row->source,
             tsv_nrows(t));
    tsv_free(t);
    if (st) return st;
    claim_set_value(row, res, hits);
    return CS_OK;
}

/* The preregistered training operating point passes at every spacing. */
cs_status claim_mech_train_row(const claim_row *row, claim_result *res, double beta)
{
    const char *sweep = "frozen/mechanism/sweep.tsv";
    tsv *t;
    cs_status st = tsv_read(sweep, &t);
    if (st) return st;
    int rows = 0, passed = 0;
    for (size_t r = 0; r < tsv_nrows(t) && !st; r++) {
        double b;
        int p;
        if ((st = tsv_double(t, r, "beta", &b))) break;
        if (fabs(b - beta) > 1e-9) continue;
        if ((st = sweep_row_pass(t, r, &p))) break;
        rows++;
        passed += p;
    }
    tsv_free(t);
    if (st) return st;
    size_t nsp = 0;
    gate *g;
    if (!(st = claim_gate_load("mechanism.gate", &g))) { nsp = gate_count(g, "spacings_m"); gate_free(g); }
    if (st) return st;
    res->gate = rows == (int)nsp && passed == rows ? VERDICT_PASS : VERDICT_FAIL;
    snprintf(res->gate_detail, sizeof res->gate_detail, "beta %.2f row passes at %d of %d spacings (%s)", beta, passed,
             (int)nsp, sweep);
    (void)row;
    return CS_OK;
}

/* ---- E2 irreducibility ---- */

cs_status claim_irred_resp_lo(const claim_row *row, claim_result *res)
{
    tsv *t;
    cs_status st = tsv_read(row->source, &t);
    if (st) return st;
    double lo = INFINITY;
    size_t n = tsv_nrows(t);
    for (size_t r = 0; r < n && !st; r++) {
        double f;
        if (!(st = tsv_double(t, r, "response_fraction", &f)) && f < lo) lo = f;
    }
    size_t want = 0;
    gate *g;
    if (!st && !(st = claim_gate_load("irreducibility.gate", &g))) { want = gate_count(g, "spacings_m"); gate_free(g); }
    if (!st && n != want)
        st = cs_err(CS_EINPUT, "%s: %zu spacings, gates/irreducibility.gate lists %zu", row->source, n, want);
    snprintf(res->where, sizeof res->where, "%s (min response_fraction over %zu spacings)", row->source, n);
    tsv_free(t);
    if (st) return st;
    claim_set_value(row, res, 100.0 * lo);
    claim_judge(row, res, GATE_GE, lo);
    return CS_OK;
}

cs_status claim_irred_resp_hi(const claim_row *row, claim_result *res)
{
    tsv *t;
    cs_status st = tsv_read(row->source, &t);
    if (st) return st;
    double hi = -INFINITY;
    for (size_t r = 0; r < tsv_nrows(t) && !st; r++) {
        double f;
        if (!(st = tsv_double(t, r, "response_fraction", &f)) && f > hi) hi = f;
    }
    snprintf(res->where, sizeof res->where, "%s (max response_fraction)", row->source);
    tsv_free(t);
    if (st) return st;
    claim_set_value(row, res, 100.0 * hi);
    return CS_OK;
}

/* Pooled row at the finest refinement level. */
static cs_status refine_finest(const char *path, size_t *row, tsv **out)
{
    tsv *t;
    cs_status st = tsv_read(path, &t);
    if (st) return st;
    double levels_hi;
    size_t nl = 0;
    gate *g;
    if ((st = claim_gate_load("irreducibility.gate", &g))) { tsv_free(t); return st; }
    nl = gate_count(g, "refine_levels");
    st = gate_value(g, "refine_levels", nl - 1, &levels_hi);
    gate_free(g);
    long found = -1;
    for (size_t r = 0; r < tsv_nrows(t) && !st && found < 0; r++) {
        const char *scope = tsv_str(t, r, "scope");
        double nres;
        if ((st = tsv_double(t, r, "nres", &nres))) break;
        if (scope && !strcmp(scope, "pooled") && nres == levels_hi) found = (long)r;
    }
    if (!st && found < 0) st = cs_err(CS_EINPUT, "%s: no pooled row at N = %g", path, levels_hi);
    if (st) { tsv_free(t); return st; }
    *row = (size_t)found;
    *out = t;
    return CS_OK;
}

/* Column `col` of the pooled row at the finest refinement level; judge != 0
 * judges the row's gate on it (at or above the threshold). */
static cs_status refine_pooled(const claim_row *row, claim_result *res, const char *col, int judge)
{
    tsv *t;
    size_t r = 0;
    cs_status st = refine_finest(row->source, &r, &t);
    if (st) return st;
    double v;
    if (!(st = tsv_double(t, r, col, &v))) {
        where_row(res, t, r, col);
        claim_set_value(row, res, v);
        if (judge) claim_judge(row, res, GATE_GE, v);
    }
    tsv_free(t);
    return st;
}

cs_status claim_irred_resp_shrink(const claim_row *row, claim_result *res)
{
    return refine_pooled(row, res, "magnitude_ratio", 1);
}
cs_status claim_irred_step_shrink(const claim_row *row, claim_result *res)
{
    return refine_pooled(row, res, "step_ratio", 0);
}

static cs_status reduction_pooled(const claim_row *row, claim_result *res, const char *col, int judge)
{
    tsv *t;
    cs_status st = tsv_read(row->source, &t);
    if (st) return st;
    size_t r = 0;
    double v;
    if (!(st = find_row(t, "scope", "pooled", &r)) && !(st = tsv_double(t, r, col, &v))) {
        where_row(res, t, r, col);
        claim_set_value(row, res, v);
        if (judge) claim_judge(row, res, GATE_GE, v);
    }
    tsv_free(t);
    return st;
}

cs_status claim_irred_steps(const claim_row *row, claim_result *res)
{
    return reduction_pooled(row, res, "miss_steps", 1);
}
cs_status claim_irred_miss(const claim_row *row, claim_result *res) { return reduction_pooled(row, res, "miss_m", 0); }

/* ---- figures: hero (E9) and point cloud (E8) ---- */

/* Stems drawn in one panel of a figure-crowns table. */
static cs_status panel_stems(const char *path, const char *panel, double d, double *n, claim_result *res)
{
    tsv *t;
    cs_status st = tsv_read(path, &t);
    if (st) return st;
    long cnt = 0;
    for (size_t r = 0; r < tsv_nrows(t) && !st; r++) {
        double dd;
        const char *p = tsv_str(t, r, "panel");
        if ((st = tsv_double(t, r, "spacing_m", &dd))) break;
        if (p && !strcmp(p, panel) && fabs(dd - d) < 1e-9) cnt++;
    }
    snprintf(res->where, sizeof res->where, "%s (rows of panel %s at %.1f m)", path, panel, d);
    tsv_free(t);
    if (!st && cnt == 0) st = cs_err(CS_EINPUT, "%s: no stems in panel %s at %.1f m", path, panel, d);
    *n = (double)cnt;
    return st;
}

/* Stems of the hero figure's beta_train panel at the row's spacing. */
cs_status claim_hero_stems(const claim_row *row, claim_result *res)
{
    double n;
    cs_status st = claim_param_need(row, PARAM_SPACING);
    if (!st) st = panel_stems(row->source, "beta_train", row->param.spacing, &n, res);
    if (st) return st;
    claim_set_value(row, res, n);
    return CS_OK;
}

/* A point-cloud stand (stand), quantity: its stems drawn in the coupled
 * panel, or its contact fraction (percent). */
cs_status claim_pc_stand(const claim_row *row, claim_result *res)
{
    double d;
    cs_status st = claim_param_need(row, PARAM_QUANTITY);
    if (!st) st = claim_param_stand_spacing(row, &d);
    if (st) return st;
    const int stems = !strcmp(row->param.quantity, "stems");
    if (!stems && strcmp(row->param.quantity, "contact")) return claim_param_bad(row, "quantity", "stems or contact");
    if (stems) {
        double n;
        if ((st = panel_stems(row->source, "coupled", d, &n, res))) return st;
        claim_set_value(row, res, n);
        return CS_OK;
    }
    tsv *t;
    if ((st = tsv_read(row->source, &t))) return st;
    char ds[16];
    snprintf(ds, sizeof ds, "%g", d);
    size_t r = 0;
    double v;
    if (!(st = find_row(t, "spacing_m", ds, &r)) && !(st = tsv_double(t, r, "contact_fraction", &v))) {
        where_row(res, t, r, "contact_fraction");
        claim_set_value(row, res, 100.0 * v);
    }
    tsv_free(t);
    return st;
}

/* k1 of the shown stand's coupled or uncoupled growth (arm). */
cs_status claim_pc_clearance(const claim_row *row, claim_result *res)
{
    tsv *t;
    cs_status st = claim_param_need(row, PARAM_ARM);
    if (st) return st;
    if (row->param.arm != ARM_COUPLED && row->param.arm != ARM_UNCOUPLED)
        return claim_param_bad(row, "arm", "coupled or uncoupled");
    char col[32];
    snprintf(col, sizeof col, "k1_%s_m", param_arm_name(row->param.arm));
    if ((st = tsv_read(row->source, &t))) return st;
    size_t r = 0;
    double v;
    if (!(st = find_row(t, "spacing_m", "3", &r)) && !(st = tsv_double(t, r, col, &v))) {
        where_row(res, t, r, col);
        claim_set_value(row, res, v);
    }
    tsv_free(t);
    return st;
}
