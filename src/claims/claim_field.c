/* claim_field: computing functions for the E5 claims (reference paper §5.3;
 * design.md §7 E5 and "Field reference data"). Each reads its frozen table (a
 * summary is first checked against its per-tree table, fs_load_checked) and
 * recomputes the value with the library code the experiment used.
 * Field figures (FieldTrees, ElongLo, ...) come from frozen/field/reference.tsv
 * and are cross-checked against the preregistered gate files where both hold
 * them. The spread ratios need the raw field table: without FIELD_TABLE they
 * are PENDING with the reason, never a number. */
#include "claims.h"
#include "field.h"
#include "fieldsim.h"
#include "tsv.h"
#include <math.h>
#include <stdio.h>
#include <string.h>

/* The gate value a reference quantity must equal (file, key, index) when a
 * gate also states it; the quantity itself is the row's `quantity` param. */
static const struct { const char *quantity, *gate_file, *gate_key; int idx; } field_gated[] = {
    {"elong_band_lo", "field.gate", "elongation_band", 0},
    {"elong_band_hi", "field.gate", "elongation_band", 1},
    {"aniso_band_lo", "anisotropy.gate", "field_band", 0},
    {"aniso_band_hi", "anisotropy.gate", "field_band", 1},
    {"aniso_median", "anisotropy.gate", "field_median", 0},
};

cs_status claim_field_reference(const claim_row *row, claim_result *res)
{
    cs_status st = claim_param_need(row, PARAM_QUANTITY);
    if (st) return st;
    const char *quantity = row->param.quantity;
    double v;
    int line = 0;
    if ((st = field_reference_get(row->source, quantity, &v, &line))) return st;
    for (size_t i = 0; i < sizeof field_gated / sizeof field_gated[0]; i++) {
        if (strcmp(field_gated[i].quantity, quantity)) continue;
        gate *g;
        double gv;
        if ((st = claim_gate_load(field_gated[i].gate_file, &g))) return st;
        st = gate_value(g, field_gated[i].gate_key, (size_t)field_gated[i].idx, &gv);
        gate_free(g);
        if (st) return st;
        if (gv != v)
            return cs_err(CS_EINPUT, "%s:%d: field 'value': %s = %.17g but gates/%s %s states %.17g", row->source,
                          line, quantity, v, field_gated[i].gate_file, field_gated[i].gate_key, gv);
    }
    snprintf(res->where, sizeof res->where, "%s:%d (%s; published figure, not measured here)", row->source, line,
             quantity);
    claim_set_value(row, res, v);
    return CS_OK;
}

cs_status claim_field_calib_dieback(const claim_row *row, claim_result *res)
{
    fs_calibration c;
    cs_status st = fs_beta_field(row->source, &c);
    if (st) return st;
    snprintf(res->where, sizeof res->where, "%s:%d (interpolated %.4f%s)", row->source, c.line_lo, c.interp,
             c.bracketed ? "" : "; TARGET NOT BRACKETED by the grid");
    claim_set_value(row, res, c.value);
    return CS_OK;
}

/* The held-out summary row of one arm; *line gets its file line. */
static cs_status heldout_row(const char *path, int coupled, double *spread, double *elong, int *line)
{
    tsv *t;
    fs_trees tr;
    cs_status st = fs_load_checked(path, &t, &tr);
    if (st) return st;
    fs_trees_free(&tr);
    long r = tsv_find(t, "arm", coupled ? "coupled" : "uncoupled");
    if (r < 0) st = cs_err(CS_EINPUT, "%s: field 'arm': no %s row", path, coupled ? "coupled" : "uncoupled");
    if (!st && spread) st = tsv_double(t, (size_t)r, "spread", spread);
    if (!st && elong) st = tsv_double(t, (size_t)r, "elong_median", elong);
    if (!st) *line = tsv_line(t, (size_t)r);
    tsv_free(t);
    return st;
}

cs_status claim_field_elong(const claim_row *row, claim_result *res)
{
    double e;
    int line;
    cs_status st = heldout_row(row->source, 1, NULL, &e, &line);
    if (st) return st;
    snprintf(res->where, sizeof res->where, "%s:%d (elong_median, coupled)", row->source, line);
    claim_set_value(row, res, e);
    claim_judge(row, res, GATE_IN, e);
    return CS_OK;
}

static cs_status spread_pending_or_ratio(const claim_row *row, claim_result *res, double sim, int line,
                                         const char *what, double *ratio)
{
    const char *path = field_table_env();
    if (!path) {
        claim_pending(res, "needs the raw field table: set %s=path (TSV columns tree, direction, clearance_m; "
                           "Markham & Fernandez Otarola 2020, Dryad doi:10.5061/dryad.34tmpg4hk), not on this machine; "
                           "simulated %s spread = %.4f m (%s:%d)", FIELD_TABLE_ENV, what, sim, row->source, line);
        return CS_OK;
    }
    field_table ft;
    field_summary fs;
    cs_status st = field_table_load(path, &ft);
    if (st) return st;
    st = field_summarize((const double (*)[4])ft.gap, ft.n, &fs);
    field_table_free(&ft);
    if (st) return st;
    if (!(fs.spread > 0)) return cs_err(CS_EINPUT, "%s: field spread is %.17g (need > 0 for a ratio)", path, fs.spread);
    *ratio = sim / fs.spread;
    snprintf(res->where, sizeof res->where, "%s:%d (%s spread %.4f m) / %s (field spread %.4f m, %zu trees)",
             row->source, line, what, sim, path, fs.spread, fs.trees);
    return CS_OK;
}

/* SpreadRatio, JitterSpread: simulated coupled spread / field spread, gate IN band. */
cs_status claim_field_spread_ratio(const claim_row *row, claim_result *res)
{
    double sim, ratio = NAN;
    int line;
    cs_status st = heldout_row(row->source, 1, &sim, NULL, &line);
    if (st) return st;
    if ((st = spread_pending_or_ratio(row, res, sim, line, "held-out coupled", &ratio))) return st;
    if (res->status == VERDICT_PENDING) return CS_OK;
    claim_set_value(row, res, ratio);
    claim_judge(row, res, GATE_IN, ratio);
    return CS_OK;
}

/* ControlSpread: uncoupled twin spread / field spread; the preregistered gate
 * (control_spread_outside_band 1) says it must fall outside spread_ratio_band. */
cs_status claim_field_control_spread(const claim_row *row, claim_result *res)
{
    double sim, ratio = NAN;
    int line;
    cs_status st = heldout_row(row->source, 0, &sim, NULL, &line);
    if (st) return st;
    if ((st = spread_pending_or_ratio(row, res, sim, line, "uncoupled twin", &ratio))) return st;
    if (res->status == VERDICT_PENDING) return CS_OK;
    claim_set_value(row, res, ratio);
    gate *g;
    double flag, lo, hi;
    if ((st = claim_gate_load("field.gate", &g))) return st;
    st = gate_value(g, "control_spread_outside_band", 0, &flag);
    if (!st) st = gate_value(g, "spread_ratio_band", 0, &lo);
    if (!st) st = gate_value(g, "spread_ratio_band", 1, &hi);
    gate_free(g);
    if (st) return st;
    gate_op op = flag != 0 ? GATE_OUT : GATE_IN;
    res->gate = gate_judge(op, ratio, lo, hi);
    snprintf(res->gate_detail, sizeof res->gate_detail, "%.6g %s [%g, %g]", ratio, gate_op_text(op), lo, hi);
    return CS_OK;
}
