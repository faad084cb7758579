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
    if (end == r->reference) return cs_err(CS_EINPUT, "%s:%d: field 'reference': %s is not a number", PATHS_CLAIMS, r->line, macro);
    return CS_OK;
}

/* Clearance over beta d, ours: the lattice sweep at beta_train (Lo/Hi over
 * spacings), the figure stand (both on), the field held-out stands
 * (tree-mean median over beta_field times the field spacing). */
cs_status claim_sens_gap(const claim_row *row, claim_result *res)
{
    tsv *t;
    cs_status st = tsv_read(row->source, &t);
    if (st) return st;
    double v = NAN;
    const char *m = row->macro;
    if (!strncmp(m, "SensGapLattice", 14)) {
        double bt, lo = INFINITY, hi = -INFINITY;
        st = gate_read_value(PATHS_GATE("mechanism"), "dieback_train", 0, &bt);
        for (size_t r = 0; r < tsv_nrows(t) && !st; r++) {
            double b, d, k1;
            if ((st = tsv_double(t, r, "beta", &b)) || (st = tsv_double(t, r, "spacing_m", &d)) || (st = tsv_double(t, r, "k1_m", &k1))) break;
            if (b != bt) continue;
            double g = k1 / (b * d);
            if (g < lo) lo = g;
            if (g > hi) hi = g;
        }
        v = strstr(m, "Lo") ? lo : hi;
        snprintf(res->where, sizeof res->where, "%s (k1_m / (beta d) over the beta_train rows)", row->source);
    } else {
        int field = !strcmp(m, "SensGapField");
        long r = tsv_find(t, "arm", field ? "coupled" : "both_on");
        double g, b, d = DESIGN_FIELD_SPACING_M;
        if (r < 0) st = cs_err(CS_EINPUT, "%s: field 'arm': no %s row", row->source, field ? "coupled" : "both_on");
        if (!st) st = tsv_double(t, (size_t)r, field ? "tree_mean_median" : "k1_m", &g);
        if (!st) st = tsv_double(t, (size_t)r, "beta", &b);
        if (!st && !field) st = tsv_double(t, (size_t)r, "spacing_m", &d);
        if (!st) v = g / (b * d);
        if (!st) snprintf(res->where, sizeof res->where, "%s:%d (%s / (beta x %g m))", row->source, tsv_line(t, (size_t)r),
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
    claims c;
    cs_status st = claims_load(PATHS_CLAIMS, &c);
    if (st) return st;
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
    const char *m = row->macro;
    double mech = on / (bt * dab), v;
    if (!strcmp(m, "SensGapPaperMech")) v = mech;
    else if (!strcmp(m, "SensGapPaperField")) v = tgt / (bf * DESIGN_FIELD_SPACING_M);
    else if (!strcmp(m, "SensPaperFieldSpacing")) v = tgt / (bf * mech);
    else if (!strcmp(m, "SensStepPaper")) v = miss / steps;
    else return cs_err(CS_EINPUT, "claim_sens_paper: no quantity %s", m);
    snprintf(res->where, sizeof res->where, "%s reference column (MechOn %g, CalibDiebackTrain %g, CalibTarget %g, CalibDieback %g, IrredMiss %g, IrredSteps %g), ablation spacing %g m, field spacing %g m",
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

cs_status claim_sens_table(const claim_row *row, claim_result *res)
{
    static const struct { const char *macro, *q, *unit; double x; int hi; } map[] = {
        {"SensMechOnLo", "MechOn", NULL, NAN, 0}, {"SensMechOnHi", "MechOn", NULL, NAN, 1},
        {"SensStepsHeight", "IrredSteps", "height_sd", 6.0, 1}, {"SensStepsMax", "IrredSteps", NULL, NAN, 1},
        {"SensRespShrinkLo", "IrredRespShrink", NULL, NAN, 0}, {"SensRespShrinkHi", "IrredRespShrink", NULL, NAN, 1},
        {"SensIsoLo", "MainIso", NULL, NAN, 0}, {"SensIsoHi", "MainIso", NULL, NAN, 1},
        {"SensCoupOffSmall", "MechCoupOff", "crown_R", 3.0, 1}, {"SensCoupOffSmallKTwo", "MechCoupOffKTwo", "crown_R", 3.0, 1},
        {"SensCoupOffSmallKThree", "MechCoupOffKThree", "crown_R", 3.0, 1},
        {"SensArcMechOn", "MechOn", "arc", NAN, 1}, {"SensArcCalibDieback", "CalibDieback", "arc", NAN, 1},
        {"SensTargetMechOn", "MechOn", "dieback", 2.0, 1},
    };
    for (size_t i = 0; i < sizeof map / sizeof *map; i++) {
        if (strcmp(map[i].macro, row->macro)) continue;
        int readings = strstr(row->source, "readings/") != NULL;
        double lo, hi;
        int n;
        /* spans "under every unstated choice" leave out the die-back readings' units */
        cs_status st = table_pick(row->source, map[i].q, readings ? "reading" : "choice", map[i].unit, map[i].x,
                                  map[i].unit ? NULL : "dieback", &lo, &hi, &n);
        if (st) return st;
        snprintf(res->where, sizeof res->where, "%s (%s of %s%s%s over %d row(s))", row->source, map[i].hi ? "highest" : "lowest",
                 map[i].q, map[i].unit ? " under " : "", map[i].unit ? map[i].unit : ", every unit but the die-back readings'", n);
        claim_set_value(row, res, map[i].hi ? hi : lo);
        return CS_OK;
    }
    return cs_err(CS_EINPUT, "claim_sens_table: no quantity %s", row->macro);
}

/* The abrasion-off rows of the E1 sweep (beta = 0): lowest and highest k1. */
cs_status claim_sens_abroff(const claim_row *row, claim_result *res)
{
    tsv *t;
    cs_status st = tsv_read(row->source, &t);
    if (st) return st;
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
    claim_set_value(row, res, strstr(row->macro, "Lo") ? lo : hi);
    return CS_OK;
}
