/* exp_mechanism: E1 mechanism units (design.md §7 E1; reference paper §3.2),
 * writing <out>/mechanism/ (see exp_mechanism.c for the tables). */
#ifndef EXP_MECHANISM_H
#define EXP_MECHANISM_H
#include "exp_common.h"

/* 16 rows beta x d on the controlled lattice -> mechanism/sweep.tsv */
cs_status exp_mechanism_sweep(const exp_opts *o);
/* coupling off / abrasion off / both on at 3.5 m -> mechanism/ablation.tsv */
cs_status exp_mechanism_ablation(const exp_opts *o);
/* crowns of the three figure panels -> mechanism/figure_crowns.tsv */
cs_status exp_mechanism_figure(const exp_opts *o);

#endif
