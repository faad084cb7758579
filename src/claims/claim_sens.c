/* claim_sens: the numbers of the write-up's account of what the reference
 * paper leaves unstated (design.md §7 E0 "sensitivity"; registry kind probe,
 * never gated, not in the paper): the operating-point tension (gap over
 * beta times stem distance, ours and the paper's), the growth step of the
 * reduction, spans over the sensitivity table and the die-back readings,
 * and the abrasion-off rows of the E1 sweep. Each is recomputed from the
 * frozen table its row names (the sensitivity and readings summaries are
 * themselves recomputed from their run tables by their claim tests), or,
 * for the paper's side, from the registry's reference column. */
#include "claims.h"
#include "design.h"
#include "paths.h"
#include "tsv.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The reference paper's value of a claim (registry reference column). */
static cs_status paper_value(const claims *c, const char *macro, double *v)
{
    const claim_row *r = claims_find(c, macro);
    char *end;
    if (!r) return cs_err(CS_EINPUT, "%s: no claim %s", PATHS_CLAIMS, macro);
    *v = strtod(r->reference, &end);
    if (end == r->reference)
        return cs_err(CS_EINPUT, "%s:%d: field 'reference': %s is not a number", PATHS_CLAIMS, r->line, macro);
    return CS_OK;
}

/* Clearance over beta d, ours (quantity): the lattice sweep at beta_train
 * (its lowest or highest over spacings, bound), the figure stand (both on),
 * the field held-out stands (tree-mean median over beta_field times the
 * field spacing). */
cs_status claim_sens_gap(const claim_row *row, claim_result *res)
{
    cs_status st = claim_param_need(row, PARAM_QUANTITY);
    if (st) return st;
    const char *q = row->param.quantity;
    const int lattice = !strcmp(q, "lattice"), field = !strcmp(q, "field");
    if (!lattice && !field && strcmp(q, "figure")) return claim_param_bad(row, "quantity", "lattice, figure or field");
    if (lattice && (st = claim_param_need(row, PARAM_BOUND))) return st;
    tsv *t;
    if ((st = tsv_read(row->source, &t))) return st;
    double v = NAN;
    if (lattice) {
        double bt, lo = INFINITY, hi = -INFINITY;
        st = gate_read_value(PATHS_GATE("mechanism"), "dieback_train", 0, &bt);
        for (size_t r = 0; r < tsv_nrows(t) && !st; r++) {
            double b, d, k1;
            if ((st = tsv_double(t, r, "beta", &b)) || (st = tsv_double(t, r, "spacing_m", &d)) ||
                (st = tsv_double(t, r, "k1_m", &k1)))
                break;
            if (b != bt) continue;
            double g = k1 / (b * d);
            if (g < lo) lo = g;
            if (g > hi) hi = g;
        }
        v = row->param.bound == BOUND_LO ? lo : hi;
        snprintf(res->where, sizeof res->where, "%s (k1_m / (beta d) over the beta_train rows)", row->source);
    } else {
        long r = tsv_find(t, "arm", field ? "coupled" : "both_on");
        double g, b, d = DESIGN_FIELD_SPACING_M;
        if (r < 0) st = cs_err(CS_EINPUT, "%s: field 'arm': no %s row", row->source, field ? "coupled" : "both_on");
        if (!st) st = tsv_double(t, (size_t)r, field ? "tree_mean_median" : "k1_m", &g);
        if (!st) st = tsv_double(t, (size_t)r, "beta", &b);
        if (!st && !field) st = tsv_double(t, (size_t)r, "spacing_m", &d);
        if (!st) v = g / (b * d);
        if (!st)
            snprintf(res->where, sizeof res->where, "%s:%d (%s / (beta x %g m))", row->source, tsv_line(t, (size_t)r),
                     field ? "tree_mean_median" : "k1_m", d);
    }
    tsv_free(t);
    if (st) return st;
    claim_set_value(row, res, v);
    return CS_OK;
}

/* The paper's side, from its own numbers: MechOn / (beta_train x the
 * ablation spacing); the field calibration target / (beta_field x our field
 * spacing); the field spacing at which the field calibration would give the
 * mechanism's clearance per beta d; the growth step of its reduction
 * (IrredMiss / IrredSteps). */
cs_status claim_sens_paper(const claim_row *row, claim_result *res)
{
    cs_status st = claim_param_need(row, PARAM_QUANTITY);
    if (st) return st;
    claims c;
    if ((st = claims_registry(&c))) return st;
    double on, bt, tgt, bf, miss, steps, dab;
    st = paper_value(&c, "MechOn", &on);
    if (!st) st = paper_value(&c, "CalibDiebackTrain", &bt);
    if (!st) st = paper_value(&c, "CalibTarget", &tgt);
    if (!st) st = paper_value(&c, "CalibDieback", &bf);
    if (!st) st = paper_value(&c, "IrredMiss", &miss);
    if (!st) st = paper_value(&c, "IrredSteps", &steps);
    claims_free(&c);
    if (!st) st = gate_read_value(PATHS_GATE("mechanism"), "ablation_spacing_m", 0, &dab);
    if (st) return st;
    const char *q = row->param.quantity;
    double mech = on / (bt * dab), v;
    if (!strcmp(q, "gap_mech")) v = mech;
    else if (!strcmp(q, "gap_field")) v = tgt / (bf * DESIGN_FIELD_SPACING_M);
    else if (!strcmp(q, "field_spacing")) v = tgt / (bf * mech);
    else if (!strcmp(q, "step")) v = miss / steps;
    else return claim_param_bad(row, "quantity", "gap_mech, gap_field, field_spacing or step");
    snprintf(res->where, sizeof res->where,
             "%s reference column (MechOn %g, CalibDiebackTrain %g, CalibTarget %g, CalibDieback %g, IrredMiss %g, "
             "IrredSteps %g), ablation spacing %g m, field spacing %g m",
             PATHS_CLAIMS, on, bt, tgt, bf, miss, steps, dab, DESIGN_FIELD_SPACING_M);
    claim_set_value(row, res, v);
    return CS_OK;
}

/* Our growth step of the reduction (pooled row of reduction_<tag>.tsv). */
cs_status claim_sens_step(const claim_row *row, claim_result *res)
{
    tsv *t;
    cs_status st = tsv_read(row->source, &t);
    if (st) return st;
    long r = tsv_find(t, "scope", "pooled");
    double v = NAN;
    if (r < 0) st = cs_err(CS_EINPUT, "%s: field 'scope': no pooled row", row->source);
    if (!st) st = tsv_double(t, (size_t)r, "step_m", &v);
    if (!st) snprintf(res->where, sizeof res->where, "%s:%d (step_m)", row->source, tsv_line(t, (size_t)r));
    tsv_free(t);
    if (st) return st;
    claim_set_value(row, res, v);
    return CS_OK;
}

/* Spans and single cells of a summary table (sensitivity: quantity choice x
 * value; readings: quantity reading value). */
static cs_status table_pick(const char *path, const char *q, const char *unitcol, const char *unit, double x,
                            const char *skip, double *lo, double *hi, int *n)
{
    tsv *t;
    cs_status st = tsv_read(path, &t);
    if (st) return st;
    *lo = INFINITY;
    *hi = -INFINITY;
    *n = 0;
    for (size_t r = 0; r < tsv_nrows(t) && !st; r++) {
        const char *qq = tsv_str(t, r, "quantity"), *u = tsv_str(t, r, unitcol);
        if (!qq || !u || strcmp(qq, q) || (unit && strcmp(u, unit)) || (skip && !strcmp(u, skip))) continue;
        double v, xx = NAN;
        if ((st = tsv_double_nf(t, r, "value", &v))) break;
        if (isfinite(x) && ((st = tsv_double_nf(t, r, "x", &xx)) || xx != x)) continue;
        if (v < *lo) *lo = v;
        if (v > *hi) *hi = v;
        (*n)++;
    }
    tsv_free(t);
    if (!st && !*n) st = cs_err(CS_EINPUT, "%s: no row of %s%s%s", path, q, unit ? " under " : "", unit ? unit : "");
    return st;
}

/* The lowest or highest (bound) value of the claim `of` over the rows of a
 * summary table: under one choice (or reading) at its value x when the row
 * names them, else over every unit but the die-back readings'. */
cs_status claim_sens_table(const claim_row *row, claim_result *res)
{
    cs_status st = claim_param_need(row, PARAM_OF | PARAM_BOUND);
    if (st) return st;
    const claim_params *p = &row->param;
    const char *unit = p->set & PARAM_CHOICE ? p->choice : NULL;
    int readings = strstr(row->source, "readings/") != NULL;
    double lo, hi;
    int n;
    /* spans "under every unstated choice" leave out the die-back readings' units */
    if ((st = table_pick(row->source, p->of, readings ? "reading" : "choice", unit, p->set & PARAM_X ? p->x : NAN,
                         unit ? NULL : "dieback", &lo, &hi, &n)))
        return st;
    const int high = p->bound == BOUND_HI;
    snprintf(res->where, sizeof res->where, "%s (%s of %s%s%s over %d row(s))", row->source,
             high ? "highest" : "lowest", p->of, unit ? " under " : "",
             unit ? unit : ", every unit but the die-back readings'", n);
    claim_set_value(row, res, high ? hi : lo);
    return CS_OK;
}

/* The abrasion-off rows of the E1 sweep (beta = 0): their lowest or highest k1 (bound). */
cs_status claim_sens_abroff(const claim_row *row, claim_result *res)
{
    tsv *t;
    cs_status st = claim_param_need(row, PARAM_BOUND);
    if (st || (st = tsv_read(row->source, &t))) return st;
    double lo = INFINITY, hi = -INFINITY;
    int n = 0;
    for (size_t r = 0; r < tsv_nrows(t) && !st; r++) {
        double b, k1;
        if ((st = tsv_double(t, r, "beta", &b)) || (st = tsv_double(t, r, "k1_m", &k1))) break;
        if (b != 0.0) continue;
        n++;
        if (k1 < lo) lo = k1;
        if (k1 > hi) hi = k1;
    }
    tsv_free(t);
    if (!st && !n) st = cs_err(CS_EINPUT, "%s: no beta = 0 rows", row->source);
    if (st) return st;
    snprintf(res->where, sizeof res->where, "%s (k1_m of the %d beta = 0 rows)", row->source, n);
    claim_set_value(row, res, row->param.bound == BOUND_LO ? lo : hi);
    return CS_OK;
}
