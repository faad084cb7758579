/* claim_teacher_table: the teacher experiments' claims: E1 mechanism, E2 irreducibility, E9 hero (sections 1 to
 * 3 and 5), and E8 point-cloud stands (section 5.5). One row per claim: macro, kind, source, computing function,
 * registry gate column, section, format, reference and the typed params (claims.h). The registry,
 * audit/claims.tsv, is their print (`crownshy claims-table`); the CLAIMS rows of src/base/manifest.h give the
 * tables' order. */
#include "claims.h"

/* mechanism, irreducibility and hero rows, in the registry's order */
const claim_spec claim_table_teacher[] = {
    {"MechCoupOff", "measured", "frozen/mechanism/figure_stats.tsv", "claim_mech_ablation_k", "mechanism.gate:coupling_off_k1_max_m", "3.2", "%+.3f", "-4.541", {.set = PARAM_ARM | PARAM_COLUMN, .arm = ARM_COUPLING_OFF, .column = "k1_m"}},
    {"MechAbrOff", "measured", "frozen/mechanism/figure_stats.tsv", "claim_mech_ablation_k", "mechanism.gate:abrasion_off_k1_max_m", "3.2", "%+.3f", "+0.028", {.set = PARAM_ARM | PARAM_COLUMN, .arm = ARM_ABRASION_OFF, .column = "k1_m"}},
    {"MechOn", "measured", "frozen/mechanism/figure_stats.tsv", "claim_mech_ablation_k", "mechanism.gate:clearance_k1_min_m", "3.2", "%+.3f", "+0.364", {.set = PARAM_ARM | PARAM_COLUMN, .arm = ARM_BOTH_ON, .column = "k1_m"}},
    {"MechOverlap", "measured", "frozen/mechanism/figure_stats.tsv", "claim_mech_overlap", "mechanism.gate:overlap_max_m", "3.1", "%.2f", "0.00", {0}},
    {"MechOnKTwo", "measured", "frozen/mechanism/figure_stats.tsv", "claim_mech_ablation_k", "mechanism.gate:clearance_k2_min_m", "3.2", "%+.3f", "+0.390", {.set = PARAM_ARM | PARAM_COLUMN, .arm = ARM_BOTH_ON, .column = "k2_m"}},
    {"MechOnKThree", "measured", "frozen/mechanism/figure_stats.tsv", "claim_mech_ablation_k", "mechanism.gate:clearance_k3_min_m", "3.2", "%+.3f", "+0.421", {.set = PARAM_ARM | PARAM_COLUMN, .arm = ARM_BOTH_ON, .column = "k3_m"}},
    {"MechCoupOffKTwo", "measured", "frozen/mechanism/figure_stats.tsv", "claim_mech_ablation_k", "-", "3.2", "%+.3f", "-3.487", {.set = PARAM_ARM | PARAM_COLUMN, .arm = ARM_COUPLING_OFF, .column = "k2_m"}},
    {"MechCoupOffKThree", "measured", "frozen/mechanism/figure_stats.tsv", "claim_mech_ablation_k", "-", "3.2", "%+.3f", "-3.214", {.set = PARAM_ARM | PARAM_COLUMN, .arm = ARM_COUPLING_OFF, .column = "k3_m"}},
    {"MechCoverOn", "measured", "frozen/mechanism/figure_stats.tsv", "claim_mech_cover", "mechanism.gate:cover_min", "3.2", "%.2f", "0.85", {0}},
    {"MechHits", "measured", "frozen/mechanism/sweep.tsv", "claim_mech_hits", "-", "3.2", "%.0f", "14", {0}},
    {"MechRows", "design", "gates/mechanism.gate", "claim_design_mech_rows", "-", "3.2", "%.0f", "16", {0}},
    {"IrredRespLo", "measured", "frozen/irreducibility/perturb_field.tsv", "claim_irred_resp_lo", "irreducibility.gate:response_fraction_min", "3.3", "%.0f", "74", {0}},
    {"IrredRespHi", "measured", "frozen/irreducibility/perturb_field.tsv", "claim_irred_resp_hi", "-", "3.3", "%.0f", "100", {0}},
    {"IrredSpacings", "design", "gates/irreducibility.gate", "claim_design_irred_spacings", "-", "3.3", "%.0f", "5", {0}},
    {"IrredStepShrink", "measured", "frozen/irreducibility/refine_field.tsv", "claim_irred_step_shrink", "-", "3.3", "%.2f", "0.12", {0}},
    {"IrredRespShrink", "measured", "frozen/irreducibility/refine_field.tsv", "claim_irred_resp_shrink", "irreducibility.gate:refine_magnitude_ratio_min", "3.3", "%.2f", "0.41", {0}},
    {"IrredMiss", "measured", "frozen/irreducibility/reduction_field.tsv", "claim_irred_miss", "-", "3.3", "%.2f", "0.55", {0}},
    {"IrredSteps", "measured", "frozen/irreducibility/reduction_field.tsv", "claim_irred_steps", "irreducibility.gate:reduction_miss_steps_min", "3.3", "%.1f", "6.6", {0}},
    {"IrredRefineMax", "design", "gates/irreducibility.gate", "claim_design_irred_refine_max", "-", "3.3", "%.0f", "8", {0}},
    {"IrredTrainRespLo", "measured", "frozen/irreducibility/perturb_train.tsv", "claim_irred_resp_lo", "irreducibility.gate:response_fraction_min", "5", "%.0f", "74", {0}},
    {"IrredTrainSteps", "measured", "frozen/irreducibility/reduction_train.tsv", "claim_irred_steps", "irreducibility.gate:reduction_miss_steps_min", "5", "%.1f", "6.7", {0}},
    {"IrredTrainShrink", "measured", "frozen/irreducibility/refine_train.tsv", "claim_irred_resp_shrink", "irreducibility.gate:refine_magnitude_ratio_min", "5", "%.2f", "0.40", {0}},
    {"CalibDiebackTrain", "design", "gates/mechanism.gate", "claim_design_dieback_train", "mechanism.gate:dieback_train", "3.2", "%.2f", "0.06", {0}},
    {"HeroStemsDense", "measured", "frozen/hero/figure_crowns.tsv", "claim_hero_stems", "-", "1", "%.0f", "144", {.set = PARAM_SPACING, .spacing = 3}},
    {"HeroStemsSparse", "measured", "frozen/hero/figure_crowns.tsv", "claim_hero_stems", "-", "1", "%.0f", "30", {.set = PARAM_SPACING, .spacing = 6.5}},
};
CLAIM_TABLE_SIZE(claim_table_teacher);

/* the point-cloud stands */
const claim_spec claim_table_pointcloud[] = {
    {"PcSpacing", "design", "src/base/design.h", "claim_design_pc_spacing", "-", "5.5", "%.0f", "3", {.set = PARAM_STAND, .stand = STAND_SHOWN}},
    {"PcTrees", "measured", "frozen/pointcloud/figure_crowns.tsv", "claim_pc_stand", "-", "5.5", "%.0f", "144", {.set = PARAM_STAND | PARAM_QUANTITY, .stand = STAND_SHOWN, .quantity = "stems"}},
    {"PcCoupled", "measured", "frozen/pointcloud/stats.tsv", "claim_pc_clearance", "-", "5.5", "%+.3f", "+0.180", {.set = PARAM_ARM, .arm = ARM_COUPLED}},
    {"PcUncoupled", "measured", "frozen/pointcloud/stats.tsv", "claim_pc_clearance", "-", "5.5", "%+.3f", "-7.034", {.set = PARAM_ARM, .arm = ARM_UNCOUPLED}},
    {"PcContacted", "measured", "frozen/pointcloud/stats.tsv", "claim_pc_stand", "-", "5.5", "%.0f", "96", {.set = PARAM_STAND | PARAM_QUANTITY, .stand = STAND_SHOWN, .quantity = "contact"}},
    {"PcOtherASpacing", "design", "src/base/design.h", "claim_design_pc_spacing", "-", "5.5", "%.0f", "5", {.set = PARAM_STAND, .stand = STAND_OTHER_A}},
    {"PcOtherATrees", "measured", "frozen/pointcloud/figure_crowns.tsv", "claim_pc_stand", "-", "5.5", "%.0f", "51", {.set = PARAM_STAND | PARAM_QUANTITY, .stand = STAND_OTHER_A, .quantity = "stems"}},
    {"PcOtherAContacted", "measured", "frozen/pointcloud/stats.tsv", "claim_pc_stand", "-", "5.5", "%.0f", "85", {.set = PARAM_STAND | PARAM_QUANTITY, .stand = STAND_OTHER_A, .quantity = "contact"}},
    {"PcOtherBSpacing", "design", "src/base/design.h", "claim_design_pc_spacing", "-", "5.5", "%.0f", "4", {.set = PARAM_STAND, .stand = STAND_OTHER_B}},
    {"PcOtherBContacted", "measured", "frozen/pointcloud/stats.tsv", "claim_pc_stand", "-", "5.5", "%.0f", "92", {.set = PARAM_STAND | PARAM_QUANTITY, .stand = STAND_OTHER_B, .quantity = "contact"}},
};
CLAIM_TABLE_SIZE(claim_table_pointcloud);
