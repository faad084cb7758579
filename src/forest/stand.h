/* stand: one simulated stand = stems (design.md §2) + crown draws (design.md §3), with
 * seeds from seed_derive(experiment, d, index, "stems" / "crowns"). Coupled
 * and uncoupled twins, perturbed copies and figure panels are made from the
 * same stand object, so they share stems and draws by construction. */
#ifndef STAND_H
#define STAND_H
#include "cs.h"
#include "stems.h"
#include "crown.h"

/* A read-only view of a stand's arrays: what the teacher grows (teacher.h
 * names it teacher_stand) and what a perturbation modifies (a copy of h). */
typedef struct {
    size_t n;
    const double *x, *y;  /* stems, m */
    const double *h;      /* heights, m: order and vigour (per-tree override = pass a modified copy) */
    const double *R;      /* open-grown radii, m (Delta = median R / N) */
    const double *rstar;  /* targets, n x CROWN_NSEC */
} stand_arrays;

typedef struct {
    stems *s;
    crown_draw *draw;
    double *h, *R, *rstar;   /* n, n, n x CROWN_NSEC */
} stand;

/* Stems of process kind (stems.h: its shape parameter), then crowns. */
cs_status stand_alloc(stand **out, const stems_type *kind, double d, double L, double shape,
                      const char *experiment, unsigned index);
/* The same with crowns from distribution cd (NULL: the default, bit-identical
 * to stand_alloc); the sensitivity runs (design.md §7 E0) change cd. */
cs_status stand_alloc_dist(stand **out, const stems_type *kind, double d, double L, double shape,
                           const char *experiment, unsigned index, const crown_dist *cd);
cs_status stand_from_stems_dist(stand **out, stems *s, uint64_t crown_seed, const crown_dist *cd);
void stand_free(stand *sd);
void stand_view(const stand *sd, stand_arrays *v);

#endif
