/* adamw: Adam with decoupled weight decay (Loshchilov & Hutter) on flat float
 * buffers; decay applies to the first ndecay values only (the model puts its
 * weight matrices first, so gains and biases are not decayed). design.md §8. */
#ifndef ADAMW_H
#define ADAMW_H
#include <stddef.h>

typedef struct { double beta1, beta2, eps, wd; } adamw_hp;

/* beta1 0.9, beta2 0.999, eps 1e-8, wd 0.01. */
adamw_hp adamw_defaults(void);
/* One update at 1-based step t with learning rate lr:
 * m = b1 m + (1-b1) g;  v = b2 v + (1-b2) g^2;
 * p = p (1 - lr wd [i < ndecay]) - lr (m / (1 - b1^t)) / (sqrt(v / (1 - b2^t)) + eps). */
void adamw_update(float *p, const float *g, float *m, float *v, size_t n, size_t ndecay,
                  long t, double lr, const adamw_hp *hp);

#endif
