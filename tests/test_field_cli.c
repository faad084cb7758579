/* Exit codes and messages of the E5/E6 commands (design.md §11): --help 0,
 * usage errors 2, bad or missing input 3 naming file, line and field.
 * Runs build/crownshy; the fixture tests/data/field_synthetic.tsv is SYNTHETIC. */
#include "testutil.h"
#include <sys/wait.h>

static char out[65536];

static int run(const char *args) { return tu_run_cli("env -u FIELD_TABLE ", args, out, sizeof out); }

static void test_help_exits_zero(void **s)
{
    (void)s;
    const char *cmds[] = {
        "field-summary",      "field-calibrate",     "field-beta",        "field-heldout",
        "anisotropy-lattice", "anisotropy-hardcore", "anisotropy-jitter", "anisotropy-jitter-calibrate",
        "anisotropy-heldout", "field-diagnose"};
    for (size_t i = 0; i < sizeof cmds / sizeof *cmds; i++) {
        char a[96];
        snprintf(a, sizeof a, "%s --help", cmds[i]);
        if (run(a) != 0 || !strstr(out, "usage:")) fail_msg("crownshy %s: %s", a, out);
    }
}

static void test_field_summary_of_synthetic_table(void **s)
{
    (void)s;
    assert_int_equal(run("field-summary tests/data/field_synthetic.tsv"), 0);
    assert_non_null(strstr(out, "trees\t3"));
    assert_non_null(strstr(out, "spread_iqr_m\t0.625"));
    assert_non_null(strstr(out, "aniso_excluded\t1"));
}

static void test_field_summary_without_table_is_input_error(void **s)
{
    (void)s;
    assert_int_equal(run("field-summary"), 3);
    assert_non_null(strstr(out, "FIELD_TABLE"));
}

static void test_field_summary_bad_table_names_line(void **s)
{
    (void)s;
    assert_int_equal(tu_run_cli_on("env -u FIELD_TABLE ", "field-summary", "field_cli_bad", "bad.tsv",
                                   "tree\tdirection\tclearance_m\nx\tE\t0.5\nx\tup\t0.5\n", out, sizeof out),
                     3);
    assert_non_null(strstr(out, "bad.tsv:3: field 'direction'"));
}

static void test_usage_errors(void **s)
{
    (void)s;
    assert_int_equal(run("field-calibrate"), 2);
    assert_non_null(strstr(out, "--out"));
    assert_int_equal(run("field-heldout --out build/test-tmp/x.tsv"), 2);
    assert_non_null(strstr(out, "--calibration"));
    assert_int_equal(run("anisotropy-lattice --stands 0 --out build/test-tmp/x.tsv"), 2);
    assert_int_equal(run("anisotropy-jitter --bogus 1 --out build/test-tmp/x.tsv"), 2);
    assert_int_equal(run("field-beta"), 2);
}

static void test_missing_inputs_are_input_errors(void **s)
{
    (void)s;
    assert_int_equal(run("field-beta build/test-tmp/no-such-calibration.tsv"), 3);
    assert_non_null(strstr(out, "no-such-calibration.tsv"));
    assert_int_equal(run("anisotropy-jitter-calibrate --sweep build/test-tmp/no-such.tsv --out build/test-tmp/x.tsv"),
                     3);
    assert_int_equal(run("anisotropy-heldout --calibration build/test-tmp/no-such.tsv --jitter-calibration x --out "
                         "build/test-tmp/x.tsv"),
                     3);
}

/* trace of a claim whose input is bad exits 3 (bad input), naming the file,
 * line and field, after printing what it could (design.md §11). */
static void test_trace_of_a_bad_field_table_exits_3(void **s)
{
    (void)s;
    char p[600], env[700];
    tu_write_in(p, sizeof p, tu_tmpdir("field_cli_trace"), "bad.tsv", "tree\tdirection\tclearance_m\n1\tN\tabc\n");
    snprintf(env, sizeof env, "FIELD_TABLE=%s ", p);
    int rc = tu_run_cli(env, "trace SpreadRatio", out, sizeof out);
    if (rc != 3) fail_msg("trace exit %d, expected 3: %s", rc, out);
    assert_non_null(strstr(out, "bad.tsv:2: field 'clearance_m'"));
    assert_non_null(strstr(out, "registry"));
    if ((rc = run("trace SpreadRatio")) != 0)
        fail_msg("trace without a field table: exit %d, expected 0 (pending): %s", rc, out);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_help_exits_zero),
        cmocka_unit_test(test_field_summary_of_synthetic_table),
        cmocka_unit_test(test_field_summary_without_table_is_input_error),
        cmocka_unit_test(test_field_summary_bad_table_names_line),
        cmocka_unit_test(test_usage_errors),
        cmocka_unit_test(test_missing_inputs_are_input_errors),
        cmocka_unit_test(test_trace_of_a_bad_field_table_exits_3),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
