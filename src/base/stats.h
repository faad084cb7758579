/* stats: the study's statistics (design.md §6). Exact two-sided Wilcoxon
 * signed-rank with zeros dropped and average ranks for ties; Spearman rho and
 * quantiles via GSL on sorted copies. W1 lives in the pinned estimator
 * (src/forest/estimator.c, est_w1) because it is part of the instrument. */
#ifndef STATS_H
#define STATS_H
#include "cs.h"
#include <stddef.h>

/* Paired differences d_i = x_i - y_i. Zeros are dropped; ties get average
 * ranks and the exact conditional null distribution of T+ (all 2^n sign
 * assignments of the observed ranks). p = min(1, 2 min(P(T+<=t), P(T+>=t))).
 * n_used (may be NULL) = number of non-zero differences. With no non-zero
 * difference p = 1. n_used above 60 is refused (exact enumeration only). */
cs_status stats_wilcoxon_exact(const double *x, const double *y, size_t n,
                               double *p, double *tplus, size_t *n_used);
/* Spearman rank correlation (GSL, average ranks for ties). n >= 2. */
cs_status stats_spearman(const double *x, const double *y, size_t n, double *rho);
/* Quantile q in [0,1] (GSL linear interpolation on a sorted copy). n >= 1. */
cs_status stats_quantile(const double *x, size_t n, double q, double *out);
cs_status stats_median(const double *x, size_t n, double *out);
/* Interquartile range q75 - q25. */
cs_status stats_iqr(const double *x, size_t n, double *out);
double stats_mean(const double *x, size_t n);
double stats_min(const double *x, size_t n);
double stats_max(const double *x, size_t n);

#endif
