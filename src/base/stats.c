/* stats: exact Wilcoxon signed-rank, Spearman rho, quantiles (design.md §6).
 * The Wilcoxon null is enumerated exactly on doubled ranks (integers even with
 * average ranks for ties) by a subset-sum count: counts stay exact in double
 * up to 2^53, hence the n <= 60 limit. */
#include "stats.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <gsl/gsl_sort.h>
#include <gsl/gsl_statistics_double.h>

typedef struct { double a; int pos; } absd;

static int cmp_absd(const void *x, const void *y)
{
    const absd *p = x, *q = y;
    if (p->a < q->a) return -1;
    if (p->a > q->a) return 1;
    return p->pos - q->pos;
}

cs_status stats_wilcoxon_exact(const double *x, const double *y, size_t n,
                               double *p, double *tplus, size_t *n_used)
{
    absd *d = malloc((n ? n : 1) * sizeof *d);
    if (!d) return cs_err(CS_ENOMEM, "wilcoxon: out of memory");
    size_t m = 0;
    for (size_t i = 0; i < n; i++) {
        double di = x[i] - y[i];
        if (!isfinite(di)) { free(d); return cs_err(CS_EINPUT, "wilcoxon: non-finite difference at pair %zu", i + 1); }
        if (di != 0.0) { d[m].a = fabs(di); d[m].pos = di > 0 ? 1 : 0; m++; }
    }
    if (n_used) *n_used = m;
    if (m == 0) { free(d); *p = 1.0; if (tplus) *tplus = 0.0; return CS_OK; }
    if (m > 60) {
        free(d);
        return cs_err(CS_EINPUT, "wilcoxon: %zu non-zero pairs, exact enumeration limited to 60", m);
    }
    qsort(d, m, sizeof *d, cmp_absd);
    /* doubled average ranks: tie group occupying ranks i+1..j gets (i+1+j) */
    int *rank2 = malloc(m * sizeof *rank2);
    if (!rank2) { free(d); return cs_err(CS_ENOMEM, "wilcoxon: out of memory"); }
    for (size_t i = 0; i < m;) {
        size_t j = i;
        while (j + 1 < m && d[j + 1].a == d[i].a) j++;
        for (size_t k = i; k <= j; k++) rank2[k] = (int)(i + 1 + j + 1);
        i = j + 1;
    }
    long t2 = 0, total = 0;
    for (size_t i = 0; i < m; i++) { total += rank2[i]; if (d[i].pos) t2 += rank2[i]; }
    double *cnt = calloc((size_t)total + 1, sizeof *cnt);
    if (!cnt) { free(d); free(rank2); return cs_err(CS_ENOMEM, "wilcoxon: out of memory"); }
    cnt[0] = 1.0;
    long hi = 0;
    for (size_t i = 0; i < m; i++) {
        for (long s = hi; s >= 0; s--)
            if (cnt[s] != 0.0) cnt[s + rank2[i]] += cnt[s];
        hi += rank2[i];
    }
    double le = 0.0, ge = 0.0;
    for (long s = 0; s <= total; s++) {
        if (s <= t2) le += cnt[s];
        if (s >= t2) ge += cnt[s];
    }
    double all = ldexp(1.0, (int)m);
    double pl = le / all, pg = ge / all;
    double pv = 2.0 * (pl < pg ? pl : pg);
    *p = pv > 1.0 ? 1.0 : pv;
    if (tplus) *tplus = 0.5 * (double)t2;
    free(cnt); free(rank2); free(d);
    return CS_OK;
}

cs_status stats_spearman(const double *x, const double *y, size_t n, double *rho)
{
    if (n < 2) return cs_err(CS_EINPUT, "spearman: need at least 2 pairs, got %zu", n);
    double *a = malloc(4 * n * sizeof *a);
    if (!a) return cs_err(CS_ENOMEM, "spearman: out of memory");
    memcpy(a, x, n * sizeof *a);
    memcpy(a + n, y, n * sizeof *a);
    /* GSL sorts its inputs in place, hence the copies. */
    *rho = gsl_stats_spearman(a, 1, a + n, 1, n, a + 2 * n);
    free(a);
    if (!isfinite(*rho)) return cs_err(CS_ENUMERIC, "spearman: undefined (constant input)");
    return CS_OK;
}

cs_status stats_quantile(const double *x, size_t n, double q, double *out)
{
    if (n == 0) return cs_err(CS_EINPUT, "quantile of an empty sample");
    if (!(q >= 0.0 && q <= 1.0)) return cs_err(CS_EINPUT, "quantile level %.17g outside [0,1]", q);
    double *a = malloc(n * sizeof *a);
    if (!a) return cs_err(CS_ENOMEM, "quantile: out of memory");
    memcpy(a, x, n * sizeof *a);
    gsl_sort(a, 1, n);
    *out = gsl_stats_quantile_from_sorted_data(a, 1, n, q);
    free(a);
    return CS_OK;
}

cs_status stats_median(const double *x, size_t n, double *out)
{
    return stats_quantile(x, n, 0.5, out);
}

cs_status stats_iqr(const double *x, size_t n, double *out)
{
    double q1, q3;
    cs_status st = stats_quantile(x, n, 0.25, &q1);
    if (!st) st = stats_quantile(x, n, 0.75, &q3);
    if (!st) *out = q3 - q1;
    return st;
}

double stats_mean(const double *x, size_t n)
{
    double s = 0.0;
    for (size_t i = 0; i < n; i++) s += x[i];
    return n ? s / (double)n : NAN;
}

double stats_min(const double *x, size_t n)
{
    double m = INFINITY;
    for (size_t i = 0; i < n; i++) if (x[i] < m) m = x[i];
    return m;
}

double stats_max(const double *x, size_t n)
{
    double m = -INFINITY;
    for (size_t i = 0; i < n; i++) if (x[i] > m) m = x[i];
    return m;
}
