/* figstand: the figure stands of E1, E8 and E9 (hard-core, L = 36 m; design.md §7 E1/E8/E9) and
 * the numbers each gives on stand k of its family (k = 0: the stand the figure shows; k > 0: the
 * replicate stands of design.md §6.1). The figure units (exp_mechanism.c, exp_stands.c) and the
 * replicates (exp_replicates.c) compute them here, so that stand 0 of the replicates is the
 * figure's number bit for bit. It grows stands and measures them; it writes no table. */
#ifndef FIGSTAND_H
#define FIGSTAND_H
#include "exp_common.h"

/* ---- pooled statistics of grown stands (the E1 cells) ---- */
/* A cell's numbers: k = 1..3 NN clearance medians, mean cover, worst overlap, interior trees. */
typedef struct { double k[3], cover, overlap; size_t trees; } figstand_cell;
/* One grown stand's share of a cell: its interior trees' k = 1..3 clearances appended to g,
 * its interior cover *cov, its worst overlap *w; *trees += its interior trees. */
cs_status figstand_stand_stats(const stand *sd, const double *r, dvec g[3], double *cov, double *w, size_t *trees);
/* A cell's result from its pooled clearances (freed here) after status st. */
cs_status figstand_cell_close(dvec g[3], double cover, double overlap, size_t trees, cs_status st,
                              figstand_cell *res);

/* ---- E1: the ablation's three arms (coupling off, abrasion off, both on) ---- */
extern const char *const figstand_ablation_arms[3];
extern const int figstand_ablation_coupled[3];
/* The gate's ablation spacing *d and each arm's die-back (dieback_train, 0, dieback_train). */
cs_status figstand_ablation_gate(double *d, double beta[3]);
/* Stand k of the E1 figure family (hard-core, d, L = 36 m) grown in the three arms: *sd and
 * *r (3 x n x CROWN_NSEC radii, arm-major) owned by the caller (also on failure), *worst the
 * worst overlap over the arms (maximum kept), fres the arms' numbers. */
cs_status figstand_mechanism_grow(const exp_opts *o, unsigned k, double d, const double beta[3], stand **sd,
                                  double **r, double *worst, figstand_cell fres[3]);
/* The E1 figure stand's numbers on stand k of its family, per ablation arm, as
 * mechanism/figure_stats.tsv gives them for k = 0. */
typedef struct { char arm[16]; double d, k[3], cover, overlap; size_t trees; } figstand_arm;
cs_status figstand_mechanism(const exp_opts *o, unsigned k, figstand_arm out[3]);

/* ---- E8 and E9 ---- */
/* One point-cloud stand (k = 0: the figure's) at spacing d, die-back beta: stems, interior
 * trees, contact and overlap shares, median k1 coupled and uncoupled, as a row of
 * pointcloud/stats.tsv; *worst: the coupled growth's worst overlap (maximum kept). */
typedef struct { size_t stems, trees; double contact, ovl_c, ovl_u, k1_c, k1_u; } figstand_pc_row;
cs_status figstand_pointcloud(const exp_opts *o, double d, double beta, unsigned k, figstand_pc_row *row,
                              double *worst);
/* Stems of hero stand k (k = 0: the figure's) at spacing d. */
cs_status figstand_hero_stems(const exp_opts *o, double d, unsigned k, size_t *stems_n);

#endif
