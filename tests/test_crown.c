/* Tests for src/forest/crown.c: interpolation rule, lobed targets, draw ranges. */
#include "testutil.h"
#include "crown.h"
#include <gsl/gsl_rng.h>

static void ramp(double r[CROWN_NSEC]) { for (int s = 0; s < CROWN_NSEC; s++) r[s] = 1.0 + 0.1 * s; }

static void test_radius_at_sector_centres_is_the_sector_value(void **st)
{
    (void)st;
    double r[CROWN_NSEC];
    ramp(r);
    ASSERT_NEAR(crown_radius_at(r, crown_theta(6)), 1.6, 1e-15);
    ASSERT_EXACT(crown_radius_at(r, 0.0), 1.0);
}

static void test_radius_between_centres_is_linear_in_angle(void **st)
{
    (void)st;
    double r[CROWN_NSEC];
    ramp(r);
    /* A quarter of the way from sector 3 to sector 4. */
    ASSERT_NEAR(crown_radius_at(r, (3.25) * CROWN_DTHETA), 1.325, 1e-14);
}

static void test_radius_wraps_periodically(void **st)
{
    (void)st;
    double r[CROWN_NSEC];
    ramp(r);
    /* Halfway between sector 23 (3.3) and sector 0 (1.0), reached from both sides. */
    ASSERT_NEAR(crown_radius_at(r, 23.5 * CROWN_DTHETA), 2.15, 1e-14);
    ASSERT_NEAR(crown_radius_at(r, -0.5 * CROWN_DTHETA), 2.15, 1e-14);
    ASSERT_NEAR(crown_radius_at(r, 2.0 * CROWN_PI + 3.25 * CROWN_DTHETA), 1.325, 1e-13);
}

static void test_lobed_target_follows_eq1(void **st)
{
    (void)st;
    crown_draw c = {.h = 20.0, .R = 3.7, .a = 0.13, .k = 3, .phi = 0.4};
    double t[CROWN_NSEC];
    crown_target(&c, t);
    for (int s = 0; s < CROWN_NSEC; s++)
        ASSERT_NEAR(t[s], 3.7 * (1.0 + 0.13 * cos(3.0 * 2.0 * CROWN_PI * s / 24.0 + 0.4)), 1e-14);
    /* Sector 0: 3.7 (1 + 0.13 cos 0.4). */
    ASSERT_NEAR(t[0], 4.143030338115388, 1e-14);
}

static void test_draws_stay_in_their_ranges(void **st)
{
    (void)st;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, 12345);
    crown_draw d[2000];
    assert_int_equal(crown_draw_n(rng, 2000, d), CS_OK);
    double hs = 0.0;
    int kseen[6] = {0};
    for (int i = 0; i < 2000; i++) {
        assert_true(d[i].h >= 12.0 && d[i].h <= 38.0);
        assert_true(d[i].R > 0.0);
        assert_true(d[i].a >= 0.0 && d[i].a < 0.2);
        assert_true(d[i].k >= 2 && d[i].k <= 5);
        assert_true(d[i].phi >= 0.0 && d[i].phi < 2.0 * CROWN_PI);
        kseen[d[i].k]++;
        hs += d[i].h;
    }
    ASSERT_NEAR(hs / 2000.0, 25.0, 0.5);
    for (int k = 2; k <= 5; k++) assert_true(kseen[k] > 400);
    gsl_rng_free(rng);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_radius_at_sector_centres_is_the_sector_value),
        cmocka_unit_test(test_radius_between_centres_is_linear_in_angle),
        cmocka_unit_test(test_radius_wraps_periodically),
        cmocka_unit_test(test_lobed_target_follows_eq1),
        cmocka_unit_test(test_draws_stay_in_their_ranges),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
