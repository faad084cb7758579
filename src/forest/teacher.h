/* teacher: coupled crown growth with contact abrasion (design.md §4; reference
 * paper §3.1, Eqs. 1-3). The adopted reading of Eq. 3 is mutual abrasion,
 * `teacher-2`, pinned by the audit. teacher_params selects the other readings
 * the paper's words allow, kept runnable for the readings and sensitivity
 * tables (design.md §7, E0): one_sided (`teacher-1`) and the die-back rule
 * (dieback: own sector only, the default; the contact arc s-1..s+1; beta of
 * the target length), each named by teacher_version().
 *
 * Rule: step Delta = median_i(R_i) / N; hbar = mean height as drawn (or an
 * explicit override: a perturbation keeps the unperturbed mean). Start at
 * r = f r* (Eq. 1 targets; f = start_frac, 0.05 by default). Rounds: trees in descending height (ties by
 * lower index); each tree advances, in sector order 0..23, every sector
 * neither frozen nor at target to r' = min(r + Delta (h_i/hbar)^gamma, r*_s)
 * (Eq. 2). Coupling on: if the proposed boundary of sector s of tree i would
 * enter another crown (the contact test below), the sector freezes for good
 * and dies back, r <- (1 - beta) r (Eq. 3, "where sector s made contact");
 * otherwise r <- r'. Coupling off: every sector ends at its target. Stop when
 * a round changes nothing; more than 100 N rounds is an error.
 *
 * teacher-2, mutual abrasion (Eq. 3 read for each crown in the contact): in
 * addition, every crown j the proposal would enter loses beta of its own
 * sector t nearest the bearing from p_j to i's proposed tip p_i + r' u_s
 * (t = round(bearing / 15 deg) mod 24, half-way to the counter-clockwise
 * sector), r_j,t <- (1 - beta) r_j,t, and that sector freezes; at every such
 * contact, so a frozen sector can lose beta again. All crowns entered are
 * found against the same state before any die-back is applied.
 * teacher-1, one-sided: only i's sector dies back; j may regrow into the
 * space i gave up.
 * Die-back readings (dieback; apply to every crown that loses a sector):
 *   TEACHER_DIEBACK_OWN (default, Eq. 3 as written): r_s <- (1 - beta) r_s;
 *   TEACHER_DIEBACK_NEIGHBOURS (`-arc`): the sectors either side of the
 *     contacting one die back the same way and freeze too (the contact test
 *     already looks at the arc [theta_{s-1}, theta_{s+1}]);
 *   TEACHER_DIEBACK_TARGET (`-target`): r_s <- max(0, r_s - beta r*_s), beta
 *     of the target length (contradicts Eq. 3; a reading only).
 * Both extra readings only lower radii, so the safety argument below holds.
 * Why j's die-back is safe for the self-check: it only lowers r_j,t, so j's
 * region shrinks (interpolation weights are >= 0): no clearance g falls and no
 * point enters j that was outside. j's changed sample points move inward along
 * their own rays by at least beta r_j,t / 8; such a point can land inside a
 * crown k only where j and k already overlapped in area that deep, and the
 * test below leaves no overlap beyond the sub-sample lens between sample
 * points (depth ~ r dphi^2 / 8 ~ 0.5 mm at r = 4 m, dphi = 2 pi/192). So for
 * beta >= ~0.01 it cannot raise the measured overlap; at beta = 0 nothing
 * moves; the end-of-growth self-check guards whatever this bound leaves.
 * Freezing j's sector only stops its growth (fewer proposals, never a larger
 * crown); the bookkeeping counts it once as no longer active.
 *
 * Contact test ("would enter"): moving sector s changes the boundary on the
 * two arcs [theta_{s-1}, theta_{s+1}]. For every neighbour j that a cheap
 * wedge/disk bound cannot exclude, the test rejects the proposal when
 *   (a) a sample point of i's changed arcs lies strictly inside j's current crown,
 *   (b) g(i,j) < 0 (Eq. 5, the estimator's own function), or
 *   (c) a sample point of j's boundary lies strictly inside i's proposed crown.
 * Sample points: 8 per sector interval, at bearings (8s+q) 2 pi/192, radius
 * r_s + (q/8)(r_{s+1} - r_s). The self-check (teacher_worst_overlap) measures
 * exactly the quantities (a)-(c) test, with the same arithmetic, so it cannot
 * fire unless the rule is broken.
 * A stand whose starting crowns already overlap (stems closer than about
 * 0.05 (r*_i + r*_j), possible under strong jitter) is refused with CS_EINPUT
 * ("unbuildable") instead of being grown with a bent rule.
 * Neighbours come from a uniform grid (pairs with nu < max r*_i + max r*_j):
 * no all-pairs loops. Single-threaded, deterministic. */
#ifndef TEACHER_H
#define TEACHER_H
#include "cs.h"
#include "crown.h"
#include "stand.h"
#include <stddef.h>

#define TEACHER_VERSION "teacher-2"           /* the adopted reading, pinned by the audit */
#define TEACHER_VERSION_ONE_SIDED "teacher-1" /* one-sided die-back, a reading (design.md §7 E0) */
#define TEACHER_SAMPLES_PER_SECTOR 8
#define TEACHER_OVERLAP_MAX_M 1e-9

typedef enum {
    TEACHER_DIEBACK_OWN = 0,        /* the contacting sector only (Eq. 3) */
    TEACHER_DIEBACK_NEIGHBOURS = 1, /* and its two neighbours */
    TEACHER_DIEBACK_TARGET = 2      /* beta of the target length */
} teacher_dieback;

typedef struct {
    double beta;    /* die-back fraction (dimensionless) */
    int coupled;    /* 1: occupancy + abrasion; 0: grow to target */
    int nres;       /* growth resolution N (default 48) */
    double gamma;   /* vigour exponent (1) */
    double hbar;    /* > 0: use this stand mean height; <= 0: mean of h */
    unsigned char *frozen_out; /* optional, n x CROWN_NSEC: 1 where a sector froze on contact
                                  (teacher-2: both the entering and the entered sector) */
    int one_sided;  /* 0 (default): teacher-2, mutual abrasion; 1: teacher-1, one-sided */
    teacher_dieback dieback; /* die-back rule (default TEACHER_DIEBACK_OWN) */
    double start_frac;       /* starting radius as a fraction of r*, in (0, 1] (default 0.05) */
} teacher_params;

/* The version string of the reading p selects: "teacher-2" or "teacher-1",
 * with "-arc" or "-target" for the other die-back rules. Provenance records
 * it (start_frac is a parameter, not a reading: units record it themselves). */
const char *teacher_version(const teacher_params *p);

/* beta 0.06, coupled, N 48, gamma 1, hbar from the heights, no frozen output,
 * teacher-2, own-sector die-back, start 0.05 r*. */
void teacher_params_default(teacher_params *p);

/* What the teacher reads of a stand (stand.h: stems, heights, radii, targets;
 * heights may be a modified copy for a perturbation). */
typedef stand_arrays teacher_stand;

typedef struct {
    double step;          /* Delta, m */
    double hbar;          /* mean height used, m */
    long rounds;          /* rounds run (0 when uncoupled: targets copied) */
    size_t frozen;        /* frozen sectors (teacher-2: both sides of each contact) */
    size_t abraded;       /* teacher-2: die-backs of entered crowns (repeats counted); 0 under teacher-1 */
    double worst_overlap; /* self-check, m (coupled runs); 0 when uncoupled */
} teacher_info;

/* Grow the stand; r (n x CROWN_NSEC) receives the final crowns. Errors:
 * CS_EINPUT (bad parameters; starting crowns overlap: "unbuildable"), CS_ENOMEM, CS_ENUMERIC (> 100 N rounds),
 * CS_EINVARIANT (self-check above 1e-9 m; info->worst_overlap holds it). */
cs_status teacher_grow(const teacher_stand *st, const teacher_params *p, double *r, teacher_info *info);

/* Worst overlap of crowns r: max over stem pairs within reach of max(0, -g(i,j))
 * and of the penetration of each crown's sample points (8 per sector) into the
 * other. 0 when no crowns touch. */
cs_status teacher_worst_overlap(const double *x, const double *y, const double *r, size_t n,
                                double *worst);


#endif
