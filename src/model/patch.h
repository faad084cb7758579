/* patch: model inputs from a stand given as plain arrays (paper §4.1, design.md §8):
 * the T = 24 stems nearest a focal stem (focal first, then by distance, ties by
 * index), per-token features ((p_i - p_focal)/d, rbar_i/d), the patch condition
 * vector, the deviation profile x_i = r_i - rbar_i (standardised by one global
 * scale fitted on training data), and a batched clearance estimator on patches
 * (paper Eq. 5; design.md §1, §5) with a check against the canonical estimator.
 * Sector s of a crown vector is centred on theta_s = 2 pi s / 24, counter-
 * clockwise from east; r(theta) is periodic linear interpolation in angle.
 * Independent of the teacher module: stands come in as arrays. The batched
 * clearance (patch_radius_at, patch_clearance) is a second copy of the
 * canonical rule (crown.h, estimator.h), kept here so the model stage does
 * not import the forest stage; patch_clearance_check compares the two within
 * 1e-6 m at the start of every run (paper §4.3). */
#ifndef PATCH_H
#define PATCH_H
#include "cs.h"
#include <gsl/gsl_rng.h>

#define PATCH_T 24     /* trees per patch */
#define PATCH_P 24     /* sectors per crown */
/* Per-token features: (x_i - x_f)/d, (y_i - y_f)/d, rbar_i/d, then the same
 * relative position in a polar Fourier basis: cos k phi_i, sin k phi_i for
 * k = 1..4 (phi_i the bearing of stem i from the focal stem; 0 for the focal
 * itself) and rho_i / d. The basis is a fixed function of (p_i - p_f)/d, so a
 * token still carries only its own position and size (design.md §8); it makes the
 * map from a bearing to a crown profile linear, which the flow model
 * otherwise failed to learn within the E3 budget (see paper, Method). */
#define PATCH_NFEAT 12
#define PATCH_FEAT_RBAR 2 /* index of rbar_i/d; every other feature is positional */
/* Conditions: d/5 m; local density * d^2 (24 / (pi rho^2), rho = distance to the
 * 24th stem); mean and sd of the patch stems' nearest-neighbour distances / d;
 * stand median height / 25 m (0 when heights are not given). */
#define PATCH_NCOND 5

typedef struct {
    int n;
    const double *x, *y; /* [n] stem positions, m */
    const double *r;     /* [n*24] crown radii, m */
    double d;            /* nominal spacing, m */
    double median_h;     /* stand median height, m (0 if unknown) */
} patch_stand;

/* Validate and fill `s` (h may be NULL). CS_EINPUT on n < 24, d <= 0, or a
 * non-finite or negative value (message names the array and index). */
cs_status patch_stand_init(patch_stand *s, int n, const double *x, const double *y,
                           const double *r, const double *h, double d);

typedef struct {
    int idx[PATCH_T];                /* stand indices, focal first */
    double px[PATCH_T], py[PATCH_T]; /* positions relative to the focal stem, m */
    double rbar[PATCH_T];            /* mean crown radius, m */
    double dev[PATCH_T * PATCH_P];   /* r - rbar, m */
    float feat[PATCH_T * PATCH_NFEAT];
    float cond[PATCH_NCOND];
} patch;

/* The 24 stems nearest stem `focal` (focal included, first), by distance then index. */
cs_status patch_neighbours(const patch_stand *s, int focal, int idx[PATCH_T]);
cs_status patch_build(const patch_stand *s, int focal, patch *p);

/* A growable set of patches in model layout. */
typedef struct {
    int n, cap;
    float *x1;    /* [n*T*P] deviations: metres until standardised, then / scale */
    float *feat;  /* [n*T*NFEAT] */
    float *cond;  /* [n*NCOND] */
    double *px, *py, *rbar; /* [n*T] geometry for reconstruction and evaluation */
    double scale; /* 0 until patch_set_standardise */
} patch_set;

cs_status patch_set_alloc(patch_set **out, int cap);
void patch_set_free(patch_set *s);
cs_status patch_set_add(patch_set *s, const patch *p);
/* Root-mean-square deviation over all values of the set (the global scale). */
double patch_set_rms(const patch_set *s);
/* Divide all deviations by `scale` (> 0) and record it. */
cs_status patch_set_standardise(patch_set *s, double scale);
/* Crown radii r[T*P] (m) of patch k from standardised deviations x[T*P]. */
void patch_set_radii(const patch_set *s, int k, const float *x, double *r);

/* r(theta) of one crown (periodic linear interpolation between sector centres). */
double patch_radius_at(const double *r, double theta);
/* g(i,j) = nu - r_i(theta_ij) - r_j(theta_ji) (paper Eq. 5). */
double patch_clearance(double xi, double yi, const double *ri, double xj, double yj,
                       const double *rj);
/* Batched: for each of n patches (px, py [n*T], radii r [n*T*P]), clearance of
 * the focal tree (token 0) toward its k-th nearest neighbour (token k),
 * k = 1..K; out[n*K]. K < T. */
cs_status patch_focal_clearances(const double *px, const double *py, const double *r,
                                 int n, int K, double *out);

/* Signature of the canonical estimator's pairwise clearance (est_clearance). */
typedef double (*patch_clearance_ref)(double xi, double yi, const double *ri,
                                      double xj, double yj, const double *rj);
/* Compare patch_clearance with `ref` on every pair of trees in n patches;
 * CS_EINVARIANT (message: patch, pair, both values) if any differs by more than
 * 1e-6 m or is not finite. *maxdiff (may be NULL) receives the largest difference. */
cs_status patch_clearance_check(patch_clearance_ref ref, const double *px, const double *py,
                                const double *r, int n, double *maxdiff);

/* Toy stand for development and tests until the teacher supplies stands:
 * side x side jittered lattice (spacing d, jitter sd 0.1 d), crowns of mean
 * radius R ~ 0.4 d (1 + 0.1 z) flattened toward the nearest stem,
 * r(theta) = R (1 - 0.2 cos(theta - theta_nn)). x, y [side^2], r [side^2 * 24]. */
void patch_toy_stand(gsl_rng *rng, int side, double d, double *x, double *y, double *r);

/* Shuffled-geometry probe (design.md §8): permute the position features
 * ((x - x_f)/d, (y - y_f)/d) among the T tokens of each of n patches in
 * feat[n*T*NFEAT] (uniform permutation from rng; rbar_i/d stays with its
 * token). Generation then sees wrong geometry; evaluate with the true positions. */
void patch_shuffle_positions(float *feat, int n, gsl_rng *rng);
/* The permutation patch_shuffle_positions draws for one patch (token i is
 * given the position of token perm[i]); the same draws from rng. */
void patch_shuffle_perm(gsl_rng *rng, int perm[PATCH_T]);
/* Rotation probe (design.md §8, added after the first verdict): patch g of an
 * evaluation set is rotated about its focal stem by (1 + g mod 7) x 45 deg
 * (rad), every angle a whole number of sectors. */
double patch_rotation_angle(int g);
/* Rotate the geometry of n patches in feat[n*T*NFEAT] about the focal stem,
 * patch k by alpha[k] (rad): (x, y)/d and the polar Fourier basis turn; rbar/d
 * and rho/d stay. Generation then sees turned geometry; evaluate with the
 * true positions. */
void patch_rotate_positions(float *feat, int n, const double *alpha);
/* Crown r[P] turned counter-clockwise by `steps` sectors (15 deg each):
 * out[s] = r[(s - steps) mod P]; out must not alias r. The teacher's side of
 * the rotation probe. */
void patch_rotate_crown(const double *r, int steps, double *out);
/* Direction-blind baseline (design.md §8): every crown of r[ncrowns*P] replaced by
 * its circular mean (all sectors equal to the mean radius); in place allowed. */
void patch_direction_blind(const double *r, int ncrowns, double *out);

/* Append the patches of `nstands` toy stands (12 x 12 stems, spacing d) to s,
 * one per interior stem (at least 2 d from the lattice edge: 64 per stand).
 * Stand k draws from mt19937 seeded with seed + k. */
cs_status patch_set_add_toy(patch_set *s, int nstands, double d, unsigned long seed);

#endif
