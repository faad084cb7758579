/* exp_replicates: replicate stands of the one-stand figure numbers
 * (design.md §6.4, §7 E1/E8/E9), writing <out>/replicates/figure_stands.tsv. */
#ifndef EXP_REPLICATES_H
#define EXP_REPLICATES_H
#include "exp_common.h"
/* Stands k = 0..o->stands-1 of each figure family (k = 0: the figure's own). */
cs_status exp_replicates_run(const exp_opts *o);
#endif
