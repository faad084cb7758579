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
/* The figure stand's numbers on stand k of its family (hard-core, 3.5 m,
 * L = 36 m; k = 0 is the stand shown): per ablation arm, as figure_stats.tsv. */
typedef struct { char arm[16]; double d, k[3], cover, overlap; size_t trees; } exp_fig_arm;
cs_status exp_mechanism_figure_stand(const exp_opts *o, unsigned k, exp_fig_arm out[3]);

#endif
