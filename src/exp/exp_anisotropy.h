/* exp_anisotropy: E6, what sets the gap anisotropy (design.md §7 E6; reference
 * paper §5.4). The entry points of its commands (argv tables:
 * src/cli/cli_field.c); each runs at beta_field from E5's calibration
 * table (o->calibration) and returns a status. */
#ifndef EXP_ANISOTROPY_H
#define EXP_ANISOTROPY_H
#include "cs.h"

/* The arguments (fieldrun.h). */
typedef struct exp_field_opts exp_field_opts;

cs_status exp_anisotropy_lattice(const exp_field_opts *o);
cs_status exp_anisotropy_hardcore(const exp_field_opts *o);
cs_status exp_anisotropy_jitter(const exp_field_opts *o);
/* a* from the jitter sweep o->sweep: o->out. */
cs_status exp_anisotropy_jitter_calibrate(const exp_field_opts *o);
/* Held-out stands at a* (o->jitter_calibration): o->out. */
cs_status exp_anisotropy_heldout(const exp_field_opts *o);

#endif
