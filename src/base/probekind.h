/* probekind: the names of the probes of what a generator uses (design.md
 * §8.4), shared by the experiment that runs them (src/exp/genprobe.h, where
 * each is described) and the claims that read their tables. */
#ifndef PROBEKIND_H
#define PROBEKIND_H
#include "cs.h"

typedef enum {
    PROBEKIND_NONE = 0, PROBEKIND_SELF, PROBEKIND_ROT15, PROBEKIND_ROT45, PROBEKIND_ROT90,
    PROBEKIND_NNSWAP, PROBEKIND_DEJITTER, PROBEKIND_SIZES, PROBEKIND_N
} probekind;

/* "none", "self", "rot15", "rot45", "rot90", "nnswap", "dejitter", "sizes". */
const char *probekind_name(probekind k);
/* CS_EINPUT for an unknown name. */
cs_status probekind_parse(const char *name, probekind *k);
/* 1 when the probe has a teacher's side (rot15, rot45, rot90, nnswap). */
int probekind_has_teacher(probekind k);

#endif
