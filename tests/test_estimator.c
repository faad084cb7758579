/* Tests for src/forest/estimator.c on hand-built stands: Eq. 5, k-NN, W1 (Eq. 6),
 * cover, cardinal gaps, anisotropy, elongation over all 12 axes (a square
 * reads sqrt 2 at 0, 15 and 30 degrees; a fine sweep agrees) beside the
 * cardinal reading (the square reads 1), spread. */
#include "testutil.h"
#include "estimator.h"
#include "crown.h"

static void fill(double *r, double v) { for (int s = 0; s < CROWN_NSEC; s++) r[s] = v; }

static void test_clearance_two_trees_by_hand(void **st)
{
    (void)st;
    double ra[CROWN_NSEC], rb[CROWN_NSEC];
    for (int s = 0; s < CROWN_NSEC; s++) { ra[s] = 1.0 + 0.1 * s; rb[s] = 2.0 - 0.05 * s; }
    /* B at (3, 4) from A: nu = 5; bearing 53.13 deg (sector 3.542), back-bearing 233.13 deg (15.542). */
    double ua = atan2(4.0, 3.0) / CROWN_DTHETA;
    double ub = (atan2(-4.0, -3.0) + 2.0 * CROWN_PI) / CROWN_DTHETA;
    double expect = 5.0 - (1.0 + 0.1 * ua) - (2.0 - 0.05 * ub);
    ASSERT_NEAR(est_clearance(0.0, 0.0, ra, 3.0, 4.0, rb), expect, 1e-12);
    ASSERT_NEAR(expect, 2.4228997, 1e-6); /* 5 - 1.3541997 - 1.2229006 */
}

static void test_clearance_is_negative_when_crowns_interpenetrate(void **st)
{
    (void)st;
    double ra[CROWN_NSEC], rb[CROWN_NSEC];
    fill(ra, 1.25);
    fill(rb, 0.875);
    ASSERT_EXACT(est_clearance(1.0, 1.0, ra, 1.0, 2.5, rb), 1.5 - 1.25 - 0.875);
}

/* Tree 0 at the origin; 1 east at 2, 4 south at 2.5, 2 north at 3, 3 west at 4. */
static const double X5[5] = {0.0, 2.0, 0.0, -4.0, 0.0};
static const double Y5[5] = {0.0, 0.0, 3.0, 0.0, -2.5};
static void five(double r[5 * CROWN_NSEC])
{
    const double rad[5] = {0.5, 0.7, 0.9, 1.1, 0.3};
    for (int i = 0; i < 5; i++) fill(r + i * CROWN_NSEC, rad[i]);
}

static void test_knn_orders_by_stem_distance(void **st)
{
    (void)st;
    assert_int_equal(est_knn(X5, Y5, 5, 0, 1), 1);
    assert_int_equal(est_knn(X5, Y5, 5, 0, 2), 4);
    assert_int_equal(est_knn(X5, Y5, 5, 0, 3), 2);
    assert_int_equal(est_knn(X5, Y5, 5, 0, 5), -1);
}

static void test_knn_clearance_three_neighbours_by_hand(void **st)
{
    (void)st;
    double r[5 * CROWN_NSEC], g;
    five(r);
    assert_int_equal(est_knn_clearance(X5, Y5, r, 5, 0, 1, &g), CS_OK);
    ASSERT_NEAR(g, 2.0 - 0.5 - 0.7, 1e-15);
    assert_int_equal(est_knn_clearance(X5, Y5, r, 5, 0, 2, &g), CS_OK);
    ASSERT_NEAR(g, 2.5 - 0.5 - 0.3, 1e-15);
    assert_int_equal(est_knn_clearance(X5, Y5, r, 5, 0, 3, &g), CS_OK);
    ASSERT_NEAR(g, 3.0 - 0.5 - 0.9, 1e-15);
    assert_int_equal(est_knn_clearance(X5, Y5, r, 2, 0, 2, &g), CS_EINPUT);
}

static void test_knn_ties_go_to_the_lower_index(void **st)
{
    (void)st;
    double x[3] = {0.0, 1.0, -1.0}, y[3] = {0.0, 0.0, 0.0};
    assert_int_equal(est_knn(x, y, 3, 0, 1), 1);
    assert_int_equal(est_knn(x, y, 3, 0, 2), 2);
}

static void test_cardinal_gaps_and_tree_mean(void **st)
{
    (void)st;
    double r[5 * CROWN_NSEC], gaps[4];
    five(r);
    est_cardinal_gaps(X5, Y5, r, 5, 0, gaps);
    ASSERT_NEAR(gaps[EST_E], 0.8, 1e-15);
    ASSERT_NEAR(gaps[EST_N], 1.6, 1e-15);
    ASSERT_NEAR(gaps[EST_W], 2.4, 1e-15);
    ASSERT_NEAR(gaps[EST_S], 1.7, 1e-15);
    ASSERT_NEAR(est_tree_mean(gaps), 1.625, 1e-15);
    double a = 0.0;
    assert_int_equal(est_anisotropy(gaps, &a), 1);
    ASSERT_NEAR(a, 3.0, 1e-14);
    /* Tree 3 (west end) has nobody to its west: NaN, and it is excluded. */
    est_cardinal_gaps(X5, Y5, r, 5, 3, gaps);
    assert_true(isnan(gaps[EST_W]));
    assert_int_equal(est_anisotropy(gaps, &a), 0);
}

static void test_cardinal_gap_takes_the_smallest_in_the_cone(void **st)
{
    (void)st;
    /* Two trees east of 0 within +-45 deg: a far big crown and a near small one. */
    double x[3] = {0.0, 3.0, 5.0}, y[3] = {0.0, 2.0, -1.0}, r[3 * CROWN_NSEC], gaps[4];
    fill(r, 1.0);
    fill(r + CROWN_NSEC, 0.2);
    fill(r + 2 * CROWN_NSEC, 3.5);
    est_cardinal_gaps(x, y, r, 3, 0, gaps);
    ASSERT_NEAR(gaps[EST_E], hypot(5.0, 1.0) - 1.0 - 3.5, 1e-14);
    assert_true(isnan(gaps[EST_N]));
}

static void test_anisotropy_excludes_nonpositive_gaps(void **st)
{
    (void)st;
    double gaps[4] = {0.3, -0.01, 0.5, 0.2}, a = 7.0;
    assert_int_equal(est_anisotropy(gaps, &a), 0);
    ASSERT_EXACT(a, 7.0);
}

static void test_elongation_of_an_oval(void **st)
{
    (void)st;
    double r[CROWN_NSEC];
    fill(r, 0.7);
    r[0] = 1.0; r[12] = 1.2; r[6] = 0.6; r[18] = 0.8;
    /* Axes E-W 2.2, N-S 1.4, every other 0.7 + 0.7 = 1.4: both readings agree. */
    ASSERT_NEAR(est_elongation(r), 2.2 / 1.4, 1e-15);
    ASSERT_NEAR(est_elongation_cardinal(r), 2.2 / 1.4, 1e-15);
    /* The same oval turned 45 degrees (long axis NE-SW, sectors 3 and 15): the
     * cardinal axes are both 1.4, only the all-axis reading sees it. */
    fill(r, 0.7);
    r[3] = 1.0; r[15] = 1.2; r[9] = 0.6; r[21] = 0.8;
    ASSERT_NEAR(est_elongation(r), 2.2 / 1.4, 1e-15);
    ASSERT_EXACT(est_elongation_cardinal(r), 1.0);
}

static void test_w1_of_a_shift_is_the_shift(void **st)
{
    (void)st;
    double a[7] = {0.3, -1.2, 2.5, 0.0, 0.7, 0.71, 4.0}, b[7];
    for (int i = 0; i < 7; i++) b[i] = a[i] - 0.37;
    double w = 0.0;
    assert_int_equal(est_w1(a, 7, b, 7, &w), CS_OK);
    ASSERT_NEAR(w, 0.37, 1e-15);
}

static void test_w1_different_sizes_by_hand(void **st)
{
    (void)st;
    /* Quantile functions: a = 0 on [0,1/2), 1 on [1/2,1); b = 0, 0.5, 3 on thirds.
     * |diff|: 0 on [0,1/3), 0.5 on [1/3,2/3), 2 on [2/3,1) -> 0 + 1/6 + 2/3 = 5/6. */
    double a[2] = {1.0, 0.0}, b[3] = {3.0, 0.0, 0.5}, w = 0.0;
    assert_int_equal(est_w1(a, 2, b, 3, &w), CS_OK);
    ASSERT_NEAR(w, 5.0 / 6.0, 1e-15);
    assert_int_equal(est_w1(b, 3, a, 2, &w), CS_OK);
    ASSERT_NEAR(w, 5.0 / 6.0, 1e-15);
}

static void test_w1_rejects_empty_and_nonfinite(void **st)
{
    (void)st;
    double a[2] = {1.0, NAN}, w;
    assert_int_equal(est_w1(a, 0, a, 1, &w), CS_EINPUT);
    assert_int_equal(est_w1(a, 2, a, 1, &w), CS_EINPUT);
}

static void test_cover_of_one_disk(void **st)
{
    (void)st;
    double x = 0.0, y = 0.0, r[CROWN_NSEC], c = 0.0;
    fill(r, 1.0);
    assert_int_equal(est_cover(&x, &y, r, 1, -2.0, -2.0, 2.0, 2.0, &c), CS_OK);
    ASSERT_NEAR(c, CROWN_PI / 16.0, 2e-3);
    fill(r, 10.0);
    assert_int_equal(est_cover(&x, &y, r, 1, -2.0, -2.0, 2.0, 2.0, &c), CS_OK);
    ASSERT_EXACT(c, 1.0);
}

static void test_spread_is_the_iqr(void **st)
{
    (void)st;
    double g[5] = {0.4, 0.1, 0.9, 0.2, 0.3}, q = 0.0, m = 0.0;
    assert_int_equal(est_spread(g, 5, &q), CS_OK);
    ASSERT_NEAR(q, 0.2, 1e-15);
    assert_int_equal(est_median(g, 5, &m), CS_OK);
    ASSERT_EXACT(m, 0.3);
}

static void test_directional_summary_of_the_hand_built_stand(void **st)
{
    (void)st;
    double r[5 * CROWN_NSEC];
    five(r);
    unsigned char use[5] = {1, 0, 0, 1, 0};
    est_directional d;
    assert_int_equal(est_directional_summary(X5, Y5, r, 5, use, &d), CS_OK);
    /* Tree 3 has nobody to its west: incomplete, left out. Tree 0 only. */
    assert_int_equal(d.trees, 1);
    assert_int_equal(d.incomplete, 1);
    assert_int_equal(d.aniso_excluded, 0);
    ASSERT_NEAR(d.tree_mean_median, 1.625, 1e-15);
    /* IQR of {0.8, 1.6, 1.7, 2.4} with GSL's interpolation: 1.875 - 1.4. */
    ASSERT_NEAR(d.spread, 0.475, 1e-14);
    ASSERT_NEAR(d.aniso_median, 3.0, 1e-14);
    ASSERT_EXACT(d.elong_median, 1.0);
    ASSERT_EXACT(d.elong_cardinal_median, 1.0);
    unsigned char none[5] = {0, 0, 0, 0, 0};
    assert_int_equal(est_directional_summary(X5, Y5, r, 5, none, &d), CS_EINPUT);
}

/* Square crown of half-width hw rotated by alpha: r(theta) = hw / max(|cos|,
 * |sin|)(theta - alpha) at the 24 sector centres. */
static void square(double *r, double hw, double alpha)
{
    for (int s = 0; s < CROWN_NSEC; s++) {
        double u = crown_theta(s) - alpha;
        r[s] = hw / fmax(fabs(cos(u)), fabs(sin(u)));
    }
}

/* design.md §5: elongation over the 12 axes r(theta_s) + r(theta_s + pi).
 * For a square the shortest axis is the side-to-side width 2 hw and the longest
 * the diagonal 2 sqrt(2) hw. At 0, 15 and 30 degrees both directions fall on
 * sector centres (they are 15 degrees apart): the diagonal at 45, 60, 75
 * degrees (sectors 3, 4, 5), the width at 0, 15, 30 (sectors 0, 1, 2). So the
 * all-axis reading is sqrt(2) up to rounding of cos/sin and two divisions
 * (a few ulp of ~1.4, i.e. < 1e-15); tolerance 1e-14. The two cardinal axes of
 * a square are equal at any rotation (90 degree symmetry): the cardinal
 * reading is 1, same tolerance. */
static void test_elongation_of_a_square_is_sqrt2_over_all_axes_and_1_over_the_cardinal_two(void **st)
{
    (void)st;
    const double deg[3] = {0.0, 15.0, 30.0};
    for (int k = 0; k < 3; k++) {
        double r[CROWN_NSEC];
        square(r, 1.7, deg[k] * CROWN_PI / 180.0);
        double all = est_elongation(r), card = est_elongation_cardinal(r);
        print_message("square rotated %g deg: all-axis %.17g (expected %.17g), cardinal %.17g (expected 1)\n",
                      deg[k], all, sqrt(2.0), card);
        ASSERT_NEAR(all, sqrt(2.0), 1e-14);
        ASSERT_NEAR(card, 1.0, 1e-14);
    }
}

/* Axis lengths are piecewise linear between sector centres (both ends of an
 * axis interpolate over sectors 12 apart), so no finer axis is longer or
 * shorter than the 12 on sector centres: a 4800-axis sweep through
 * crown_radius_at gives the same ratio, for lobed crowns of every k. */
static void test_elongation_twelve_axes_equal_a_fine_sweep(void **st)
{
    (void)st;
    for (int k = 2; k <= 5; k++) {
        crown_draw c = {.h = 25.0, .R = 3.1, .a = 0.17, .k = k, .phi = 0.3 * k};
        double r[CROWN_NSEC];
        crown_target(&c, r);
        r[5] *= 1.3; /* an odd bump so the extremes are not symmetric */
        double lo = INFINITY, hi = 0.0;
        for (int q = 0; q < 4800; q++) {
            double th = CROWN_PI * (double)q / 4800.0;
            double ax = crown_radius_at(r, th) + crown_radius_at(r, th + CROWN_PI);
            if (ax < lo) lo = ax;
            if (ax > hi) hi = ax;
        }
        ASSERT_NEAR(est_elongation(r), hi / lo, 1e-12);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_clearance_two_trees_by_hand),
        cmocka_unit_test(test_clearance_is_negative_when_crowns_interpenetrate),
        cmocka_unit_test(test_knn_orders_by_stem_distance),
        cmocka_unit_test(test_knn_clearance_three_neighbours_by_hand),
        cmocka_unit_test(test_knn_ties_go_to_the_lower_index),
        cmocka_unit_test(test_cardinal_gaps_and_tree_mean),
        cmocka_unit_test(test_cardinal_gap_takes_the_smallest_in_the_cone),
        cmocka_unit_test(test_anisotropy_excludes_nonpositive_gaps),
        cmocka_unit_test(test_elongation_of_an_oval),
        cmocka_unit_test(test_elongation_of_a_square_is_sqrt2_over_all_axes_and_1_over_the_cardinal_two),
        cmocka_unit_test(test_elongation_twelve_axes_equal_a_fine_sweep),
        cmocka_unit_test(test_w1_of_a_shift_is_the_shift),
        cmocka_unit_test(test_w1_different_sizes_by_hand),
        cmocka_unit_test(test_w1_rejects_empty_and_nonfinite),
        cmocka_unit_test(test_cover_of_one_disk),
        cmocka_unit_test(test_spread_is_the_iqr),
        cmocka_unit_test(test_directional_summary_of_the_hand_built_stand),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
