/* stems: stem processes (design.md §2; reference paper §3, §5.4).
 * - Jittered ("controlled") lattice: square lattice of spacing d, rotated by
 *   U[0, pi/2), phase U[0,1)^2 in lattice units, per-axis Gaussian jitter sd a*d.
 *   A lattice node belongs to the stand when its unjittered position lies in
 *   the L x L footprint [0,L)^2 (so the count does not depend on the jitter).
 * - Hard-core Poisson (random sequential addition): n = floor((L/d)^2)
 *   uniform proposals in [0,L)^2, rejecting any closer than c*d to an accepted
 *   stem; after 1e5*n rejections the draw fails with CS_EINPUT ("unbuildable").
 * Interior trees: stems at least 2*d from every footprint edge.
 * RNG: gsl_rng_mt19937 seeded with seed_mt(seed). */
#ifndef STEMS_H
#define STEMS_H
#include "cs.h"
#include <stddef.h>
#include <stdint.h>

typedef struct {
    size_t n;
    double *x, *y;   /* stem positions, m */
    double L, d;     /* footprint side and nominal spacing, m */
} stems;

cs_status stems_lattice_alloc(stems **out, double d, double L, double jitter_a, uint64_t seed);
cs_status stems_hardcore_alloc(stems **out, double d, double L, double c, uint64_t seed);
/* A stem process as a type, in the manner of GSL's random-number types: its
 * name, what its one shape parameter is, and its alloc. A new process is a new
 * alloc and one entry of stems_types (stems.c). */
typedef struct {
    const char *name;  /* "lattice", "hardcore" */
    const char *shape; /* the shape parameter, in units of d */
    cs_status (*alloc)(stems **out, double d, double L, double shape, uint64_t seed);
} stems_type;
extern const stems_type *const stems_lattice;  /* the controlled lattice; shape: jitter sd a (design.md §2) */
extern const stems_type *const stems_hardcore; /* hard-core Poisson; shape: minimum distance c */
/* Every stem process, NULL-terminated. */
extern const stems_type *const stems_types[];
/* The process called name, or NULL. */
const stems_type *stems_type_find(const char *name);
/* A stand from given coordinates (copied); for tests and hand-built cases. */
cs_status stems_from_xy(stems **out, size_t n, const double *x, const double *y, double d, double L);
void stems_free(stems *s);
/* 1 when stem i is at least 2*d from every edge of [0,L]^2. */
int stems_interior(const stems *s, size_t i);
/* The focal stem of a stand (E2's perturbed tree, E7's comparison patch): the
 * interior stem nearest the footprint centre, the lowest index on a tie.
 * CS_EINPUT when no stem is interior. */
cs_status stems_focal(const stems *s, size_t *focal);

#endif
