/* exp_stands: the hard-core canopy stands of E8 (point cloud) and E9 (hero),
 * design.md §7 E8/E9, writing <out>/pointcloud/ and <out>/hero/. */
#ifndef EXP_STANDS_H
#define EXP_STANDS_H
#include "exp_common.h"

/* E9: rows beta_train and, when o->beta is a number, beta_field. */
cs_status exp_hero_figure(const exp_opts *o);
/* E8: 5, 4, 3 m coupled + uncoupled, and pointcloud/stats.tsv. */
cs_status exp_pointcloud_figure(const exp_opts *o);
/* One point-cloud stand (k = 0: the figure's) at spacing d, die-back beta:
 * stems, interior trees, contact and overlap shares, median k1 coupled and
 * uncoupled, as a row of pointcloud/stats.tsv; *worst: the coupled growth's
 * worst overlap (maximum kept). */
typedef struct { size_t stems, trees; double contact, ovl_c, ovl_u, k1_c, k1_u; } exp_pc_row;
cs_status exp_pointcloud_stand(const exp_opts *o, double d, double beta, unsigned k, exp_pc_row *row, double *worst);
/* Stems of hero stand k (k = 0: the figure's) at spacing d. */
cs_status exp_hero_stems(const exp_opts *o, double d, unsigned k, size_t *stems_n);

#endif
