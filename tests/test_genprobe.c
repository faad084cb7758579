/* Tests for the probes of what a generator uses (src/exp/genprobe.c,
 * src/base/probekind.c; design.md §8.4): each probe changes exactly what it
 * names in a patch's token features and nothing else, and the names parse. */
#include "testutil.h"
#include "genprobe.h"
#include "patch.h"
#include "probekind.h"
#include <gsl/gsl_rng.h>

/* One patch: token i on a lattice of unit spacing turned by 0.3 rad, at
 * lattice coordinates (u_i, v_i) ordered by distance from the focal stem,
 * each offset by a small jitter; sizes 0.5 + 0.01 i. */
static void lattice_patch(float *f, double jit)
{
    static const int uv[PATCH_T][2] = {
        {0, 0}, {1, 0}, {0, 1}, {-1, 0}, {0, -1}, {1, 1}, {-1, 1}, {-1, -1}, {1, -1}, {2, 0}, {0, 2}, {-2, 0},
        {0, -2}, {2, 1}, {1, 2}, {-1, 2}, {-2, 1}, {-2, -1}, {-1, -2}, {1, -2}, {2, -1}, {2, 2}, {-2, 2}, {-2, -2}};
    const double th = 0.3;
    memset(f, 0, sizeof(float) * PATCH_T * PATCH_NFEAT);
    for (int i = 0; i < PATCH_T; i++) {
        double u = uv[i][0], v = uv[i][1];
        double x = cos(th) * u - sin(th) * v, y = sin(th) * u + cos(th) * v;
        if (i) { x += jit * ((i * 7) % 5 - 2) / 2.0; y += jit * ((i * 3) % 5 - 2) / 2.0; }
        float *t = f + i * PATCH_NFEAT;
        t[0] = (float)x; t[1] = (float)y;
        t[PATCH_FEAT_RBAR] = (float)(0.5 + 0.01 * i);
        const double rho = hypot(x, y), phi = atan2(y, x);
        for (int h = 1; h <= 4; h++) {
            t[1 + 2 * h] = i ? (float)cos(h * phi) : 0.f;
            t[2 + 2 * h] = i ? (float)sin(h * phi) : 0.f;
        }
        t[11] = (float)rho;
    }
}

/* The lattice patch (jitter 0.05) in f, and in g the same patch after probe k:
 * every probe is judged by what it changed in g against f. */
static void probed_patch(probekind k, float *f, float *g, gsl_rng *r)
{
    lattice_patch(f, 0.05);
    memcpy(g, f, sizeof(float) * PATCH_T * PATCH_NFEAT);
    genprobe_apply(k, g, 1, r);
}

static void names_parse_both_ways(void **st)
{
    (void)st;
    for (int k = 0; k < PROBEKIND_N; k++) {
        probekind q;
        assert_int_equal(probekind_parse(probekind_name((probekind)k), &q), CS_OK);
        assert_int_equal(q, k);
    }
    probekind q;
    assert_int_equal(probekind_parse("rot30", &q), CS_EINPUT);
    assert_int_equal(probekind_has_teacher(PROBEKIND_ROT90), 1);
    assert_int_equal(probekind_has_teacher(PROBEKIND_SELF), 0);
}

static void rot90_turns_every_position_and_keeps_sizes(void **st)
{
    (void)st;
    float f[PATCH_T * PATCH_NFEAT], g[PATCH_T * PATCH_NFEAT];
    probed_patch(PROBEKIND_ROT90, f, g, NULL);
    for (int i = 0; i < PATCH_T; i++) {
        const float *a = f + i * PATCH_NFEAT, *b = g + i * PATCH_NFEAT;
        ASSERT_NEAR(b[0], -a[1], 1e-6);
        ASSERT_NEAR(b[1], a[0], 1e-6);
        ASSERT_EXACT(b[PATCH_FEAT_RBAR], a[PATCH_FEAT_RBAR]);
        ASSERT_NEAR(b[11], a[11], 1e-6);
        /* the bearing turned by 90 degrees: cos 4 phi unchanged, cos phi -> -sin phi */
        ASSERT_NEAR(b[3 + 2 * 3], a[3 + 2 * 3], 1e-5);
        if (i) ASSERT_NEAR(b[3], -a[4], 1e-5);
    }
}

static void nnswap_exchanges_the_nearest_with_the_second_to_fourth(void **st)
{
    (void)st;
    enum { N = 60 };
    static float f[N * PATCH_T * PATCH_NFEAT], g[N * PATCH_T * PATCH_NFEAT];
    for (int k = 0; k < N; k++) lattice_patch(f + (size_t)k * PATCH_T * PATCH_NFEAT, 0.05);
    memcpy(g, f, sizeof f);
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(r, 11);
    genprobe_apply(PROBEKIND_NNSWAP, g, N, r);
    gsl_rng_free(r);
    int seen[PATCH_T] = {0};
    for (int k = 0; k < N; k++) {
        const float *a = f + (size_t)k * PATCH_T * PATCH_NFEAT, *b = g + (size_t)k * PATCH_T * PATCH_NFEAT;
        int partner = -1;
        for (int j = 2; j < PATCH_T; j++)
            if (b[j * PATCH_NFEAT] != a[j * PATCH_NFEAT]) { assert_int_equal(partner, -1); partner = j; }
        assert_true(partner >= 2 && partner <= 4);
        seen[partner]++;
        for (int q = 0; q < PATCH_NFEAT; q++) {
            if (q == PATCH_FEAT_RBAR) { ASSERT_EXACT(b[PATCH_NFEAT + q], a[PATCH_NFEAT + q]); continue; }
            ASSERT_EXACT(b[PATCH_NFEAT + q], a[partner * PATCH_NFEAT + q]);
            ASSERT_EXACT(b[partner * PATCH_NFEAT + q], a[PATCH_NFEAT + q]);
        }
        for (int q = 0; q < PATCH_NFEAT; q++) ASSERT_EXACT(b[q], a[q]); /* the focal token untouched */
    }
    assert_true(seen[2] > 0 && seen[3] > 0 && seen[4] > 0);
}

/* De-jittered positions form an exact lattice of unit spacing through the
 * focal stem (every offset an integer combination of two orthonormal
 * vectors), turned within 0.01 rad of the true orientation; sizes kept. */
static void dejitter_snaps_to_the_lattice(void **st)
{
    (void)st;
    float f[PATCH_T * PATCH_NFEAT], clean[PATCH_T * PATCH_NFEAT];
    lattice_patch(f, 0.06);
    lattice_patch(clean, 0.0);
    genprobe_apply(PROBEKIND_DEJITTER, f, 1, NULL);
    const double th = atan2(f[PATCH_NFEAT + 1], f[PATCH_NFEAT]); /* token 1 sits at lattice (1, 0) */
    ASSERT_NEAR(th, 0.3, 0.01);
    for (int i = 0; i < PATCH_T; i++) {
        const double x = f[i * PATCH_NFEAT], y = f[i * PATCH_NFEAT + 1];
        const double u = cos(th) * x + sin(th) * y, v = -sin(th) * x + cos(th) * y;
        ASSERT_NEAR(u, nearbyint(u), 1e-5);
        ASSERT_NEAR(v, nearbyint(v), 1e-5);
        ASSERT_NEAR(x, clean[i * PATCH_NFEAT], 0.03);
        ASSERT_NEAR(y, clean[i * PATCH_NFEAT + 1], 0.03);
        ASSERT_NEAR(f[i * PATCH_NFEAT + 11], hypot(x, y), 1e-5);
        ASSERT_EXACT(f[i * PATCH_NFEAT + PATCH_FEAT_RBAR], clean[i * PATCH_NFEAT + PATCH_FEAT_RBAR]);
    }
    double sx, sy;
    genprobe_snap(1.2, -0.4, 0.0, &sx, &sy);
    ASSERT_EXACT(sx, 1.0);
    ASSERT_EXACT(sy, 0.0);
}

static void sizes_permute_the_neighbours_only(void **st)
{
    (void)st;
    float f[PATCH_T * PATCH_NFEAT], g[PATCH_T * PATCH_NFEAT];
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(r, 5);
    probed_patch(PROBEKIND_SIZES, f, g, r);
    gsl_rng_free(r);
    ASSERT_EXACT(g[PATCH_FEAT_RBAR], f[PATCH_FEAT_RBAR]);
    double sa = 0, sb = 0;
    int moved = 0;
    for (int i = 1; i < PATCH_T; i++) {
        sa += f[i * PATCH_NFEAT + PATCH_FEAT_RBAR];
        sb += g[i * PATCH_NFEAT + PATCH_FEAT_RBAR];
        moved += g[i * PATCH_NFEAT + PATCH_FEAT_RBAR] != f[i * PATCH_NFEAT + PATCH_FEAT_RBAR];
        for (int q = 0; q < PATCH_NFEAT; q++)
            if (q != PATCH_FEAT_RBAR) ASSERT_EXACT(g[i * PATCH_NFEAT + q], f[i * PATCH_NFEAT + q]);
    }
    ASSERT_NEAR(sb, sa, 1e-5);
    assert_true(moved > PATCH_T / 2);
}

static void none_and_self_leave_the_features(void **st)
{
    (void)st;
    float f[PATCH_T * PATCH_NFEAT], g[PATCH_T * PATCH_NFEAT];
    probed_patch(PROBEKIND_NONE, f, g, NULL);
    genprobe_apply(PROBEKIND_SELF, g, 1, NULL);
    assert_memory_equal(f, g, sizeof f);
}

int main(void)
{
    const struct CMUnitTest t[] = {
        cmocka_unit_test(names_parse_both_ways),
        cmocka_unit_test(rot90_turns_every_position_and_keeps_sizes),
        cmocka_unit_test(nnswap_exchanges_the_nearest_with_the_second_to_fourth),
        cmocka_unit_test(dejitter_snaps_to_the_lattice),
        cmocka_unit_test(sizes_permute_the_neighbours_only),
        cmocka_unit_test(none_and_self_leave_the_features),
    };
    return cmocka_run_group_tests(t, NULL, NULL);
}
