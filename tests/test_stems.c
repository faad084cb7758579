/* Tests for src/forest/stems.c and src/forest/stand.c: lattice, hard-core, interior, twins. */
#include "testutil.h"
#include "stems.h"
#include "stand.h"
#include "seed.h"

static void test_lattice_has_about_144_stems_and_is_repeatable(void **st)
{
    (void)st;
    stems *a = NULL, *b = NULL;
    assert_int_equal(stems_lattice_alloc(&a, 4.5, 54.0, 0.04, 99), CS_OK);
    assert_int_equal(stems_lattice_alloc(&b, 4.5, 54.0, 0.04, 99), CS_OK);
    /* Area / d^2 = 144 nodes on average; a rotated lattice gives a few more or less. */
    assert_true(a->n >= 130 && a->n <= 158);
    assert_int_equal(a->n, b->n);
    assert_memory_equal(a->x, b->x, a->n * sizeof(double));
    assert_memory_equal(a->y, b->y, a->n * sizeof(double));
    stems_free(a);
    stems_free(b);
}

static void test_lattice_without_jitter_has_exact_spacing(void **st)
{
    (void)st;
    stems *a = NULL;
    assert_int_equal(stems_lattice_alloc(&a, 3.5, 42.0, 0.0, 5), CS_OK);
    /* Every stem's nearest other stem is exactly d away (up to rounding). */
    for (size_t i = 0; i < a->n; i++) {
        double best = 1e9;
        for (size_t j = 0; j < a->n; j++) {
            if (j == i) continue;
            double dd = hypot(a->x[j] - a->x[i], a->y[j] - a->y[i]);
            if (dd < best) best = dd;
        }
        ASSERT_NEAR(best, 3.5, 1e-12);
    }
    stems_free(a);
}

static void test_hardcore_respects_the_core_and_count(void **st)
{
    (void)st;
    stems *a = NULL;
    assert_int_equal(stems_hardcore_alloc(&a, 3.0, 36.0, 0.5, 4242), CS_OK);
    assert_int_equal(a->n, 144);
    double dmin = 1e9;
    for (size_t i = 0; i < a->n; i++) {
        assert_true(a->x[i] >= 0.0 && a->x[i] < 36.0 && a->y[i] >= 0.0 && a->y[i] < 36.0);
        for (size_t j = i + 1; j < a->n; j++) {
            double dd = hypot(a->x[j] - a->x[i], a->y[j] - a->y[i]);
            if (dd < dmin) dmin = dd;
        }
    }
    assert_true(dmin >= 1.5);
    stems_free(a);
}

static void test_hardcore_unbuildable_fails_cleanly(void **st)
{
    (void)st;
    stems *a = (stems *)0x1;
    /* c = 1.3: 25 disks of diameter 1.3 d cannot fit a 5 d square by sequential addition. */
    cs_errclear();
    assert_int_equal(stems_hardcore_alloc(&a, 1.0, 5.0, 1.3, 1), CS_EINPUT);
    assert_null(a);
    assert_non_null(strstr(cs_errmsg(), "unbuildable"));
}

static void test_interior_is_two_spacings_from_the_edge(void **st)
{
    (void)st;
    double x[4] = {7.0, 6.99, 20.0, 35.0}, y[4] = {7.0, 20.0, 29.0, 20.0};
    stems *a = NULL;
    assert_int_equal(stems_from_xy(&a, 4, x, y, 3.5, 36.0), CS_OK);
    assert_true(stems_interior(a, 0));
    assert_false(stems_interior(a, 1));
    assert_true(stems_interior(a, 2));
    assert_false(stems_interior(a, 3));
    stems_free(a);
}

static void test_twins_share_stems_and_crown_draws(void **st)
{
    (void)st;
    stand *a = NULL, *b = NULL, *c = NULL;
    assert_int_equal(stand_alloc(&a, stems_lattice, 5.5, 66.0, 0.04, "mechanism", 3), CS_OK);
    assert_int_equal(stand_alloc(&b, stems_lattice, 5.5, 66.0, 0.04, "mechanism", 3), CS_OK);
    assert_int_equal(stand_alloc(&c, stems_lattice, 5.5, 66.0, 0.04, "mechanism", 4), CS_OK);
    assert_int_equal(a->s->n, b->s->n);
    size_t n = a->s->n;
    assert_memory_equal(a->s->x, b->s->x, n * sizeof(double));
    assert_memory_equal(a->h, b->h, n * sizeof(double));
    assert_memory_equal(a->rstar, b->rstar, n * CROWN_NSEC * sizeof(double));
    /* Another stand index draws different stems and crowns. */
    assert_true(a->s->x[0] != c->s->x[0]);
    assert_true(a->h[0] != c->h[0]);
    stand_free(a); stand_free(b); stand_free(c);
}

static void test_train_and_eval_stands_are_disjoint(void **st)
{
    (void)st;
    stand *a = NULL, *b = NULL;
    assert_int_equal(stand_alloc(&a, stems_lattice, 4.5, 54.0, 0.04, "main/train", 0), CS_OK);
    assert_int_equal(stand_alloc(&b, stems_lattice, 4.5, 54.0, 0.04, "main/eval", 0), CS_OK);
    assert_true(a->h[0] != b->h[0]);
    assert_true(a->s->x[0] != b->s->x[0]);
    stand_free(a); stand_free(b);
}

/* The stem processes are a table: found by name, and each type's alloc is
 * the process it names (same stems as calling the alloc directly). */
static void test_stem_types_are_a_table(void **st)
{
    (void)st;
    assert_ptr_equal(stems_type_find("lattice"), stems_lattice);
    assert_ptr_equal(stems_type_find("hardcore"), stems_hardcore);
    assert_null(stems_type_find("poisson"));
    size_t n = 0;
    for (const stems_type *const *t = stems_types; *t; t++) n++;
    assert_int_equal(n, 2);
    stems *a = NULL, *b = NULL;
    assert_int_equal(stems_hardcore->alloc(&a, 4.0, 36.0, 0.5, 7), CS_OK);
    assert_int_equal(stems_hardcore_alloc(&b, 4.0, 36.0, 0.5, 7), CS_OK);
    assert_int_equal(a->n, b->n);
    for (size_t i = 0; i < a->n; i++) { ASSERT_EXACT(a->x[i], b->x[i]); ASSERT_EXACT(a->y[i], b->y[i]); }
    stems_free(a);
    stems_free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_lattice_has_about_144_stems_and_is_repeatable),
        cmocka_unit_test(test_lattice_without_jitter_has_exact_spacing),
        cmocka_unit_test(test_hardcore_respects_the_core_and_count),
        cmocka_unit_test(test_hardcore_unbuildable_fails_cleanly),
        cmocka_unit_test(test_interior_is_two_spacings_from_the_edge),
        cmocka_unit_test(test_twins_share_stems_and_crown_draws),
        cmocka_unit_test(test_train_and_eval_stands_are_disjoint),
        cmocka_unit_test(test_stem_types_are_a_table),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
