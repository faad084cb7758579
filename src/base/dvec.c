/* dvec: see dvec.h. */
#include "dvec.h"
#include <stdlib.h>

cs_status dvec_push(dvec *a, double x)
{
    if (a->n == a->cap) {
        size_t c = a->cap ? 2 * a->cap : 256;
        double *nv = realloc(a->v, c * sizeof *nv);
        if (!nv) return cs_err(CS_ENOMEM, "out of memory");
        a->v = nv;
        a->cap = c;
    }
    a->v[a->n++] = x;
    return CS_OK;
}
