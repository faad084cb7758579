/* crown: the 24-sector radial crown, its one interpolation rule, and the
 * per-tree crown draws (design.md §1, §3; reference paper §3.1, Eq. 1).
 * Sector s is centred on bearing 2*pi*s/24, counter-clockwise from east (+x);
 * north (+y) is sector 6. Between sector centres the radius is linear in
 * angle (periodic). crown_radius_at implements that rule for the teacher,
 * the estimator and the renderers. One copy stands elsewhere on purpose:
 * patch_radius_at (src/model/patch.c), the batched estimator the model's
 * training and evaluation use on patches (paper §4.3), which is kept
 * independent of this stage and is checked against the canonical estimator
 * within 1e-6 m at the start of every run (patch_clearance_check). */
#ifndef CROWN_H
#define CROWN_H
#include "cs.h"
#include <stddef.h>
#include <gsl/gsl_rng.h>

#define CROWN_NSEC 24
#define CROWN_PI 3.14159265358979323846
#define CROWN_DTHETA (2.0 * CROWN_PI / CROWN_NSEC)
#define CROWN_R_LOG_SD 0.15 /* sd of log R (R = 4 exp(0.15 z), design.md §3) */

/* Radius of crown r at bearing theta (any real theta, wrapped periodically). */
double crown_radius_at(const double r[CROWN_NSEC], double theta);
/* Bearing of sector s (radians). */
double crown_theta(int s);

/* One tree's draw (design.md §3; crown_dist below gives the distributions). */
typedef struct {
    double h;    /* height, m: N(25, 4^2) truncated to [12, 38] by redraw */
    double R;    /* open-grown radius, m: 4 exp(0.15 z), z ~ N(0,1) */
    double a;    /* lobing amplitude ~ U[0, 0.2] */
    int k;       /* lobe count, uniform on {2,3,4,5} */
    double phi;  /* lobe phase ~ U[0, 2 pi) */
} crown_draw;

/* The per-tree distributions the paper leaves unstated (design.md §3). The
 * default is the design's; the sensitivity runs (design.md §7 E0) change one
 * field at a time. The lobe count stays uniform on {2,3,4,5}. */
typedef struct {
    double h_mean, h_sd;   /* height N(h_mean, h_sd^2), m ... */
    double h_lo, h_hi;     /* ... truncated to [h_lo, h_hi] by redraw */
    double R_scale;        /* R = R_scale exp(R_lnsd z), m */
    double R_lnsd;
    double a_max;          /* lobing amplitude a ~ U[0, a_max] */
} crown_dist;
#define CROWN_DIST_DEFAULT {25.0, 4.0, 12.0, 38.0, 4.0, CROWN_R_LOG_SD, 0.2}
void crown_dist_default(crown_dist *c);

/* Lobed target r*_s = R (1 + a cos(k theta_s + phi)) (paper Eq. 1). */
void crown_target(const crown_draw *c, double rstar[CROWN_NSEC]);
/* Draw n trees in index order from rng, fields drawn in the order h, z, a, k, phi,
 * from the default distribution. CS_ENUMERIC if the height redraw fails 1000
 * times (probability ~0). */
cs_status crown_draw_n(gsl_rng *rng, size_t n, crown_draw *out);
/* The same from distribution c (NULL: the default; bit-identical to
 * crown_draw_n then). CS_EINPUT for a distribution that cannot be drawn
 * (sd < 0, empty height range, a_max outside [0, 1), R_scale <= 0). */
cs_status crown_draw_n_dist(gsl_rng *rng, size_t n, const crown_dist *c, crown_draw *out);

#endif
