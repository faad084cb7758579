/* Tests for src/base/stats.c against hand-computed cases (design.md §6). */
#include "testutil.h"
#include "stats.h"

static void test_wilcoxon_twelve_one_sign_is_two_over_4096(void **s)
{
    (void)s;
    double x[12], y[12];
    for (int i = 0; i < 12; i++) { x[i] = 0.9 + 0.01 * i; y[i] = 0.4 - 0.013 * i; }
    double p, t; size_t n;
    assert_int_equal(stats_wilcoxon_exact(x, y, 12, &p, &t, &n), CS_OK);
    ASSERT_EXACT(p, 0.00048828125);
    ASSERT_EXACT(t, 78.0);
    assert_int_equal(n, 12);
    /* The other sign gives the same two-sided p with T+ = 0. */
    assert_int_equal(stats_wilcoxon_exact(y, x, 12, &p, &t, &n), CS_OK);
    ASSERT_EXACT(p, 0.00048828125);
    ASSERT_EXACT(t, 0.0);
}

static void test_wilcoxon_five_hand_computed(void **s)
{
    (void)s;
    /* d = 1,-2,3,4,5: T+ = 13; P(T+>=13) = 3/32 (subsets of {1..5} summing to <=2). */
    double x[] = {1, -2, 3, 4, 5}, y[] = {0, 0, 0, 0, 0};
    double p, t;
    assert_int_equal(stats_wilcoxon_exact(x, y, 5, &p, &t, NULL), CS_OK);
    ASSERT_EXACT(t, 13.0);
    ASSERT_EXACT(p, 0.1875);
}

static void test_wilcoxon_five_all_positive_is_0625(void **s)
{
    (void)s;
    double x[] = {1, 2, 3, 4, 5}, y[] = {0, 0, 0, 0, 0};
    double p;
    assert_int_equal(stats_wilcoxon_exact(x, y, 5, &p, NULL, NULL), CS_OK);
    ASSERT_EXACT(p, 0.0625);
}

static void test_wilcoxon_ties_use_average_ranks_and_exact_conditional(void **s)
{
    (void)s;
    /* |d| = 1,1,2,3 -> ranks 1.5,1.5,3,4; T+ = 7; by enumeration of the 16
     * sign patterns P(T+>=7) = 5/16, so p = 0.625. */
    double x[] = {1, 1, -2, 3}, y[] = {0, 0, 0, 0};
    double p, t;
    assert_int_equal(stats_wilcoxon_exact(x, y, 4, &p, &t, NULL), CS_OK);
    ASSERT_EXACT(t, 7.0);
    ASSERT_EXACT(p, 0.625);
}

static void test_wilcoxon_drops_zeros(void **s)
{
    (void)s;
    double x[] = {1, 0.5, -2, 3, 4, 7, 5}, y[] = {0, 0.5, 0, 0, 0, 7, 0};
    double p, t; size_t n;
    assert_int_equal(stats_wilcoxon_exact(x, y, 7, &p, &t, &n), CS_OK);
    assert_int_equal(n, 5);
    ASSERT_EXACT(t, 13.0);
    ASSERT_EXACT(p, 0.1875);
}

static void test_wilcoxon_all_zero_gives_p_one(void **s)
{
    (void)s;
    double x[] = {1, 2}, y[] = {1, 2};
    double p; size_t n;
    assert_int_equal(stats_wilcoxon_exact(x, y, 2, &p, NULL, &n), CS_OK);
    assert_int_equal(n, 0);
    ASSERT_EXACT(p, 1.0);
}

static void test_spearman_one_swap_is_minus_nine_tenths(void **s)
{
    (void)s;
    double c[] = {0.3, 0.4, 0.5, 0.6, 0.7};
    double a[] = {1.9, 1.7, 1.6, 1.2, 1.4};
    double rho;
    assert_int_equal(stats_spearman(c, a, 5, &rho), CS_OK);
    ASSERT_NEAR(rho, -0.9, 1e-15);
}

static void test_spearman_monotone_is_one(void **s)
{
    (void)s;
    double x[] = {0.04, 0.06, 0.08, 0.10, 0.12, 0.16};
    double y[] = {1.1, 1.2, 1.35, 1.36, 1.5, 2.0};
    double rho;
    assert_int_equal(stats_spearman(x, y, 6, &rho), CS_OK);
    ASSERT_NEAR(rho, 1.0, 1e-15);
}

static void test_median_odd_even_and_unsorted(void **s)
{
    (void)s;
    double a[] = {5, 1, 3}, b[] = {4, 1, 3, 2};
    double m;
    assert_int_equal(stats_median(a, 3, &m), CS_OK);
    ASSERT_EXACT(m, 3.0);
    assert_int_equal(stats_median(b, 4, &m), CS_OK);
    ASSERT_EXACT(m, 2.5);
    ASSERT_EXACT(a[0], 5.0); /* input untouched */
}

static void test_iqr_linear_interpolation(void **s)
{
    (void)s;
    /* sorted 1..9: q25 = 3, q75 = 7 (positions 2 and 6 of 0..8) */
    double x[] = {9, 1, 8, 2, 7, 3, 6, 4, 5};
    double q;
    assert_int_equal(stats_iqr(x, 9, &q), CS_OK);
    ASSERT_EXACT(q, 4.0);
    assert_int_equal(stats_quantile(x, 9, 0.125, &q), CS_OK);
    ASSERT_EXACT(q, 2.0);
}

static void test_empty_input_is_error(void **s)
{
    (void)s;
    double m;
    assert_int_equal(stats_median(NULL, 0, &m), CS_EINPUT);
    assert_int_equal(stats_quantile((double[]){1}, 1, 1.5, &m), CS_EINPUT);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_wilcoxon_twelve_one_sign_is_two_over_4096),
        cmocka_unit_test(test_wilcoxon_five_hand_computed),
        cmocka_unit_test(test_wilcoxon_five_all_positive_is_0625),
        cmocka_unit_test(test_wilcoxon_ties_use_average_ranks_and_exact_conditional),
        cmocka_unit_test(test_wilcoxon_drops_zeros),
        cmocka_unit_test(test_wilcoxon_all_zero_gives_p_one),
        cmocka_unit_test(test_spearman_one_swap_is_minus_nine_tenths),
        cmocka_unit_test(test_spearman_monotone_is_one),
        cmocka_unit_test(test_median_odd_even_and_unsorted),
        cmocka_unit_test(test_iqr_linear_interpolation),
        cmocka_unit_test(test_empty_input_is_error),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
