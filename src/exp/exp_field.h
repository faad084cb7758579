/* exp_field: E5, field validation (design.md §7 E5; reference paper §5.3).
 * The entry points of its commands (argv tables: src/cli/cli_field.c); each
 * returns a status. E6 (anisotropy) is exp_anisotropy.h. */
#ifndef EXP_FIELD_H
#define EXP_FIELD_H
#include "cs.h"

/* The arguments (fieldrun.h). */
typedef struct exp_field_opts exp_field_opts;

/* Summarise a raw field table (NULL: $FIELD_TABLE) beside the published figures. */
cs_status exp_field_summary(const char *table);
/* Calibrate beta to the field's tree-mean median clearance: o->out. */
cs_status exp_field_calibrate(const exp_field_opts *o);
/* Print beta_field recomputed from a calibration table. */
cs_status exp_field_beta(const char *calibration);
/* Held-out stands at beta_field (coupled and the uncoupled twin): o->out. */
cs_status exp_field_heldout(const exp_field_opts *o);
/* Diagnostics of the elongation and anisotropy verdicts (printed only). */
cs_status exp_field_diagnose(const exp_field_opts *o);

#endif
