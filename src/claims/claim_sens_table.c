/* claim_sens_table: E0 sensitivity claims: the perfect-probe bounds (section 5.1) and the sensitivity and
 * readings account. One row per claim: macro, kind, source, computing function, registry gate column, section,
 * format, reference and the typed params (claims.h). The registry, audit/claims.tsv, is their print (`crownshy
 * claims-table`); the CLAIMS rows of src/base/manifest.h give the tables' order. */
#include "claims.h"

/* what a perfect generator would reach under the shuffled probe */
const claim_spec claim_table_perfect[] = {
    {"PerfectShufLo", "probe", "frozen/sensitivity/summary.tsv", "claim_perfect_shuf_lo", "-", "5.1", "%.3f", "-", {0}},
    {"PerfectShufHi", "probe", "frozen/sensitivity/summary.tsv", "claim_perfect_shuf_hi", "-", "5.1", "%.3f", "-", {0}},
    {"PerfectShufNeeded", "probe", "frozen/sensitivity/summary.tsv", "claim_perfect_shuf_needed", "-", "5.1", "%.3f", "-", {0}},
    {"PerfectBoundMax", "probe", "frozen/sensitivity/summary.tsv", "claim_perfect_bound_max", "-", "5.1", "%.2f", "-", {0}},
    {"PerfectBoundReaching", "probe", "frozen/sensitivity/summary.tsv", "claim_perfect_reaching", "-", "5.1", "%.0f", "-", {0}},
    {"PerfectTeachers", "probe", "frozen/sensitivity/summary.tsv", "claim_perfect_teachers", "-", "5.1", "%.0f", "-", {0}},
};
CLAIM_TABLE_SIZE(claim_table_perfect);

/* the sensitivity and readings account (section E0) */
const claim_spec claim_table_sensitivity[] = {
    {"SensGapLatticeLo", "probe", "frozen/mechanism/sweep.tsv", "claim_sens_gap", "-", "E0", "%.2f", "-", {.set = PARAM_QUANTITY | PARAM_BOUND, .quantity = "lattice", .bound = BOUND_LO}},
    {"SensGapLatticeHi", "probe", "frozen/mechanism/sweep.tsv", "claim_sens_gap", "-", "E0", "%.2f", "-", {.set = PARAM_QUANTITY | PARAM_BOUND, .quantity = "lattice", .bound = BOUND_HI}},
    {"SensGapFigure", "probe", "frozen/mechanism/figure_stats.tsv", "claim_sens_gap", "-", "E0", "%.2f", "-", {.set = PARAM_QUANTITY, .quantity = "figure"}},
    {"SensGapField", "probe", "frozen/field/heldout.tsv", "claim_sens_gap", "-", "E0", "%.2f", "-", {.set = PARAM_QUANTITY, .quantity = "field"}},
    {"SensGapPaperMech", "probe", "audit/claims.tsv", "claim_sens_paper", "-", "E0", "%.2f", "-", {.set = PARAM_QUANTITY, .quantity = "gap_mech"}},
    {"SensGapPaperField", "probe", "audit/claims.tsv", "claim_sens_paper", "-", "E0", "%.2f", "-", {.set = PARAM_QUANTITY, .quantity = "gap_field"}},
    {"SensPaperFieldSpacing", "probe", "audit/claims.tsv", "claim_sens_paper", "-", "E0", "%.1f", "-", {.set = PARAM_QUANTITY, .quantity = "field_spacing"}},
    {"SensStepPaper", "probe", "audit/claims.tsv", "claim_sens_paper", "-", "E0", "%.3f", "-", {.set = PARAM_QUANTITY, .quantity = "step"}},
    {"SensStepOurs", "probe", "frozen/irreducibility/reduction_field.tsv", "claim_sens_step", "-", "E0", "%.3f", "-", {0}},
    {"SensMechOnLo", "probe", "frozen/sensitivity/summary.tsv", "claim_sens_table", "-", "E0", "%+.3f", "-", {.set = PARAM_OF | PARAM_BOUND, .of = "MechOn", .bound = BOUND_LO}},
    {"SensMechOnHi", "probe", "frozen/sensitivity/summary.tsv", "claim_sens_table", "-", "E0", "%+.3f", "-", {.set = PARAM_OF | PARAM_BOUND, .of = "MechOn", .bound = BOUND_HI}},
    {"SensStepsHeight", "probe", "frozen/sensitivity/summary.tsv", "claim_sens_table", "-", "E0", "%.1f", "-", {.set = PARAM_OF | PARAM_CHOICE | PARAM_X | PARAM_BOUND, .of = "IrredSteps", .choice = "height_sd", .x = 6, .bound = BOUND_HI}},
    {"SensStepsMax", "probe", "frozen/sensitivity/summary.tsv", "claim_sens_table", "-", "E0", "%.1f", "-", {.set = PARAM_OF | PARAM_BOUND, .of = "IrredSteps", .bound = BOUND_HI}},
    {"SensRespShrinkLo", "probe", "frozen/sensitivity/summary.tsv", "claim_sens_table", "-", "E0", "%.2f", "-", {.set = PARAM_OF | PARAM_BOUND, .of = "IrredRespShrink", .bound = BOUND_LO}},
    {"SensRespShrinkHi", "probe", "frozen/sensitivity/summary.tsv", "claim_sens_table", "-", "E0", "%.2f", "-", {.set = PARAM_OF | PARAM_BOUND, .of = "IrredRespShrink", .bound = BOUND_HI}},
    {"SensIsoLo", "probe", "frozen/sensitivity/summary.tsv", "claim_sens_table", "-", "E0", "%.2f", "-", {.set = PARAM_OF | PARAM_BOUND, .of = "MainIso", .bound = BOUND_LO}},
    {"SensIsoHi", "probe", "frozen/sensitivity/summary.tsv", "claim_sens_table", "-", "E0", "%.2f", "-", {.set = PARAM_OF | PARAM_BOUND, .of = "MainIso", .bound = BOUND_HI}},
    {"SensCoupOffSmall", "probe", "frozen/sensitivity/summary.tsv", "claim_sens_table", "-", "E0", "%+.2f", "-", {.set = PARAM_OF | PARAM_CHOICE | PARAM_X | PARAM_BOUND, .of = "MechCoupOff", .choice = "crown_R", .x = 3, .bound = BOUND_HI}},
    {"SensCoupOffSmallKTwo", "probe", "frozen/sensitivity/summary.tsv", "claim_sens_table", "-", "E0", "%+.2f", "-", {.set = PARAM_OF | PARAM_CHOICE | PARAM_X | PARAM_BOUND, .of = "MechCoupOffKTwo", .choice = "crown_R", .x = 3, .bound = BOUND_HI}},
    {"SensCoupOffSmallKThree", "probe", "frozen/sensitivity/summary.tsv", "claim_sens_table", "-", "E0", "%+.2f", "-", {.set = PARAM_OF | PARAM_CHOICE | PARAM_X | PARAM_BOUND, .of = "MechCoupOffKThree", .choice = "crown_R", .x = 3, .bound = BOUND_HI}},
    {"SensArcMechOn", "probe", "frozen/readings/summary.tsv", "claim_sens_table", "-", "E0", "%+.3f", "-", {.set = PARAM_OF | PARAM_CHOICE | PARAM_BOUND, .of = "MechOn", .choice = "arc", .bound = BOUND_HI}},
    {"SensArcCalibDieback", "probe", "frozen/readings/summary.tsv", "claim_sens_table", "-", "E0", "%.2f", "-", {.set = PARAM_OF | PARAM_CHOICE | PARAM_BOUND, .of = "CalibDieback", .choice = "arc", .bound = BOUND_HI}},
    {"SensTargetMechOn", "probe", "frozen/sensitivity/summary.tsv", "claim_sens_table", "-", "E0", "%+.3f", "-", {.set = PARAM_OF | PARAM_CHOICE | PARAM_X | PARAM_BOUND, .of = "MechOn", .choice = "dieback", .x = 2, .bound = BOUND_HI}},
    {"SensAbrOffLo", "probe", "frozen/mechanism/sweep.tsv", "claim_sens_abroff", "-", "E0", "%+.3f", "-", {.set = PARAM_BOUND, .bound = BOUND_LO}},
    {"SensAbrOffHi", "probe", "frozen/mechanism/sweep.tsv", "claim_sens_abroff", "-", "E0", "%+.3f", "-", {.set = PARAM_BOUND, .bound = BOUND_HI}},
};
CLAIM_TABLE_SIZE(claim_table_sensitivity);
