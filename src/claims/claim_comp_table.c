/* claim_comp_table: E7 comparison claims (sections 3.1 and 6): the 24-tree patch, the dart probe and the pair
 * extension's comparison. One row per claim: macro, kind, source, computing function, registry gate column,
 * section, format, reference and the typed params (claims.h). The registry, audit/claims.tsv, is their print
 * (`crownshy claims-table`); the CLAIMS rows of src/base/manifest.h give the tables' order. */
#include "claims.h"

/* the 24-tree patch */
const claim_spec claim_table_comparison[] = {
    {"NSec", "design", "src/forest/crown.h", "claim_design_nsec", "-", "3.1", "%.0f", "24", {0}},
    {"CompGenOverlap", "measured", "frozen/paper-reading/comparison/dist_summary.tsv", "claim_comp_overlap", "-", "3.1", "%.0f", "9", {.set = PARAM_ARM | PARAM_STAT, .arm = ARM_JOINT, .stat = STAT_MEDIAN}},
    {"CompGenOverlapRange", "measured", "frozen/paper-reading/comparison/dist_summary.tsv", "claim_comp_overlap", "-", "3.1", "text", "-", {.set = PARAM_ARM | PARAM_STAT, .arm = ARM_JOINT, .stat = STAT_RANGE}},
    {"CompGenNoOverlap", "measured", "frozen/paper-reading/comparison/dist_summary.tsv", "claim_comp_no_overlap", "-", "3.1", "%.0f", "-", {0}},
    {"CompIndepOverlap", "measured", "frozen/paper-reading/comparison/dist_summary.tsv", "claim_comp_overlap", "-", "3.1", "%.0f", "15", {.set = PARAM_ARM | PARAM_STAT, .arm = ARM_INDEP, .stat = STAT_MEDIAN}},
    {"CompIndepOverlapRange", "measured", "frozen/paper-reading/comparison/dist_summary.tsv", "claim_comp_overlap", "-", "3.1", "text", "-", {.set = PARAM_ARM | PARAM_STAT, .arm = ARM_INDEP, .stat = STAT_RANGE}},
    {"CompTeachOverlap", "measured", "frozen/paper-reading/comparison/dist_summary.tsv", "claim_comp_overlap", "-", "3.1", "%.0f", "-", {.set = PARAM_ARM | PARAM_STAT, .arm = ARM_TEACHER, .stat = STAT_MEDIAN}},
    {"CompTeachOverlapRange", "measured", "frozen/paper-reading/comparison/dist_summary.tsv", "claim_comp_overlap", "-", "3.1", "text", "-", {.set = PARAM_ARM | PARAM_STAT, .arm = ARM_TEACHER, .stat = STAT_RANGE}},
    {"CompTrees", "design", "gates/main.gate", "claim_design_patch_trees", "-", "3.1", "%.0f", "24", {0}},
    {"GenCompSpacing", "design", "src/base/design.h", "claim_design_gencomp_spacing", "-", "3.1", "%.0f", "5", {0}},
    {"GenCompTeachK", "measured", "frozen/paper-reading/comparison/dist_summary.tsv", "claim_comp_k", "-", "3.1", "%+.3f", "+0.328", {.set = PARAM_ARM | PARAM_STAT, .arm = ARM_TEACHER, .stat = STAT_MEDIAN}},
    {"GenCompTeachKRange", "measured", "frozen/paper-reading/comparison/dist_summary.tsv", "claim_comp_k", "-", "3.1", "text", "-", {.set = PARAM_ARM | PARAM_STAT, .arm = ARM_TEACHER, .stat = STAT_RANGE}},
    {"GenCompGenK", "measured", "frozen/paper-reading/comparison/dist_summary.tsv", "claim_comp_k", "-", "3.1", "%+.3f", "+0.029", {.set = PARAM_ARM | PARAM_STAT, .arm = ARM_JOINT, .stat = STAT_MEDIAN}},
    {"GenCompGenKRange", "measured", "frozen/paper-reading/comparison/dist_summary.tsv", "claim_comp_k", "-", "3.1", "text", "-", {.set = PARAM_ARM | PARAM_STAT, .arm = ARM_JOINT, .stat = STAT_RANGE}},
    {"GenCompIndepK", "measured", "frozen/paper-reading/comparison/dist_summary.tsv", "claim_comp_k", "-", "3.1", "%+.3f", "-0.389", {.set = PARAM_ARM | PARAM_STAT, .arm = ARM_INDEP, .stat = STAT_MEDIAN}},
    {"GenCompIndepKRange", "measured", "frozen/paper-reading/comparison/dist_summary.tsv", "claim_comp_k", "-", "3.1", "text", "-", {.set = PARAM_ARM | PARAM_STAT, .arm = ARM_INDEP, .stat = STAT_RANGE}},
};
CLAIM_TABLE_SIZE(claim_table_comparison);

/* the dart probe, the pair extension's comparison, the canopy height model */
const claim_spec claim_table_comparison_dart_pair[] = {
    {"DartProbeTeachK", "measured", "frozen/paper-reading/comparison/dist_summary.tsv", "claim_comp_dart", "-", "6", "%+.3f", "+0.259", {.set = PARAM_ARM | PARAM_STAT, .arm = ARM_TEACHER, .stat = STAT_MEDIAN}},
    {"DartProbeTeachKRange", "measured", "frozen/paper-reading/comparison/dist_summary.tsv", "claim_comp_dart", "-", "6", "text", "-", {.set = PARAM_ARM | PARAM_STAT, .arm = ARM_TEACHER, .stat = STAT_RANGE}},
    {"DartProbeGenK", "measured", "frozen/paper-reading/comparison/dist_summary.tsv", "claim_comp_dart", "-", "6", "%+.3f", "-0.327", {.set = PARAM_ARM | PARAM_STAT, .arm = ARM_JOINT, .stat = STAT_MEDIAN}},
    {"DartProbeGenKRange", "measured", "frozen/paper-reading/comparison/dist_summary.tsv", "claim_comp_dart", "-", "6", "text", "-", {.set = PARAM_ARM | PARAM_STAT, .arm = ARM_JOINT, .stat = STAT_RANGE}},
    {"PairCompGenOverlap", "extension", "frozen/extension-pair/comparison/dist_summary.tsv", "claim_comp_overlap", "-", "3.1", "%.0f", "9", {.set = PARAM_ARM | PARAM_STAT, .arm = ARM_JOINT, .stat = STAT_MEDIAN}},
    {"PairCompGenOverlapRange", "extension", "frozen/extension-pair/comparison/dist_summary.tsv", "claim_comp_overlap", "-", "3.1", "text", "-", {.set = PARAM_ARM | PARAM_STAT, .arm = ARM_JOINT, .stat = STAT_RANGE}},
    {"PairCompGenNoOverlap", "extension", "frozen/extension-pair/comparison/dist_summary.tsv", "claim_comp_no_overlap", "-", "3.1", "%.0f", "-", {0}},
    {"PairCompIndepOverlap", "extension", "frozen/extension-pair/comparison/dist_summary.tsv", "claim_comp_overlap", "-", "3.1", "%.0f", "15", {.set = PARAM_ARM | PARAM_STAT, .arm = ARM_INDEP, .stat = STAT_MEDIAN}},
    {"PairCompIndepOverlapRange", "extension", "frozen/extension-pair/comparison/dist_summary.tsv", "claim_comp_overlap", "-", "3.1", "text", "-", {.set = PARAM_ARM | PARAM_STAT, .arm = ARM_INDEP, .stat = STAT_RANGE}},
    {"PairCompTeachOverlap", "extension", "frozen/extension-pair/comparison/dist_summary.tsv", "claim_comp_overlap", "-", "3.1", "%.0f", "-", {.set = PARAM_ARM | PARAM_STAT, .arm = ARM_TEACHER, .stat = STAT_MEDIAN}},
    {"PairCompTeachOverlapRange", "extension", "frozen/extension-pair/comparison/dist_summary.tsv", "claim_comp_overlap", "-", "3.1", "text", "-", {.set = PARAM_ARM | PARAM_STAT, .arm = ARM_TEACHER, .stat = STAT_RANGE}},
    {"PairGenCompTeachK", "extension", "frozen/extension-pair/comparison/dist_summary.tsv", "claim_comp_k", "-", "3.1", "%+.3f", "+0.328", {.set = PARAM_ARM | PARAM_STAT, .arm = ARM_TEACHER, .stat = STAT_MEDIAN}},
    {"PairGenCompTeachKRange", "extension", "frozen/extension-pair/comparison/dist_summary.tsv", "claim_comp_k", "-", "3.1", "text", "-", {.set = PARAM_ARM | PARAM_STAT, .arm = ARM_TEACHER, .stat = STAT_RANGE}},
    {"PairGenCompGenK", "extension", "frozen/extension-pair/comparison/dist_summary.tsv", "claim_comp_k", "-", "3.1", "%+.3f", "+0.029", {.set = PARAM_ARM | PARAM_STAT, .arm = ARM_JOINT, .stat = STAT_MEDIAN}},
    {"PairGenCompGenKRange", "extension", "frozen/extension-pair/comparison/dist_summary.tsv", "claim_comp_k", "-", "3.1", "text", "-", {.set = PARAM_ARM | PARAM_STAT, .arm = ARM_JOINT, .stat = STAT_RANGE}},
    {"PairGenCompIndepK", "extension", "frozen/extension-pair/comparison/dist_summary.tsv", "claim_comp_k", "-", "3.1", "%+.3f", "-0.389", {.set = PARAM_ARM | PARAM_STAT, .arm = ARM_INDEP, .stat = STAT_MEDIAN}},
    {"PairGenCompIndepKRange", "extension", "frozen/extension-pair/comparison/dist_summary.tsv", "claim_comp_k", "-", "3.1", "text", "-", {.set = PARAM_ARM | PARAM_STAT, .arm = ARM_INDEP, .stat = STAT_RANGE}},
    {"PairDartProbeTeachK", "extension", "frozen/extension-pair/comparison/dist_summary.tsv", "claim_comp_dart", "-", "6", "%+.3f", "+0.259", {.set = PARAM_ARM | PARAM_STAT, .arm = ARM_TEACHER, .stat = STAT_MEDIAN}},
    {"PairDartProbeTeachKRange", "extension", "frozen/extension-pair/comparison/dist_summary.tsv", "claim_comp_dart", "-", "6", "text", "-", {.set = PARAM_ARM | PARAM_STAT, .arm = ARM_TEACHER, .stat = STAT_RANGE}},
    {"PairDartProbeGenK", "extension", "frozen/extension-pair/comparison/dist_summary.tsv", "claim_comp_dart", "-", "6", "%+.3f", "-0.327", {.set = PARAM_ARM | PARAM_STAT, .arm = ARM_JOINT, .stat = STAT_MEDIAN}},
    {"PairDartProbeGenKRange", "extension", "frozen/extension-pair/comparison/dist_summary.tsv", "claim_comp_dart", "-", "6", "text", "-", {.set = PARAM_ARM | PARAM_STAT, .arm = ARM_JOINT, .stat = STAT_RANGE}},
    {"RealChmSpan", "needs-data", "CHM (ESRI ASCII grid, env CHM=path)", "claim_chm_span", "-", "3.1", "%.0f", "96", {0}},
};
CLAIM_TABLE_SIZE(claim_table_comparison_dart_pair);
