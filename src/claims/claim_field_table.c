/* claim_field_table: E5 field claims (section 5.3): the die-back calibration and the held-out field figures. One
 * row per claim: macro, kind, source, computing function, registry gate column, section, format, reference and
 * the typed params (claims.h). The registry, audit/claims.tsv, is their print (`crownshy claims-table`); the
 * CLAIMS rows of src/base/manifest.h give the tables' order. */
#include "claims.h"

/* the field */
const claim_spec claim_table_field[] = {
    {"CalibTarget", "field", "gates/field.gate", "claim_design_calib_target", "-", "5.3", "%.3f", "0.620", {0}},
    {"CalibDieback", "measured", "frozen/field/calibration.tsv", "claim_field_calib_dieback", "-", "5.3", "%.2f", "0.16", {0}},
    {"CalibSeeds", "design", "gates/field.gate", "claim_design_calib_seeds", "-", "5.3", "%.0f", "3", {0}},
    {"FieldTrees", "field", "frozen/field/reference.tsv", "claim_field_reference", "-", "5.3", "%.0f", "23", {.set = PARAM_QUANTITY, .quantity = "trees"}},
    {"FieldMeas", "field", "frozen/field/reference.tsv", "claim_field_reference", "-", "5.3", "%.0f", "92", {.set = PARAM_QUANTITY, .quantity = "measurements"}},
    {"SpreadRatio", "needs-data", "frozen/field/heldout.tsv", "claim_field_spread_ratio", "field.gate:spread_ratio_band", "5.3", "%.2f", "1.57", {0}},
    {"ControlSpread", "needs-data", "frozen/field/heldout.tsv", "claim_field_control_spread", "field.gate:control_spread_outside_band", "5.3", "%.1f", "31.3", {0}},
    {"Elong", "measured", "frozen/field/heldout.tsv", "claim_field_elong", "field.gate:elongation_band", "5.3", "%.3f", "1.450", {0}},
    {"ElongLo", "field", "frozen/field/reference.tsv", "claim_field_reference", "-", "5.3", "%.2f", "1.27", {.set = PARAM_QUANTITY, .quantity = "elong_band_lo"}},
    {"ElongHi", "field", "frozen/field/reference.tsv", "claim_field_reference", "-", "5.3", "%.2f", "1.91", {.set = PARAM_QUANTITY, .quantity = "elong_band_hi"}},
};
CLAIM_TABLE_SIZE(claim_table_field);
