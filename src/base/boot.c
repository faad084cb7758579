/* boot: percentile bootstrap and single-unit ranges; see boot.h (design.md §6.1). */
#include "boot.h"
#include "stats.h"
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static cs_status level_ok(double level)
{
    if (!(level > 0.0 && level < 1.0)) return cs_err(CS_EINPUT, "interval level %.17g outside (0, 1)", level);
    return CS_OK;
}

static cs_status quantile_pair(const double *v, size_t n, double level, double *lo, double *hi)
{
    for (size_t i = 0; i < n; i++)
        if (!isfinite(v[i]))
            return cs_err(CS_EINPUT, "interval: value %zu of %zu is not finite (%.17g)", i + 1, n, v[i]);
    cs_status st = stats_quantile(v, n, (1.0 - level) / 2.0, lo);
    if (!st) st = stats_quantile(v, n, (1.0 + level) / 2.0, hi);
    return st;
}

cs_status boot_range(const double *v, size_t n, double level, double *lo, double *hi)
{
    if (n == 0) return cs_err(CS_EINPUT, "interval: no replicate values");
    cs_status st = level_ok(level);
    return st ? st : quantile_pair(v, n, level, lo, hi);
}

cs_status boot_percentile(const double *x, size_t n, size_t m, boot_stat stat, const void *ctx,
                          const boot_plan *plan, double *lo, double *hi)
{
    if (n == 0 || m == 0) return cs_err(CS_EINPUT, "bootstrap: no replicate units (%zu x %zu)", n, m);
    if (plan->resamples == 0) return cs_err(CS_EINPUT, "bootstrap: zero resamples");
    if (plan->seed == 0) return cs_err(CS_EINPUT, "bootstrap: seed 0 (GSL would use 4357)");
    cs_status st = level_ok(plan->level);
    if (st) return st;
    double *draw = malloc(n * m * sizeof *draw), *v = malloc(plan->resamples * sizeof *v);
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    if (!draw || !v || !r) st = cs_err(CS_ENOMEM, "bootstrap: out of memory");
    if (!st) gsl_rng_set(r, plan->seed);
    for (size_t b = 0; b < plan->resamples && !st; b++) {
        for (size_t i = 0; i < n; i++) {
            size_t k = (size_t)gsl_rng_uniform_int(r, (unsigned long)n);
            memcpy(draw + i * m, x + k * m, m * sizeof *draw);
        }
        st = stat(draw, n, m, ctx, &v[b]);
    }
    if (!st) st = quantile_pair(v, plan->resamples, plan->level, lo, hi);
    if (r) gsl_rng_free(r);
    free(draw);
    free(v);
    return st;
}

static cs_status column(const double *x, size_t n, size_t m, const void *ctx, double **out)
{
    size_t col = ctx ? *(const size_t *)ctx : 0;
    if (col >= m) return cs_err(CS_EINPUT, "bootstrap: column %zu of %zu", col, m);
    double *c = malloc(n * sizeof *c);
    if (!c) return cs_err(CS_ENOMEM, "bootstrap: out of memory");
    for (size_t i = 0; i < n; i++) c[i] = x[i * m + col];
    *out = c;
    return CS_OK;
}

cs_status boot_stat_median(const double *x, size_t n, size_t m, const void *ctx, double *out)
{
    double *c;
    cs_status st = column(x, n, m, ctx, &c);
    if (st) return st;
    st = stats_median(c, n, out);
    free(c);
    return st;
}

cs_status boot_stat_mean(const double *x, size_t n, size_t m, const void *ctx, double *out)
{
    double *c;
    cs_status st = column(x, n, m, ctx, &c);
    if (st) return st;
    *out = stats_mean(c, n);
    free(c);
    return CS_OK;
}
