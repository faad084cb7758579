/* Tests for src/model/patch.c: neighbour order, features and conditions, the global
 * standardisation, r(theta) interpolation, clearance (paper Eq. 5) and the
 * check against a reference estimator passed by pointer. */
#include "testutil.h"
#include "patch.h"
#include "estimator.h"
#include <gsl/gsl_rng.h>

/* Independent reference for the check: bracket the bearing by sector index. */
static double ref_r(const double *r, double th)
{
    double step = 2 * M_PI / 24;
    while (th < 0) th += 2 * M_PI;
    while (th >= 2 * M_PI) th -= 2 * M_PI;
    int s = (int)floor(th / step);
    if (s > 23) s = 23;
    double f = (th - s * step) / step;
    return r[s] + f * (r[(s + 1) % 24] - r[s]);
}
static double ref_clear(double xi, double yi, const double *ri, double xj, double yj, const double *rj)
{
    double t = atan2(yj - yi, xj - xi);
    return sqrt((xj - xi) * (xj - xi) + (yj - yi) * (yj - yi)) - ref_r(ri, t) - ref_r(rj, t + M_PI);
}
static double bad_ref(double xi, double yi, const double *ri, double xj, double yj, const double *rj)
{
    return ref_clear(xi, yi, ri, xj, yj, rj) + 2e-6;
}

enum { SIDE = 7, NS = SIDE * SIDE };
static double X[NS], Y[NS], R[NS * 24], H[NS];

static void toy(unsigned seed, double d)
{
    gsl_rng *g = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(g, seed);
    patch_toy_stand(g, SIDE, d, X, Y, R);
    for (int i = 0; i < NS; i++) H[i] = 20 + i % 11;
    gsl_rng_free(g);
}

static void test_neighbours_focal_first_then_by_distance(void **s)
{
    (void)s;
    toy(1, 4.0);
    patch_stand st;
    assert_int_equal(patch_stand_init(&st, NS, X, Y, R, H, 4.0), CS_OK);
    int idx[PATCH_T];
    int focal = 3 * SIDE + 3;
    assert_int_equal(patch_neighbours(&st, focal, idx), CS_OK);
    assert_int_equal(idx[0], focal);
    double prev = 0;
    for (int k = 1; k < PATCH_T; k++) {
        double d = hypot(X[idx[k]] - X[focal], Y[idx[k]] - Y[focal]);
        assert_true(d >= prev);
        prev = d;
    }
    /* no stem outside the patch is closer than the farthest patch stem */
    for (int i = 0; i < NS; i++) {
        int in = 0;
        for (int k = 0; k < PATCH_T; k++) in |= idx[k] == i;
        if (!in) assert_true(hypot(X[i] - X[focal], Y[i] - Y[focal]) >= prev);
    }
}

static void test_ties_are_broken_by_index(void **s)
{
    (void)s;
    /* exact lattice: many equal distances */
    static double x[36], y[36], r[36 * 24];
    for (int i = 0; i < 36; i++) { x[i] = i % 6; y[i] = i / 6; }
    for (int i = 0; i < 36 * 24; i++) r[i] = 0.3;
    patch_stand st;
    assert_int_equal(patch_stand_init(&st, 36, x, y, r, NULL, 1.0), CS_OK);
    int idx[PATCH_T];
    assert_int_equal(patch_neighbours(&st, 14, idx), CS_OK); /* (2,2) */
    int expect[5] = {14, 8, 13, 15, 20};                      /* distance 1, ascending index */
    for (int k = 0; k < 5; k++) assert_int_equal(idx[k], expect[k]);
}

static void test_features_conditions_and_deviations(void **s)
{
    (void)s;
    const double d = 5.0;
    toy(2, d);
    patch_stand st;
    assert_int_equal(patch_stand_init(&st, NS, X, Y, R, H, d), CS_OK);
    patch p;
    int focal = 24;
    assert_int_equal(patch_build(&st, focal, &p), CS_OK);
    for (int k = 0; k < PATCH_T; k++) {
        int i = p.idx[k];
        ASSERT_NEAR(p.feat[k * PATCH_NFEAT + 0], (X[i] - X[focal]) / d, 1e-6);
        ASSERT_NEAR(p.feat[k * PATCH_NFEAT + 1], (Y[i] - Y[focal]) / d, 1e-6);
        double m = 0, sdev = 0;
        for (int j = 0; j < 24; j++) m += R[i * 24 + j];
        m /= 24;
        ASSERT_NEAR(p.feat[k * PATCH_NFEAT + 2], m / d, 1e-6);
        for (int j = 0; j < 24; j++) sdev += p.dev[k * 24 + j];
        ASSERT_NEAR(sdev, 0.0, 1e-12);
        ASSERT_NEAR(p.dev[k * 24 + 5], R[i * 24 + 5] - m, 1e-12);
    }
    ASSERT_NEAR(p.cond[0], 1.0, 1e-7);           /* d / 5 m */
    assert_true(p.cond[1] > 0.5 && p.cond[1] < 2.0); /* density * d^2 near 1 on a lattice */
    assert_true(p.cond[2] > 0.6 && p.cond[2] < 1.1); /* mean NN distance / d */
    ASSERT_NEAR(p.cond[4], 24.0 / 25.0, 1e-7);   /* median of 20 + i % 11, i < 49, is 24 */
}

static void test_stand_rejects_bad_input(void **s)
{
    (void)s;
    toy(3, 4.0);
    patch_stand st;
    assert_int_equal(patch_stand_init(&st, 10, X, Y, R, NULL, 4.0), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "stems"));
    double keep = R[30];
    R[30] = NAN;
    assert_int_equal(patch_stand_init(&st, NS, X, Y, R, NULL, 4.0), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "crown 1 sector 6"));
    R[30] = keep;
    assert_int_equal(patch_stand_init(&st, NS, X, Y, R, NULL, 0.0), CS_EINPUT);
}

static void test_radius_interpolates_periodically(void **s)
{
    (void)s;
    double r[24];
    for (int k = 0; k < 24; k++) r[k] = 1 + k;
    for (int k = 0; k < 24; k++) ASSERT_NEAR(patch_radius_at(r, 2 * M_PI * k / 24), r[k], 1e-12);
    ASSERT_NEAR(patch_radius_at(r, 2 * M_PI * 2.5 / 24), 3.5, 1e-12);
    ASSERT_NEAR(patch_radius_at(r, 2 * M_PI * 23.5 / 24), 12.5, 1e-12); /* between sector 23 and 0 */
    ASSERT_NEAR(patch_radius_at(r, -2 * M_PI * 0.5 / 24), 12.5, 1e-12);
    ASSERT_NEAR(patch_radius_at(r, 2 * M_PI), 1.0, 1e-12);
}

static void test_clearance_of_two_circles(void **s)
{
    (void)s;
    double a[24], b[24];
    for (int k = 0; k < 24; k++) { a[k] = 1.0; b[k] = 1.5; }
    ASSERT_NEAR(patch_clearance(0, 0, a, 3, 4, b), 2.5, 1e-12);
    b[12] = 0.5; /* sector 12 of b faces west, toward a at (0,0) from (3,0) */
    ASSERT_NEAR(patch_clearance(0, 0, a, 3, 0, b), 1.5, 1e-12);
}

static void build_set(patch_set **ps, unsigned seed, int npatch)
{
    toy(seed, 4.5);
    patch_stand st;
    assert_int_equal(patch_stand_init(&st, NS, X, Y, R, H, 4.5), CS_OK);
    assert_int_equal(patch_set_alloc(ps, 1), CS_OK); /* grows */
    patch p;
    for (int k = 0; k < npatch; k++) {
        assert_int_equal(patch_build(&st, 8 + k, &p), CS_OK);
        assert_int_equal(patch_set_add(*ps, &p), CS_OK);
    }
}

static void test_standardise_gives_unit_rms_and_radii_round_trip(void **s)
{
    (void)s;
    patch_set *ps;
    build_set(&ps, 4, 5);
    double rms = patch_set_rms(ps);
    assert_true(rms > 0);
    double r0 = ps->rbar[2 * 24 + 3] + ps->x1[(2 * 24 + 3) * 24 + 7];
    assert_int_equal(patch_set_standardise(ps, rms), CS_OK);
    ASSERT_NEAR(patch_set_rms(ps), 1.0, 1e-6);
    double r[24 * 24];
    patch_set_radii(ps, 2, ps->x1 + 2 * 24 * 24, r);
    ASSERT_NEAR(r[3 * 24 + 7], r0, 1e-6);
    assert_int_equal(patch_set_standardise(ps, rms), CS_EINVARIANT);
    patch_set_free(ps);
}

static void set_radii(patch_set *ps, double *r)
{
    for (int k = 0; k < ps->n; k++)
        for (int t = 0; t < 24; t++)
            for (int j = 0; j < 24; j++)
                r[(k * 24 + t) * 24 + j] = ps->rbar[k * 24 + t] + ps->x1[(k * 24 + t) * 24 + j];
}

static void test_check_passes_against_reference_and_focal_clearances_agree(void **s)
{
    (void)s;
    patch_set *ps;
    build_set(&ps, 5, 6);
    double *r = malloc(sizeof(double) * ps->n * 24 * 24), diff = -1, g[6 * 3];
    set_radii(ps, r);
    assert_int_equal(patch_clearance_check(ref_clear, ps->px, ps->py, r, ps->n, &diff), CS_OK);
    assert_true(diff >= 0 && diff <= 1e-9);
    assert_int_equal(patch_focal_clearances(ps->px, ps->py, r, ps->n, 3, g), CS_OK);
    for (int k = 0; k < ps->n; k++)
        for (int j = 1; j <= 3; j++)
            ASSERT_NEAR(g[k * 3 + j - 1],
                        ref_clear(ps->px[k * 24], ps->py[k * 24], r + k * 576, ps->px[k * 24 + j], ps->py[k * 24 + j],
                                  r + (k * 24 + j) * 24),
                        1e-9);
    free(r);
    patch_set_free(ps);
}

/* The canonical estimator (src/forest/estimator.c, pinned) and the batched copy agree
 * within 1e-6 m on every pair of toy patches (design.md §5, paper §4.3). */
static void test_batched_clearance_agrees_with_canonical_estimator(void **s)
{
    (void)s;
    patch_set *ps;
    build_set(&ps, 9, 12);
    double *r = malloc(sizeof(double) * ps->n * 24 * 24), diff = -1;
    set_radii(ps, r);
    assert_int_equal(patch_clearance_check(est_clearance, ps->px, ps->py, r, ps->n, &diff), CS_OK);
    print_message("batched vs canonical clearance: max |diff| %.3g m over %d patches\n", diff, ps->n);
    assert_true(diff <= 1e-6);
    free(r);
    patch_set_free(ps);
}

static void test_check_rejects_a_disagreeing_estimator(void **s)
{
    (void)s;
    patch_set *ps;
    build_set(&ps, 6, 2);
    double *r = malloc(sizeof(double) * ps->n * 24 * 24);
    set_radii(ps, r);
    assert_int_equal(patch_clearance_check(bad_ref, ps->px, ps->py, r, ps->n, NULL), CS_EINVARIANT);
    assert_non_null(strstr(cs_errmsg(), "disagrees with the canonical estimator"));
    assert_int_equal(patch_clearance_check(NULL, ps->px, ps->py, r, ps->n, NULL), CS_EINVARIANT);
    free(r);
    patch_set_free(ps);
}

static void test_shuffled_geometry_permutes_positions_only(void **s)
{
    (void)s;
    patch_set *ps;
    build_set(&ps, 10, 3);
    size_t nf = (size_t)ps->n * 24 * PATCH_NFEAT;
    float *f = malloc(sizeof(float) * nf);
    memcpy(f, ps->feat, sizeof(float) * nf);
    gsl_rng *g = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(g, 4);
    patch_shuffle_positions(f, ps->n, g);
    gsl_rng_free(g);
    int moved = 0;
    for (int k = 0; k < ps->n; k++) {
        double sx = 0, sx0 = 0;
        for (int i = 0; i < 24; i++) {
            const float *a = f + (k * 24 + i) * PATCH_NFEAT, *b = ps->feat + (k * 24 + i) * PATCH_NFEAT;
            ASSERT_EXACT(a[PATCH_FEAT_RBAR], b[PATCH_FEAT_RBAR]); /* rbar stays with its token */
            moved += a[0] != b[0];
            sx += a[0]; sx0 += b[0];
        }
        ASSERT_NEAR(sx, sx0, 1e-4); /* the same positions, permuted */
    }
    assert_true(moved > 24);
    free(f);
    patch_set_free(ps);
}

/* Rotation probe: positions and bearings turn about the focal stem; a
 * patch turned by alpha reads like a patch built from turned stems. */
static void test_rotation_turns_positions_and_bearings(void **s)
{
    (void)s;
    patch_set *ps;
    build_set(&ps, 10, 2);
    size_t nf = (size_t)ps->n * 24 * PATCH_NFEAT;
    float *f = malloc(sizeof(float) * nf);
    memcpy(f, ps->feat, sizeof(float) * nf);
    double al[2] = {patch_rotation_angle(0), patch_rotation_angle(5)};
    ASSERT_NEAR(al[0], M_PI / 4, 1e-15);
    ASSERT_NEAR(al[1], 6 * M_PI / 4, 1e-15);
    ASSERT_NEAR(patch_rotation_angle(7), M_PI / 4, 1e-15);
    patch_rotate_positions(f, ps->n, al);
    for (int k = 0; k < ps->n; k++)
        for (int i = 0; i < 24; i++) {
            const float *a = f + (k * 24 + i) * PATCH_NFEAT, *b = ps->feat + (k * 24 + i) * PATCH_NFEAT;
            double x = b[0], y = b[1], c = cos(al[k]), sn = sin(al[k]);
            ASSERT_NEAR(a[0], c * x - sn * y, 1e-6);
            ASSERT_NEAR(a[1], sn * x + c * y, 1e-6);
            ASSERT_EXACT(a[PATCH_FEAT_RBAR], b[PATCH_FEAT_RBAR]);
            ASSERT_EXACT(a[11], b[11]);
            if (i == 0) { for (int q = 3; q < 11; q++) ASSERT_EXACT(a[q], 0.f); continue; }
            double phi = atan2(y, x) + al[k];
            for (int h = 1; h <= 4; h++) {
                ASSERT_NEAR(a[1 + 2 * h], cos(h * phi), 1e-5);
                ASSERT_NEAR(a[2 + 2 * h], sin(h * phi), 1e-5);
            }
        }
    free(f);
    patch_set_free(ps);
}

static void test_crown_rotation_shifts_sectors(void **s)
{
    (void)s;
    double r[24], o[24], back[24];
    for (int i = 0; i < 24; i++) r[i] = 1.0 + 0.1 * i;
    patch_rotate_crown(r, 3, o);
    for (int i = 0; i < 24; i++) ASSERT_EXACT(o[(i + 3) % 24], r[i]);
    /* r'(theta) = r(theta - 45 deg) */
    ASSERT_NEAR(patch_radius_at(o, 0.3 + M_PI / 4), patch_radius_at(r, 0.3), 1e-12);
    patch_rotate_crown(o, -3, back);
    for (int i = 0; i < 24; i++) ASSERT_EXACT(back[i], r[i]);
}

static void test_shuffle_perm_is_the_probe_permutation(void **s)
{
    (void)s;
    patch_set *ps;
    build_set(&ps, 10, 1);
    float f[24 * PATCH_NFEAT];
    memcpy(f, ps->feat, sizeof f);
    gsl_rng *g = gsl_rng_alloc(gsl_rng_mt19937), *h = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(g, 9); gsl_rng_set(h, 9);
    patch_shuffle_positions(f, 1, g);
    int perm[24];
    patch_shuffle_perm(h, perm);
    for (int i = 0; i < 24; i++) ASSERT_EXACT(f[i * PATCH_NFEAT], ps->feat[perm[i] * PATCH_NFEAT]);
    gsl_rng_free(g); gsl_rng_free(h);
    patch_set_free(ps);
}

static void test_direction_blind_is_circular_mean(void **s)
{
    (void)s;
    double r[2 * 24], o[2 * 24];
    for (int i = 0; i < 48; i++) r[i] = 1.0 + (i % 24) * 0.01 + (i / 24);
    patch_direction_blind(r, 2, o);
    for (int s2 = 0; s2 < 24; s2++) { ASSERT_NEAR(o[s2], 1.115, 1e-12); ASSERT_NEAR(o[24 + s2], 2.115, 1e-12); }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_neighbours_focal_first_then_by_distance),
        cmocka_unit_test(test_ties_are_broken_by_index),
        cmocka_unit_test(test_features_conditions_and_deviations),
        cmocka_unit_test(test_stand_rejects_bad_input),
        cmocka_unit_test(test_radius_interpolates_periodically),
        cmocka_unit_test(test_clearance_of_two_circles),
        cmocka_unit_test(test_standardise_gives_unit_rms_and_radii_round_trip),
        cmocka_unit_test(test_check_passes_against_reference_and_focal_clearances_agree),
        cmocka_unit_test(test_batched_clearance_agrees_with_canonical_estimator),
        cmocka_unit_test(test_check_rejects_a_disagreeing_estimator),
        cmocka_unit_test(test_shuffled_geometry_permutes_positions_only),
        cmocka_unit_test(test_direction_blind_is_circular_mean),
        cmocka_unit_test(test_rotation_turns_positions_and_bearings),
        cmocka_unit_test(test_crown_rotation_shifts_sectors),
        cmocka_unit_test(test_shuffle_perm_is_the_probe_permutation),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
