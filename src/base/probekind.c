/* probekind: the probes' names; see probekind.h. */
#include "probekind.h"
#include <string.h>

static const char *const NAMES[PROBEKIND_N] = {"none",  "self",   "rot15",    "rot45",
                                               "rot90", "nnswap", "dejitter", "sizes"};

const char *probekind_name(probekind k) { return k >= 0 && k < PROBEKIND_N ? NAMES[k] : "?"; }

cs_status probekind_parse(const char *name, probekind *k)
{
    for (int i = 0; i < PROBEKIND_N; i++)
        if (name && !strcmp(name, NAMES[i])) { *k = (probekind)i; return CS_OK; }
    return cs_err(CS_EINPUT, "unknown generator probe '%s'", name ? name : "");
}

int probekind_has_teacher(probekind k)
{
    return k == PROBEKIND_ROT15 || k == PROBEKIND_ROT45 || k == PROBEKIND_ROT90 || k == PROBEKIND_NNSWAP;
}
