/* stand_grow: the one way the experiments grow a stand with the teacher
 * (design.md §4): a stand (stand.h) under teacher parameters, optionally with
 * modified heights (E2's perturbed tree), keeping the worst self-check
 * overlap of the run. Above both stand and teacher, so that neither imports
 * the other's caller. */
#ifndef STAND_GROW_H
#define STAND_GROW_H
#include "cs.h"
#include "stand.h"
#include "teacher.h"

/* Grow sd under p into r (n x CROWN_NSEC). h: per-tree heights to use
 * instead of the drawn ones (NULL: the drawn heights). info may be NULL.
 * *worst (may be NULL) is raised to the run's self-check overlap (0 for an
 * uncoupled growth). Errors as teacher_grow. */
cs_status stand_grow(const stand *sd, const teacher_params *p, const double *h, double *r,
                     teacher_info *info, double *worst);

/* Bench (design.md §10): CPU ms (one core) per 144-tree controlled-lattice stand at
 * d = 3.5 m, beta 0.06 (the default teacher reading), for resolution nres,
 * over `reps` stands (seeds 0..reps-1), each timed alone: ms[0] the median,
 * ms[1] and ms[2] the fastest and slowest; process CPU time, which stays
 * comparable when other jobs share the machine. */
cs_status stand_grow_bench(int nres, int reps, double ms[3]);

#endif
