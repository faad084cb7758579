/* boot: percentile intervals over independent replicate units (design.md
 * §6.1). A data set is n units (rows) of m values each (columns, e.g. the
 * two arms of one seed); a statistic maps such a set to one number. The
 * percentile bootstrap draws B sets of n units with replacement (rows kept
 * whole, so pairing survives), evaluates the statistic on each and reports
 * the (1-level)/2 and (1+level)/2 quantiles (at level 0.95: 2.5 and 97.5 %;
 * GSL linear interpolation on the
 * sorted draws, as stats_quantile). Draws come from gsl_rng_mt19937 seeded
 * with `seed`: unit index = gsl_rng_uniform_int(r, n), row by row, resample
 * by resample, so an interval is a pure function of (data, stat, B, seed).
 * Non-finite statistics are refused (they would sort arbitrarily).
 * The range of single-unit values (boot_range) is the interval of a number
 * that rests on one unit: where another unit of the same family would land. */
#ifndef BOOT_H
#define BOOT_H
#include "cs.h"
#include <stddef.h>

/* x: n rows of m values, row-major; ctx: the statistic's own parameters. */
typedef cs_status (*boot_stat)(const double *x, size_t n, size_t m, const void *ctx, double *out);

typedef struct {
    size_t resamples;   /* B >= 1 */
    unsigned long seed; /* gsl_rng_mt19937 seed (0 is refused: GSL maps it to 4357) */
    double level;       /* in (0, 1), e.g. 0.95 */
} boot_plan;

/* Percentile bootstrap of stat over the n units of x; n >= 1, m >= 1. */
cs_status boot_percentile(const double *x, size_t n, size_t m, boot_stat stat, const void *ctx,
                          const boot_plan *plan, double *lo, double *hi);
/* The (1-level)/2 and (1+level)/2 quantiles of n single-unit values; n >= 1. */
cs_status boot_range(const double *v, size_t n, double level, double *lo, double *hi);

/* Ready statistics over column `col` (ctx points to a size_t column index). */
cs_status boot_stat_median(const double *x, size_t n, size_t m, const void *ctx, double *out);
cs_status boot_stat_mean(const double *x, size_t n, size_t m, const void *ctx, double *out);

#endif
