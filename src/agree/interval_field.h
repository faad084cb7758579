/* interval_field: the stand units of the E5/E6 per-tree tables (design.md
 * §6.1). A field or anisotropy claim is a median over the coupled trees of one
 * or more levels (or a curve through them: Spearman's rho, the calibrated
 * die-back and jitter); its unit is the stand, so the bootstrap draws stands
 * and regroups their trees as fs_group does. Limit: at most 32 coupled levels. */
#ifndef INTERVAL_FIELD_H
#define INTERVAL_FIELD_H
#include "interval.h"

/* The extractor of the field and anisotropy claims: which statistic follows
 * from the row's function (and, for the count and held-out rows, its column). */
cs_status interval_field_stands(const claim_row *row, const claim_result *res, const interval_spec *sp, iv_data *d);

#endif
