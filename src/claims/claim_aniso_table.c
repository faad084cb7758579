/* claim_aniso_table: E6 anisotropy claims (section 5.4): lattice, jitter and hard-core stands. One row per
 * claim: macro, kind, source, computing function, registry gate column, section, format, reference and the typed
 * params (claims.h). The registry, audit/claims.tsv, is their print (`crownshy claims-table`); the CLAIMS rows
 * of src/base/manifest.h give the tables' order. */
#include "claims.h"

/* the gap anisotropy */
const claim_spec claim_table_anisotropy[] = {
    {"AnisoLattice", "measured", "frozen/anisotropy/lattice.tsv", "claim_aniso_lattice", "-", "5.4", "%.3f", "1.176", {0}},
    {"AnisoBandLo", "field", "frozen/field/reference.tsv", "claim_field_reference", "-", "5.4", "%.2f", "1.20", {.set = PARAM_QUANTITY, .quantity = "aniso_band_lo"}},
    {"AnisoBandHi", "field", "frozen/field/reference.tsv", "claim_field_reference", "-", "5.4", "%.2f", "1.56", {.set = PARAM_QUANTITY, .quantity = "aniso_band_hi"}},
    {"AnisoTrees", "measured", "frozen/anisotropy/lattice.tsv", "claim_aniso_lattice_counts", "-", "5.4", "%.0f", "731", {.set = PARAM_COLUMN, .column = "aniso_trees"}},
    {"AnisoStands", "measured", "frozen/anisotropy/lattice.tsv", "claim_aniso_lattice_counts", "-", "5.4", "%.0f", "28", {.set = PARAM_COLUMN, .column = "stands"}},
    {"AnisoFieldMed", "field", "frozen/field/reference.tsv", "claim_field_reference", "-", "5.4", "%.3f", "1.362", {.set = PARAM_QUANTITY, .quantity = "aniso_median"}},
    {"JitterStar", "measured", "frozen/anisotropy/jitter_calibration.tsv", "claim_jitter_star", "-", "5.4", "%.2f", "0.08", {0}},
    {"JitterCanonicalPct", "design", "gates/anisotropy.gate", "claim_design_jitter_canonical_pct", "-", "5.4", "%.0f", "4", {0}},
    {"JitterStarPct", "measured", "frozen/anisotropy/jitter_calibration.tsv", "claim_jitter_star", "-", "5.4", "%.0f", "8", {.set = PARAM_SCALE, .scale = 100}},
    {"JitterAniso", "measured", "frozen/anisotropy/heldout.tsv", "claim_jitter_heldout", "anisotropy.gate:field_band", "5.4", "%.3f", "1.338", {.set = PARAM_COLUMN, .column = "aniso_median"}},
    {"JitterSpread", "needs-data", "frozen/anisotropy/heldout.tsv", "claim_field_spread_ratio", "anisotropy.gate:spread_ratio_band", "5.4", "%.2f", "1.58", {0}},
    {"JitterElong", "measured", "frozen/anisotropy/heldout.tsv", "claim_jitter_heldout", "anisotropy.gate:elongation_band", "5.4", "%.3f", "1.439", {.set = PARAM_COLUMN, .column = "elong_median"}},
    {"JitterStands", "measured", "frozen/anisotropy/heldout.tsv", "claim_jitter_heldout", "-", "5.4", "%.0f", "28", {.set = PARAM_COLUMN, .column = "stands"}},
    {"HardcoreRho", "measured", "frozen/anisotropy/hardcore.tsv", "claim_aniso_rho", "anisotropy.gate:hardcore_rho_max", "5.4", "text", "-9/10", {0}},
    {"JitterRho", "measured", "frozen/anisotropy/jitter.tsv", "claim_aniso_rho", "anisotropy.gate:jitter_rho_min", "5.4", "text", "1", {0}},
    {"HardcoreOvershoot", "measured", "frozen/anisotropy/hardcore.tsv", "claim_aniso_hardcore_overshoot", "-", "5.4", "%.3f", "1.645", {0}},
};
CLAIM_TABLE_SIZE(claim_table_anisotropy);
