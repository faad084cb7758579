/* exp_stands: the hard-core canopy stands of E8 (point cloud) and E9 (hero),
 * design.md §7 E8/E9, writing <out>/pointcloud/ and <out>/hero/. */
#ifndef EXP_STANDS_H
#define EXP_STANDS_H
#include "exp_common.h"

/* E9: rows beta_train and, when o->beta is a number, beta_field. */
cs_status exp_hero_figure(const exp_opts *o);
/* E8: 5, 4, 3 m coupled + uncoupled, and pointcloud/stats.tsv. */
cs_status exp_pointcloud_figure(const exp_opts *o);

#endif
