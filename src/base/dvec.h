/* dvec: a growable array of doubles (what the experiments pool clearances
 * into). Limits: grows by doubling; the caller frees v. */
#ifndef DVEC_H
#define DVEC_H
#include "cs.h"
#include <stddef.h>

typedef struct { double *v; size_t n, cap; } dvec;
/* Append x; CS_ENOMEM when the array cannot grow. */
cs_status dvec_push(dvec *a, double x);

#endif
