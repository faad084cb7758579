/* stand: one simulated stand = stems (SPEC §2) + crown draws (SPEC §3), with
 * seeds from seed_derive(experiment, d, index, "stems" / "crowns"). Coupled
 * and uncoupled twins, perturbed copies and figure panels are made from the
 * same stand object, so they share stems and draws by construction. */
#ifndef STAND_H
#define STAND_H
#include "cs.h"
#include "stems.h"
#include "crown.h"
#include "teacher.h"

typedef enum { STAND_LATTICE, STAND_HARDCORE } stand_kind;

typedef struct {
    stems *s;
    crown_draw *draw;
    double *h, *R, *rstar;   /* n, n, n x CROWN_NSEC */
} stand;

/* shape: jitter a (lattice) or hard-core c. */
cs_status stand_alloc(stand **out, stand_kind kind, double d, double L, double shape,
                      const char *experiment, unsigned index);
/* Crowns drawn with seed `crown_seed` on given stems (takes ownership of s). */
cs_status stand_from_stems(stand **out, stems *s, uint64_t crown_seed);
void stand_free(stand *sd);
void stand_view(const stand *sd, teacher_stand *v);

#endif
