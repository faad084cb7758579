/* Tests for src/forest/crown.c: interpolation rule, lobed targets, draw ranges. */
#include "testutil.h"
#include "crown.h"
#include <gsl/gsl_rng.h>
#include <string.h>

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


/* The default distribution reproduces crown_draw_n bit for bit (the frozen
 * stands were drawn with it), and a changed one changes only its own field. */
static void test_default_dist_draws_bit_identical(void **st)
{
    (void)st;
    gsl_rng *a = gsl_rng_alloc(gsl_rng_mt19937), *b = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(a, 777);
    gsl_rng_set(b, 777);
    crown_draw da[300], db[300];
    memset(da, 0, sizeof da); /* padding bytes compare equal */
    memset(db, 0, sizeof db);
    crown_dist cd;
    crown_dist_default(&cd);
    assert_int_equal(crown_draw_n(a, 300, da), CS_OK);
    assert_int_equal(crown_draw_n_dist(b, 300, &cd, db), CS_OK);
    assert_memory_equal(da, db, sizeof da);
    /* NULL is the default too */
    gsl_rng_set(b, 777);
    assert_int_equal(crown_draw_n_dist(b, 300, NULL, db), CS_OK);
    assert_memory_equal(da, db, sizeof da);
    gsl_rng_free(a);
    gsl_rng_free(b);
}

static void test_dist_fields_act(void **st)
{
    (void)st;
    gsl_rng *a = gsl_rng_alloc(gsl_rng_mt19937), *b = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(a, 99);
    gsl_rng_set(b, 99);
    crown_draw da[500], db[500];
    crown_dist cd;
    crown_dist_default(&cd);
    cd.R_scale = 5.0;   /* R scales exactly */
    cd.a_max = 0.3;     /* a scales exactly */
    assert_int_equal(crown_draw_n(a, 500, da), CS_OK);
    assert_int_equal(crown_draw_n_dist(b, 500, &cd, db), CS_OK);
    for (int i = 0; i < 500; i++) {
        ASSERT_NEAR(db[i].R, da[i].R * 5.0 / 4.0, 1e-12);
        ASSERT_NEAR(db[i].a, da[i].a * 0.3 / 0.2, 1e-12);
        ASSERT_EXACT(db[i].h, da[i].h);
        assert_int_equal(db[i].k, da[i].k);
    }
    /* a wider height spread stays inside the truncation bounds */
    crown_dist_default(&cd);
    cd.h_sd = 6.0;
    gsl_rng_set(b, 99);
    assert_int_equal(crown_draw_n_dist(b, 500, &cd, db), CS_OK);
    double s2 = 0.0;
    for (int i = 0; i < 500; i++) {
        assert_true(db[i].h >= 12.0 && db[i].h <= 38.0);
        s2 += (db[i].h - 25.0) * (db[i].h - 25.0);
    }
    assert_true(sqrt(s2 / 500.0) > 4.5);
    /* a bad distribution is refused, never drawn */
    cd.h_sd = -1.0;
    assert_int_equal(crown_draw_n_dist(b, 5, &cd, db), CS_EINPUT);
    gsl_rng_free(a);
    gsl_rng_free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_radius_at_sector_centres_is_the_sector_value),
        cmocka_unit_test(test_radius_between_centres_is_linear_in_angle),
        cmocka_unit_test(test_radius_wraps_periodically),
        cmocka_unit_test(test_lobed_target_follows_eq1),
        cmocka_unit_test(test_draws_stay_in_their_ranges),
        cmocka_unit_test(test_default_dist_draws_bit_identical),
        cmocka_unit_test(test_dist_fields_act),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
