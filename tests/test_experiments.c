/* Smoke tests for src/exp/ (exp_mechanism.c, exp_irreducibility.c, exp_stands.c, exp_replicates.c): units run at one
 * stand per cell into a scratch directory, write provenance and the documented columns, and keep the ablation's
 * ordering (coupling off interpenetrates, both on opens gaps). With --stand-rows the E1 sweep and the E2 units also
 * write the per-stand rows their pooled rows are made of, and the claims' stand bootstrap recomputes the pooled values
 * from them bit for bit. Stand 0 of the replicates is the figure units' own stand, with their numbers bit for bit. */
#include "testutil.h"
#include "agree.h"
#include "claims.h"
#include "cli.h"
#include "interval.h"
#include "paths.h"
#include "tsv.h"
#include <unistd.h>

static int run(const char *unit, const char *out)
{
    char *argv[] = {"crownshy", (char *)unit, "--stands", "1", "--out", (char *)out, NULL};
    return cli_main(6, argv);
}

static double cell(const tsv *t, size_t row, const char *col)
{
    double v = NAN;
    if (tsv_double(t, row, col, &v) != CS_OK) fail_msg("%s", cs_errmsg());
    return v;
}

static void test_ablation_unit_writes_three_arms_in_order(void **st)
{
    (void)st;
    const char *dir = tu_tmpdir("exp_ablation");
    assert_int_equal(run("mechanism-ablation", dir), 0);
    char path[600];
    snprintf(path, sizeof path, "%s/mechanism/ablation.tsv", dir);
    tsv *t = NULL;
    assert_int_equal(tsv_read(path, &t), CS_OK);
    assert_int_equal(tsv_nrows(t), 3);
    assert_string_equal(tsv_str(t, 0, "arm"), "coupling_off");
    assert_string_equal(tsv_str(t, 2, "arm"), "both_on");
    assert_non_null(tsv_meta(t, "teacher_version"));
    assert_non_null(tsv_meta(t, "worst_overlap_m"));
    assert_true(cell(t, 0, "k1_m") < 0.0);
    assert_true(cell(t, 2, "k1_m") > cell(t, 1, "k1_m"));
    assert_true(cell(t, 2, "overlap_m") <= 1e-9);
    tsv_free(t);
}

static void test_perturb_unit_judges_four_neighbours_per_stand(void **st)
{
    (void)st;
    const char *dir = tu_tmpdir("exp_perturb");
    assert_int_equal(run("irreducibility-perturb", dir), 0);
    char path[600];
    snprintf(path, sizeof path, "%s/irreducibility/perturb_train.tsv", dir);
    tsv *t = NULL;
    assert_int_equal(tsv_read(path, &t), CS_OK);
    assert_int_equal(tsv_nrows(t), 5);
    for (size_t r = 0; r < 5; r++) {
        ASSERT_EXACT(cell(t, r, "judged"), 4.0);
        double f = cell(t, r, "response_fraction");
        assert_true(f >= 0.0 && f <= 1.0);
    }
    ASSERT_EXACT(cell(t, 0, "spacing_m"), 3.0);
    tsv_free(t);
}

static void test_reduction_unit_reports_a_pooled_sigma(void **st)
{
    (void)st;
    const char *dir = tu_tmpdir("exp_reduction");
    assert_int_equal(run("irreducibility-reduction", dir), 0);
    char path[600];
    snprintf(path, sizeof path, "%s/irreducibility/reduction_train.tsv", dir);
    tsv *t = NULL;
    assert_int_equal(tsv_read(path, &t), CS_OK);
    assert_int_equal(tsv_nrows(t), 6);
    assert_string_equal(tsv_str(t, 0, "scope"), "pooled");
    double m = cell(t, 0, "miss_m"), s = cell(t, 0, "step_m");
    ASSERT_NEAR(cell(t, 0, "miss_steps"), m / s, 1e-12);
    /* The pooled sigma's miss can only be at least each spacing's own best. */
    for (size_t r = 1; r < 6; r++) assert_true(cell(t, r, "own_miss_m") <= cell(t, r, "miss_m"));
    tsv_free(t);
}

static int run_rows(const char *unit, const char *out, int rows)
{
    char *argv[] = {"crownshy", (char *)unit, "--stands", "2", "--out", (char *)out, "--stand-rows", NULL};
    return cli_main(rows ? 7 : 6, argv);
}

static void test_stand_rows_only_when_asked(void **st)
{
    (void)st;
    const char *dir = tu_tmpdir("exp_rows_off");
    char path[600];
    assert_int_equal(run_rows("irreducibility-perturb", dir, 0), 0);
    snprintf(path, sizeof path, "%s/irreducibility/perturb_train_stands.tsv", dir);
    assert_int_not_equal(access(path, F_OK), 0); /* the sensitivity units run without */
    char cmd[1600];
    snprintf(cmd, sizeof cmd, "grep -v '^#' %s/irreducibility/perturb_train.tsv > %s/pooled_without", dir, dir);
    assert_int_equal(system(cmd), 0);
    assert_int_equal(run_rows("irreducibility-perturb", dir, 1), 0);
    /* the pooled table's data rows do not depend on the per-stand rows */
    snprintf(cmd, sizeof cmd, "grep -v '^#' %s/irreducibility/perturb_train.tsv | cmp -s - %s/pooled_without", dir,
             dir);
    assert_int_equal(system(cmd), 0);
    tsv *t = NULL;
    assert_int_equal(tsv_read(path, &t), CS_OK);
    assert_int_equal(tsv_nrows(t), 5 * 2);
    assert_non_null(tsv_meta(t, "teacher_version"));
    assert_string_equal(tsv_str(t, 1, "stand"), "1");
    tsv_free(t);
}

/* The claims of each family, pointed at the 2-stand tables: computed, and
 * their stand bootstrap accepted (the pooled values recomputed from the
 * per-stand rows bit for bit) over 2 units. */
static void test_stand_rows_give_the_pooled_values(void **st)
{
    (void)st;
    const char *dir = tu_tmpdir("exp_rows");
    const char *units[] = {"mechanism-sweep", "irreducibility-perturb", "irreducibility-refine",
                           "irreducibility-reduction"};
    for (int u = 0; u < 4; u++) assert_int_equal(run_rows(units[u], dir, 1), 0);
    static const struct { const char *macro, *table; } c[] = {
        {"MechHits", "mechanism/sweep.tsv"}, {"IrredTrainRespLo", "irreducibility/perturb_train.tsv"},
        {"IrredRespHi", "irreducibility/perturb_train.tsv"}, {"IrredTrainShrink", "irreducibility/refine_train.tsv"},
        {"IrredStepShrink", "irreducibility/refine_train.tsv"}, {"IrredTrainSteps", "irreducibility/reduction_train.tsv"},
        {"IrredMiss", "irreducibility/reduction_train.tsv"},
    };
    claims reg;
    interval_table it;
    assert_int_equal(claims_registry(&reg), CS_OK);
    assert_int_equal(interval_table_load(PATHS_INTERVALS, &it), CS_OK);
    for (size_t i = 0; i < sizeof c / sizeof *c; i++) {
        const claim_row *orig = claims_find(&reg, c[i].macro);
        assert_non_null(orig);
        claim_row row = *orig;
        if (snprintf(row.source, sizeof row.source, "%.100s/%s", dir, c[i].table) >= (int)sizeof row.source)
            fail_msg("path too long");
        claim_result r;
        claims_eval(&row, &r);
        if (r.status != VERDICT_PASS) fail_msg("%s from %s: %s", c[i].macro, row.source, r.why);
        claim_interval ci;
        if (interval_eval(&it, &row, &r, &ci) != CS_OK) fail_msg("%s: %s", c[i].macro, cs_errmsg());
        if (!ci.has) fail_msg("%s: no interval (%s)", c[i].macro, ci.why);
        assert_int_equal(ci.n, 2);
        assert_true(ci.lo <= ci.hi);
    }
    interval_table_free(&it);
    claims_free(&reg);
}

/* Stand 0 of each replicate family is the figure's own stand: replicates-run gives the numbers of
 * mechanism/figure_stats.tsv and pointcloud/stats.tsv bit for bit (figstand.c computes all three). */
static void test_replicate_stand_0_is_the_figure_stand(void **st)
{
    (void)st;
    const char *dir = tu_tmpdir("exp_replicates");
    const char *figures[] = {"mechanism-figure", "pointcloud-figure"};
    for (int u = 0; u < 2; u++) {
        char *argv[] = {"crownshy", (char *)figures[u], "--out", (char *)dir, NULL};
        assert_int_equal(cli_main(4, argv), 0);
    }
    assert_int_equal(run("replicates-run", dir), 0);
    const char *files[3] = {"replicates/figure_stands.tsv", "mechanism/figure_stats.tsv", "pointcloud/stats.tsv"};
    tsv *t[3] = {NULL, NULL, NULL};
    for (int f = 0; f < 3; f++) {
        char path[600];
        snprintf(path, sizeof path, "%s/%s", dir, files[f]);
        assert_int_equal(tsv_read(path, &t[f]), CS_OK);
    }
    assert_int_equal(tsv_nrows(t[0]), 11); /* 3 E1 arms, 3 x 2 E8 stands, 2 E9 spacings */
    static const char *const e1[] = {"spacing_m", "trees", "k1_m", "k2_m", "k3_m", "cover", "overlap_m"};
    for (size_t a = 0; a < 3; a++) {
        assert_string_equal(tsv_str(t[0], a, "family"), "mechanism");
        assert_string_equal(tsv_str(t[0], a, "arm"), tsv_str(t[1], a, "arm"));
        for (size_t c = 0; c < sizeof e1 / sizeof *e1; c++) ASSERT_EXACT(cell(t[0], a, e1[c]), cell(t[1], a, e1[c]));
    }
    for (size_t i = 0; i < 3; i++) {
        size_t c = 3 + 2 * i, u = c + 1; /* the coupled and the uncoupled row of spacing i */
        assert_string_equal(tsv_str(t[0], c, "arm"), "coupled");
        ASSERT_EXACT(cell(t[0], c, "spacing_m"), cell(t[2], i, "spacing_m"));
        ASSERT_EXACT(cell(t[0], c, "trees"), cell(t[2], i, "trees"));
        ASSERT_EXACT(cell(t[0], c, "k1_m"), cell(t[2], i, "k1_coupled_m"));
        ASSERT_EXACT(cell(t[0], u, "k1_m"), cell(t[2], i, "k1_uncoupled_m"));
        ASSERT_EXACT(cell(t[0], c, "overlap_m"), cell(t[2], i, "overlap_fraction_coupled"));
        ASSERT_EXACT(cell(t[0], u, "overlap_m"), cell(t[2], i, "overlap_fraction_uncoupled"));
        ASSERT_EXACT(cell(t[0], c, "contact_pct"), 100.0 * cell(t[2], i, "contact_fraction"));
    }
    for (int f = 0; f < 3; f++) tsv_free(t[f]);
}

static void test_bad_usage_exits_2(void **st)
{
    (void)st;
    char *a1[] = {"crownshy", "no-such-unit", NULL};
    assert_int_equal(cli_main(2, a1), 2);
    char *a2[] = {"crownshy", "mechanism-sweep", "--stands", "0", NULL};
    assert_int_equal(cli_main(4, a2), 2);
    char *a3[] = {"crownshy", "irreducibility-perturb", "--tag", "field", NULL};
    assert_int_equal(cli_main(4, a3), 2);
    char *a4[] = {"crownshy", "mechanism-figure", "--stands", "1", NULL};
    assert_int_equal(cli_main(4, a4), 2); /* a figure unit has no stand count to set */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ablation_unit_writes_three_arms_in_order),
        cmocka_unit_test(test_perturb_unit_judges_four_neighbours_per_stand),
        cmocka_unit_test(test_reduction_unit_reports_a_pooled_sigma),
        cmocka_unit_test(test_stand_rows_only_when_asked),
        cmocka_unit_test(test_stand_rows_give_the_pooled_values),
        cmocka_unit_test(test_replicate_stand_0_is_the_figure_stand),
        cmocka_unit_test(test_bad_usage_exits_2),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
