/* Tests for src/base/boot.c (design.md §6.1) against a naive reference: the
 * same draws made with an explicit loop, sorted with qsort and interpolated
 * by hand, must give the same bits; and properties a percentile interval
 * must have whatever the data. */
#include "testutil.h"
#include "boot.h"
#include <gsl/gsl_rng.h>

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* quantile by hand: h = (n-1) q, linear between floor and ceil */
static double naive_quantile(double *v, size_t n, double q)
{
    qsort(v, n, sizeof *v, cmp);
    double h = (double)(n - 1) * q;
    size_t i = (size_t)h;
    if (i + 1 >= n) return v[n - 1];
    double f = h - (double)i;
    return (1 - f) * v[i] + f * v[i + 1];
}

static double naive_median_col(const double *x, size_t n, size_t m, size_t col)
{
    double *c = malloc(n * sizeof *c);
    for (size_t i = 0; i < n; i++) c[i] = x[i * m + col];
    double r = naive_quantile(c, n, 0.5);
    free(c);
    return r;
}

/* relative improvement of the column-0 median over the column-1 median */
static cs_status rel_stat(const double *x, size_t n, size_t m, const void *ctx, double *out)
{
    (void)ctx;
    double a = naive_median_col(x, n, m, 0), b = naive_median_col(x, n, m, 1);
    *out = (b - a) / b;
    return CS_OK;
}

static void naive_boot(const double *x, size_t n, size_t m, size_t B, unsigned long seed, double level,
                       double *lo, double *hi)
{
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(r, seed);
    double *draw = malloc(n * m * sizeof *draw), *st = malloc(B * sizeof *st);
    for (size_t b = 0; b < B; b++) {
        for (size_t i = 0; i < n; i++) {
            size_t k = gsl_rng_uniform_int(r, n);
            for (size_t j = 0; j < m; j++) draw[i * m + j] = x[k * m + j];
        }
        rel_stat(draw, n, m, NULL, &st[b]);
    }
    *lo = naive_quantile(st, B, (1 - level) / 2);
    *hi = naive_quantile(st, B, (1 + level) / 2);
    free(draw); free(st); gsl_rng_free(r);
}

static void twelve_seeds(double x[24])
{
    for (int i = 0; i < 12; i++) {
        x[2 * i] = 0.40 + 0.013 * ((i * 7) % 12);      /* joint */
        x[2 * i + 1] = 0.85 + 0.011 * ((i * 5) % 12);  /* indep */
    }
}

static void test_percentile_equals_the_naive_reference_bit_for_bit(void **s)
{
    (void)s;
    double x[24], lo, hi, nlo, nhi;
    twelve_seeds(x);
    boot_plan p = {2000, 20261201UL, 0.95};
    assert_int_equal(boot_percentile(x, 12, 2, rel_stat, NULL, &p, &lo, &hi), CS_OK);
    naive_boot(x, 12, 2, 2000, 20261201UL, 0.95, &nlo, &nhi);
    ASSERT_EXACT(lo, nlo);
    ASSERT_EXACT(hi, nhi);
    assert_true(lo < hi);
}

static void test_median_stat_equals_naive_median(void **s)
{
    (void)s;
    double x[24], v;
    twelve_seeds(x);
    size_t col = 1;
    assert_int_equal(boot_stat_median(x, 12, 2, &col, &v), CS_OK);
    ASSERT_EXACT(v, naive_median_col(x, 12, 2, 1));
    assert_int_equal(boot_stat_mean(x, 12, 2, &col, &v), CS_OK);
    double m = 0;
    for (int i = 0; i < 12; i++) m += x[2 * i + 1];
    assert_true(fabs(v - m / 12) < 1e-15);
}

static void test_same_seed_same_bits_other_seed_other_interval(void **s)
{
    (void)s;
    double x[24], a, b, c, d;
    twelve_seeds(x);
    boot_plan p = {500, 7UL, 0.95}, q = {500, 8UL, 0.95};
    assert_int_equal(boot_percentile(x, 12, 2, rel_stat, NULL, &p, &a, &b), CS_OK);
    assert_int_equal(boot_percentile(x, 12, 2, rel_stat, NULL, &p, &c, &d), CS_OK);
    ASSERT_EXACT(a, c);
    ASSERT_EXACT(b, d);
    assert_int_equal(boot_percentile(x, 12, 2, rel_stat, NULL, &q, &c, &d), CS_OK);
    assert_true(a != c || b != d);
}

static void test_constant_units_give_a_point(void **s)
{
    (void)s;
    double x[10] = {3, 3, 3, 3, 3, 3, 3, 3, 3, 3}, lo, hi;
    size_t col = 0;
    boot_plan p = {300, 11UL, 0.95};
    assert_int_equal(boot_percentile(x, 10, 1, boot_stat_median, &col, &p, &lo, &hi), CS_OK);
    ASSERT_EXACT(lo, 3.0);
    ASSERT_EXACT(hi, 3.0);
}

static void test_one_changed_unit_moves_the_interval(void **s)
{
    (void)s;
    double x[24], lo, hi, lo2, hi2;
    twelve_seeds(x);
    boot_plan p = {1000, 20261201UL, 0.95};
    assert_int_equal(boot_percentile(x, 12, 2, rel_stat, NULL, &p, &lo, &hi), CS_OK);
    x[2 * 3] += 0.2; /* one seed's joint error */
    assert_int_equal(boot_percentile(x, 12, 2, rel_stat, NULL, &p, &lo2, &hi2), CS_OK);
    assert_true(lo != lo2 || hi != hi2);
}

static void test_wider_level_gives_a_wider_interval(void **s)
{
    (void)s;
    double x[24], a, b, c, d;
    twelve_seeds(x);
    boot_plan p = {1000, 5UL, 0.5}, q = {1000, 5UL, 0.95};
    assert_int_equal(boot_percentile(x, 12, 2, rel_stat, NULL, &p, &a, &b), CS_OK);
    assert_int_equal(boot_percentile(x, 12, 2, rel_stat, NULL, &q, &c, &d), CS_OK);
    assert_true(c <= a && b <= d);
}

static void test_range_is_the_quantiles_of_the_values(void **s)
{
    (void)s;
    double v[40], w[40], lo, hi;
    for (int i = 0; i < 40; i++) v[i] = w[i] = sin(1.0 + i * 0.7);
    assert_int_equal(boot_range(v, 40, 0.95, &lo, &hi), CS_OK);
    ASSERT_EXACT(lo, naive_quantile(w, 40, 0.025));
    ASSERT_EXACT(hi, naive_quantile(w, 40, 0.975));
    assert_int_equal(boot_range(v, 1, 0.95, &lo, &hi), CS_OK);
    ASSERT_EXACT(lo, v[0]);
    ASSERT_EXACT(hi, v[0]);
}

static cs_status nan_stat(const double *x, size_t n, size_t m, const void *ctx, double *out)
{
    (void)x; (void)n; (void)m; (void)ctx;
    *out = NAN;
    return CS_OK;
}

static void test_bad_plans_and_nonfinite_statistics_are_refused(void **s)
{
    (void)s;
    double x[4] = {1, 2, 3, 4}, lo, hi;
    size_t col = 0;
    boot_plan ok = {10, 1UL, 0.95}, b0 = {0, 1UL, 0.95}, s0 = {10, 0UL, 0.95}, l1 = {10, 1UL, 1.0};
    assert_int_equal(boot_percentile(x, 0, 1, boot_stat_median, &col, &ok, &lo, &hi), CS_EINPUT);
    assert_int_equal(boot_percentile(x, 4, 1, boot_stat_median, &col, &b0, &lo, &hi), CS_EINPUT);
    assert_int_equal(boot_percentile(x, 4, 1, boot_stat_median, &col, &s0, &lo, &hi), CS_EINPUT);
    assert_int_equal(boot_percentile(x, 4, 1, boot_stat_median, &col, &l1, &lo, &hi), CS_EINPUT);
    assert_int_equal(boot_percentile(x, 4, 1, nan_stat, NULL, &ok, &lo, &hi), CS_EINPUT);
    double nv[2] = {1, NAN};
    assert_int_equal(boot_range(nv, 2, 0.95, &lo, &hi), CS_EINPUT);
}

int main(void)
{
    const struct CMUnitTest t[] = {
        cmocka_unit_test(test_percentile_equals_the_naive_reference_bit_for_bit),
        cmocka_unit_test(test_median_stat_equals_naive_median),
        cmocka_unit_test(test_same_seed_same_bits_other_seed_other_interval),
        cmocka_unit_test(test_constant_units_give_a_point),
        cmocka_unit_test(test_one_changed_unit_moves_the_interval),
        cmocka_unit_test(test_wider_level_gives_a_wider_interval),
        cmocka_unit_test(test_range_is_the_quantiles_of_the_values),
        cmocka_unit_test(test_bad_plans_and_nonfinite_statistics_are_refused),
    };
    return cmocka_run_group_tests(t, NULL, NULL);
}
