/* Tests for the E5/E6 claim functions (src/claims/claim_field.c, src/claims/claim_aniso.c):
 * the spread claims are PENDING without FIELD_TABLE and computed (and gated)
 * with the SYNTHETIC fixture tests/data/field_synthetic.tsv (invented for
 * tests, spread 0.625 m); unbuildable sweep levels are reported, not fatal. */
#include "testutil.h"
#include "claims.h"
#include "fieldsim.h"
#include "exp_common.h"

#define FIXTURE "tests/data/field_synthetic.tsv"
#define FIXTURE_SPREAD 0.625

static char g_heldout[600];
static double g_spread[2]; /* uncoupled, coupled */

/* One small held-out pair (a coupled stand and its uncoupled twin) in a scratch dir. */
static int setup_heldout(void **s)
{
    (void)s;
    snprintf(g_heldout, sizeof g_heldout, "%s/heldout.tsv", tu_tmpdir("field_claims"));
    fs_trees t;
    fs_trees_init(&t);
    stand *sd;
    if (stand_alloc(&sd, stems_lattice, 5.0, 60.0, 0.04, "test/field_claims", 0)) return -1;
    if (exp_field_grow_append(sd, NULL, 0.19, 1, 0.19, 0, &t, NULL) ||
        exp_field_grow_append(sd, NULL, 0.19, 0, 0.19, 0, &t, NULL))
        return -1;
    stand_free(sd);
    char tp[700];
    fs_trees_path(g_heldout, tp, sizeof tp);
    tsv_writer *w;
    if (tsv_writer_open(&w, tp)) return -1;
    fs_trees_write(w, &t);
    if (tsv_writer_commit(w) || tsv_writer_open(&w, g_heldout)) return -1;
    tsv_writer_columns(w, FS_SUMMARY_COLUMNS);
    for (int arm = 1; arm >= 0; arm--) {
        fs_summary sm;
        if (fs_group(&t, arm, 0.19, &sm)) return -1;
        g_spread[arm] = sm.f.spread;
        fs_summary_write_row(w, arm, 0.19, 0.19, 0, &sm);
    }
    fs_trees_free(&t);
    return tsv_writer_commit(w) ? -1 : 0;
}

static claim_row row_for(const char *macro, const char *fn, const char *gate, const char *source)
{
    claim_row r;
    memset(&r, 0, sizeof r);
    snprintf(r.macro, sizeof r.macro, "%s", macro);
    snprintf(r.kind, sizeof r.kind, "needs-data");
    snprintf(r.source, sizeof r.source, "%s", source);
    snprintf(r.function, sizeof r.function, "%s", fn);
    snprintf(r.gate, sizeof r.gate, "%s", gate);
    snprintf(r.format, sizeof r.format, "%%.2f");
    return r;
}

static void test_spread_ratio_pending_without_table(void **s)
{
    (void)s;
    unsetenv("FIELD_TABLE");
    claim_row row = row_for("SpreadRatio", "claim_field_spread_ratio", "field.gate:spread_ratio_band", g_heldout);
    claim_result r;
    claims_eval(&row, &r);
    assert_int_equal(r.status, VERDICT_PENDING);
    assert_int_equal(r.gate, VERDICT_PENDING);
    assert_non_null(strstr(r.why, "FIELD_TABLE"));
}

static void test_spread_ratio_computed_with_synthetic_table(void **s)
{
    (void)s;
    setenv("FIELD_TABLE", FIXTURE, 1);
    claim_row row = row_for("SpreadRatio", "claim_field_spread_ratio", "field.gate:spread_ratio_band", g_heldout);
    claim_result r;
    claims_eval(&row, &r);
    unsetenv("FIELD_TABLE");
    if (r.status != VERDICT_PASS) fail_msg("status %s: %s", verdict_name(r.status), r.why);
    ASSERT_NEAR(r.value, g_spread[1] / FIXTURE_SPREAD, 1e-12);
    assert_int_not_equal(r.gate, VERDICT_PENDING);
    assert_int_equal(r.gate, (g_spread[1] / FIXTURE_SPREAD >= 0.5 && g_spread[1] / FIXTURE_SPREAD <= 2.0)
                                 ? VERDICT_PASS
                                 : VERDICT_FAIL);
    assert_non_null(strstr(r.where, FIXTURE));
}

static void test_control_spread_computed_and_judged_outside(void **s)
{
    (void)s;
    setenv("FIELD_TABLE", FIXTURE, 1);
    claim_row row =
        row_for("ControlSpread", "claim_field_control_spread", "field.gate:control_spread_outside_band", g_heldout);
    claim_result r;
    claims_eval(&row, &r);
    unsetenv("FIELD_TABLE");
    if (r.status != VERDICT_PASS) fail_msg("status %s: %s", verdict_name(r.status), r.why);
    double want = g_spread[0] / FIXTURE_SPREAD;
    ASSERT_NEAR(r.value, want, 1e-12);
    /* the control passes when it falls OUTSIDE [0.5, 2.0] */
    assert_int_equal(r.gate, (want < 0.5 || want > 2.0) ? VERDICT_PASS : VERDICT_FAIL);
    assert_non_null(strstr(r.gate_detail, "outside"));
}

static void test_bad_field_table_fails_naming_file(void **s)
{
    (void)s;
    const char *dir = tu_tmpdir("field_claims_bad");
    char p[700];
    snprintf(p, sizeof p, "%s/bad.tsv", dir);
    tu_write(p, "tree\tdirection\tclearance_m\na\tE\t1\n");
    setenv("FIELD_TABLE", p, 1);
    claim_row row = row_for("SpreadRatio", "claim_field_spread_ratio", "field.gate:spread_ratio_band", g_heldout);
    claim_result r;
    claims_eval(&row, &r);
    unsetenv("FIELD_TABLE");
    assert_int_equal(r.status, VERDICT_FAIL);
    assert_non_null(strstr(r.why, "bad.tsv:2"));
}

static void test_unbuildable_level_is_reported_not_fatal(void **s)
{
    (void)s;
    /* three buildable levels with falling anisotropy and one unbuildable level */
    const char *dir = tu_tmpdir("aniso_unbuildable");
    char sp[700], tp[700];
    snprintf(sp, sizeof sp, "%s/hardcore.tsv", dir);
    fs_trees_path(sp, tp, sizeof tp);
    char tb[4096] = FS_TREE_COLUMNS "\n", sb[4096] = FS_SUMMARY_COLUMNS "\n";
    double levels[3] = {0.3, 0.4, 0.5};
    fs_trees t;
    fs_trees_init(&t);
    for (int k = 0; k < 3; k++) {
        double hi = 2.0 - 0.2 * k; /* anisotropy hi/1.0 */
        char row[256];
        snprintf(row, sizeof row, "coupled\t%.17g\t0\t0\t1\t%.17g\t1\t1\t1.1\t1\n", levels[k], hi);
        strcat(tb, row);
    }
    tu_write(tp, tb);
    assert_int_equal(fs_trees_read(tp, &t), CS_OK);
    for (int k = 0; k < 3; k++) {
        fs_summary sm;
        assert_int_equal(fs_group(&t, 1, levels[k], &sm), CS_OK);
        char row[512];
        snprintf(row, sizeof row, "coupled\t%.17g\t0.19\t%zu\t0\t%zu\t%.17g\t%.17g\t%.17g\t%zu\t%zu\t%.17g\t%.17g\n",
                 levels[k], sm.stands, sm.f.trees, sm.f.tree_mean_median, sm.f.spread, sm.f.aniso_median,
                 sm.f.aniso_trees, sm.f.aniso_excluded, sm.elong_median, sm.elong_card_median);
        strcat(sb, row);
    }
    strcat(sb, "coupled\t0.7\t0.19\t0\t12\t0\tnan\tnan\tnan\t0\t0\tnan\tnan\n");
    tu_write(sp, sb);
    fs_trees_free(&t);
    claim_row row = row_for("HardcoreRho", "claim_aniso_rho", "anisotropy.gate:hardcore_rho_max", sp);
    snprintf(row.format, sizeof row.format, "text");
    claim_result r;
    claims_eval(&row, &r);
    if (r.status != VERDICT_PASS) fail_msg("status %s: %s", verdict_name(r.status), r.why);
    assert_string_equal(r.text, "-1");
    assert_int_equal(r.gate, VERDICT_PASS);
    assert_non_null(strstr(r.where, "1 unbuildable"));
    claim_row ov = row_for("HardcoreOvershoot", "claim_aniso_hardcore_overshoot", "-", sp);
    claims_eval(&ov, &r);
    /* tightest BUILDABLE level is c = 0.5 with anisotropy 1.6 */
    ASSERT_NEAR(r.value, 1.6, 1e-15);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_spread_ratio_pending_without_table),
        cmocka_unit_test(test_spread_ratio_computed_with_synthetic_table),
        cmocka_unit_test(test_control_spread_computed_and_judged_outside),
        cmocka_unit_test(test_bad_field_table_fails_naming_file),
        cmocka_unit_test(test_unbuildable_level_is_reported_not_fatal),
    };
    return cmocka_run_group_tests(tests, setup_heldout, NULL);
}
