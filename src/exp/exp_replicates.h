/* exp_replicates: the replicate stands of the numbers that rest on one figure stand
 * (design.md §6.1), writing <out>/replicates/figure_stands.tsv (see exp_replicates.c). */
#ifndef EXP_REPLICATES_H
#define EXP_REPLICATES_H
#include "exp_common.h"

/* stands k = 0..o->stands-1 of each figure family -> replicates/figure_stands.tsv */
cs_status exp_replicates_run(const exp_opts *o);

#endif
