/* adamw: see adamw.h. Bias corrections are computed once per step in double;
 * the per-parameter loop is float and allocation-free. */
#include "adamw.h"
#include <math.h>

adamw_hp adamw_defaults(void)
{
    adamw_hp h = {0.9, 0.999, 1e-8, 0.01};
    return h;
}

static void update_range(float *restrict p, const float *restrict g, float *restrict m,
                         float *restrict v, size_t lo, size_t hi, float b1, float b2,
                         float a, float cv, float eps, float keep)
{
    const float c1 = 1.f - b1, c2 = 1.f - b2;
    for (size_t i = lo; i < hi; i++) {
        float gi = g[i];
        float mi = b1 * m[i] + c1 * gi;
        float vi = b2 * v[i] + c2 * (gi * gi);
        m[i] = mi;
        v[i] = vi;
        p[i] = p[i] * keep - a * mi / (sqrtf(vi * cv) + eps);
    }
}

void adamw_update(float *p, const float *g, float *m, float *v, size_t n, size_t ndecay,
                  long t, double lr, const adamw_hp *hp)
{
    double bc1 = 1.0 - pow(hp->beta1, (double)t), bc2 = 1.0 - pow(hp->beta2, (double)t);
    float a = (float)(lr / bc1), cv = (float)(1.0 / bc2);
    float keep = (float)(1.0 - lr * hp->wd);
    if (ndecay > n) ndecay = n;
    update_range(p, g, m, v, 0, ndecay, (float)hp->beta1, (float)hp->beta2, a, cv, (float)hp->eps, keep);
    update_range(p, g, m, v, ndecay, n, (float)hp->beta1, (float)hp->beta2, a, cv, (float)hp->eps, 1.f);
}
