/* estimator: the canonical instrument (design.md §5; reference paper §4.3,
 * Eqs. 5 and 6; elongation paper §5.3). Every clearance, W1, cover and directional statistic of the
 * teacher experiments and the claims is computed here; src/forest/estimator.c
 * is pinned by SHA-256. The one other clearance code is the batched estimator
 * on model patches (src/model/patch.c, paper §4.3's guarded instrument), which
 * every training and evaluation run checks against est_clearance within
 * 1e-6 m before it starts, and whose W1 is this file's est_w1.
 * Crowns are CROWN_NSEC radii per tree (n x 24, row-major); stems x, y in m.
 * Bearings are atan2(dy, dx), counter-clockwise from east. */
#ifndef ESTIMATOR_H
#define ESTIMATOR_H
#include "cs.h"
#include <stddef.h>

/* Cardinal directions, in the order of est_cardinal_gaps' output. */
enum { EST_E = 0, EST_N = 1, EST_W = 2, EST_S = 3 };

/* Clearance g(i,j) = nu - r_i(theta_ij) - r_j(theta_ji) (paper Eq. 5);
 * positive is a gap, negative is interpenetration. */
double est_clearance(double xi, double yi, const double *ri, double xj, double yj, const double *rj);

/* Index of the k-th (k >= 1) nearest other stem of i by stem distance, ties by
 * lower index; -1 if fewer than k others. */
long est_knn(const double *x, const double *y, size_t n, size_t i, int k);
/* g(i, k-th nearest neighbour of i). CS_EINPUT if i has fewer than k neighbours. */
cs_status est_knn_clearance(const double *x, const double *y, const double *r, size_t n,
                            size_t i, int k, double *g);

/* Exact W1 between two empirical distributions (paper Eq. 6): the integral over
 * u in (0,1) of |Fa^{-1}(u) - Fb^{-1}(u)|, evaluated piece by piece on the merged
 * breakpoints i/na and j/nb. est_w1_sorted needs both inputs sorted ascending;
 * est_w1 sorts copies. CS_EINPUT on an empty sample or a non-finite value. */
double est_w1_sorted(const double *a, size_t na, const double *b, size_t nb);
cs_status est_w1(const double *a, size_t na, const double *b, size_t nb, double *w1);

/* Canopy cover: fraction of the rectangle [x0,x1] x [y0,y1] (the interior
 * area) inside at least one crown, on a grid of cell centres with spacing at
 * most 0.05 m (nx = ceil((x1-x0)/0.05) cells across). */
#define EST_COVER_GRID_M 0.05
cs_status est_cover(const double *x, const double *y, const double *r, size_t n,
                    double x0, double y0, double x1, double y1, double *cover);

/* Cardinal gaps of tree i toward E, N, W, S: the smallest g(i,j) over all
 * other trees j whose bearing theta_ij lies within +-45 deg (inclusive) of the
 * direction; NaN where no tree lies in that cone. */
void est_cardinal_gaps(const double *x, const double *y, const double *r, size_t n,
                       size_t i, double gaps[4]);
/* Tree-mean clearance: mean of the four cardinal gaps. */
double est_tree_mean(const double gaps[4]);
/* Anisotropy: widest / narrowest cardinal gap. Returns 0 (and leaves *aniso
 * untouched) when a gap is non-positive or NaN: the tree is excluded and the
 * caller counts it; 1 when *aniso was set. */
int est_anisotropy(const double gaps[4], double *aniso);
/* Elongation (paper §5.3, "the ratio of the longest to shortest crown axis";
 * design.md §5): max / min over the 12 axes r(theta_s) + r(theta_s + pi),
 * s = 0..11. Axis length is piecewise linear between sector centres, so no
 * finer axis gives another value. A square crown reads sqrt(2) at any rotation
 * that puts sector centres on its diagonals and sides (every multiple of 15 deg). */
double est_elongation(const double *ri);
/* The two-axis reading, kept for the readings table (design.md §7 E0): longest /
 * shortest of the two cardinal axes only, r(N)+r(S) and r(E)+r(W). A square
 * crown reads 1 at any rotation, so this reads ~1 on any lattice. */
double est_elongation_cardinal(const double *ri);

/* Directional summary of a set of trees (the field comparisons, design.md §7 E5/E6):
 * for every tree with use[i] != 0 (use NULL: all trees), its four cardinal
 * gaps. A tree lacking a neighbour in some cardinal cone is "incomplete" and
 * left out of every statistic (counted); a tree with a non-positive cardinal
 * gap is left out of the anisotropy median only (counted). */
typedef struct {
    size_t trees;            /* complete trees used */
    size_t incomplete;       /* trees without a neighbour in some cone (excluded) */
    size_t aniso_excluded;   /* trees with a non-positive cardinal gap (excluded from anisotropy) */
    double tree_mean_median; /* median over trees of the tree-mean clearance, m */
    double spread;           /* IQR of the pooled cardinal gaps (4 per tree), m */
    double aniso_median;     /* median anisotropy (NaN when every tree is excluded) */
    double elong_median;     /* median elongation (all 12 axes) */
    double elong_cardinal_median; /* median two-axis elongation (cardinal axes; readings only) */
} est_directional;
cs_status est_directional_summary(const double *x, const double *y, const double *r, size_t n,
                                  const unsigned char *use, est_directional *out);

/* Median, quantile (GSL on a sorted copy) and spread (= interquartile range). */
cs_status est_median(const double *v, size_t n, double *out);
cs_status est_quantile(const double *v, size_t n, double q, double *out);
cs_status est_spread(const double *gaps, size_t n, double *iqr);

#endif
