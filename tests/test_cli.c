/* Tests of the CLI's exit codes and messages (design.md §11): 0 ok, 2 usage,
 * 3 bad input naming file, line and field. Runs build/crownshy. */
#include "testutil.h"
#include <sys/wait.h>

static int run(const char *args, char *out, size_t n) { return tu_run_cli("", args, out, n); }

static char out[65536];

static int run_on_file(const char *command, const char *scratch, const char *file, const char *text)
{
    return tu_run_cli_on("", command, scratch, file, text, out, sizeof out);
}

static void test_help_exits_zero(void **s)
{
    (void)s;
    assert_int_equal(run("--help", out, sizeof out), 0);
    const char *cmds[] = {"verify", "numbers", "audit", "trace", "gates", "check-tsv", "pin", "hash-frozen", "figures"};
    for (size_t i = 0; i < sizeof cmds / sizeof *cmds; i++) {
        char a[64];
        snprintf(a, sizeof a, "%s --help", cmds[i]);
        if (run(a, out, sizeof out) != 0) fail_msg("crownshy %s exit != 0: %s", a, out);
        if (!strstr(out, "usage:")) fail_msg("crownshy %s printed no usage", a);
    }
}

static void test_unknown_command_is_usage_error(void **s)
{
    (void)s;
    assert_int_equal(run("frobnicate", out, sizeof out), 2);
    assert_non_null(strstr(out, "frobnicate"));
    assert_int_equal(run("verify --bogus", out, sizeof out), 2);
}

static void test_malformed_gate_exit_3_names_file_line_field(void **s)
{
    (void)s;
    assert_int_equal(run_on_file("gates", "cli_gate", "bad.gate", "# c\nseeds 12\nrel_improvement_min 0.2O\n"), 3);
    assert_non_null(strstr(out, "bad.gate:3:"));
    assert_non_null(strstr(out, "rel_improvement_min"));
}

static void test_truncated_tsv_exit_3_names_line_and_field(void **s)
{
    (void)s;
    assert_int_equal(run_on_file("check-tsv", "cli_tsv", "runs.tsv",
                                 "# experiment: main\nseed\tarm\tw1\n1\tjoint\t0.4\n2\tjoint\n"),
                     3);
    assert_non_null(strstr(out, "runs.tsv:4:"));
    assert_non_null(strstr(out, "'w1'"));
}

static void test_non_number_tsv_exit_3(void **s)
{
    (void)s;
    assert_int_equal(run_on_file("check-tsv", "cli_nan", "runs.tsv", "seed\tw1\n1\t0.4\n2\t0.4x\n"), 3);
    assert_non_null(strstr(out, "runs.tsv:3:"));
    assert_non_null(strstr(out, "'w1'"));
}

static void test_missing_file_exit_3(void **s)
{
    (void)s;
    assert_int_equal(run("check-tsv build/test-tmp/nope.tsv", out, sizeof out), 3);
    assert_non_null(strstr(out, "nope.tsv"));
}

static void test_shipped_gates_parse(void **s)
{
    (void)s;
    assert_int_equal(run("gates", out, sizeof out), 0);
    assert_non_null(strstr(out, "gates/main.gate: ok"));
}

static void test_trace_unknown_macro_exit_3(void **s)
{
    (void)s;
    assert_int_equal(run("trace NoSuchMacro", out, sizeof out), 3);
    assert_non_null(strstr(out, "NoSuchMacro"));
    assert_int_equal(run("trace MainSeeds", out, sizeof out), 0);
    assert_non_null(strstr(out, "gates/main.gate"));
}

/* trace names the command that runs a claim's test alone, and that command
 * runs exactly that one test (built by make check before any test runs) */
static void test_claim_test_runs_alone_by_name(void **s)
{
    (void)s;
    assert_int_equal(run("trace MainRel", out, sizeof out), 0);
    assert_non_null(strstr(out, "make test-claim MACRO=MainRel"));
    FILE *p = popen("build/tests/test_claims MainRel 2>&1", "r");
    assert_non_null(p);
    size_t got = fread(out, 1, sizeof out - 1, p);
    out[got] = '\0';
    int st = pclose(p);
    if (!WIFEXITED(st) || WEXITSTATUS(st) != 0) fail_msg("test_claims MainRel: status %d: %s", st, out);
    assert_non_null(strstr(out, "[       OK ] claim_MainRel"));
    assert_non_null(strstr(out, "1 test(s) run."));
    p = popen("build/tests/test_claims NoSuchMacro 2>&1", "r");
    assert_non_null(p);
    got = fread(out, 1, sizeof out - 1, p);
    out[got] = '\0';
    st = pclose(p);
    assert_true(WIFEXITED(st) && WEXITSTATUS(st) == 1);
    assert_non_null(strstr(out, "no claim NoSuchMacro"));
}

/* a build/ that cannot take a file (a file-size limit of zero) is an
 * environment error, exit 4, named before any check runs: never reported as
 * an inconsistency of the results */
static void test_verify_unwritable_build_exit_4(void **s)
{
    (void)s;
    assert_int_equal(tu_run_cli("ulimit -f 0; OPENBLAS_NUM_THREADS=1 ", "verify --no-figures", out, sizeof out), 4);
    assert_non_null(strstr(out, "an environment error"));
    assert_null(strstr(out, "INCONSISTENT"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_help_exits_zero),
        cmocka_unit_test(test_unknown_command_is_usage_error),
        cmocka_unit_test(test_malformed_gate_exit_3_names_file_line_field),
        cmocka_unit_test(test_truncated_tsv_exit_3_names_line_and_field),
        cmocka_unit_test(test_non_number_tsv_exit_3),
        cmocka_unit_test(test_missing_file_exit_3),
        cmocka_unit_test(test_shipped_gates_parse),
        cmocka_unit_test(test_trace_unknown_macro_exit_3),
        cmocka_unit_test(test_claim_test_runs_alone_by_name),
        cmocka_unit_test(test_verify_unwritable_build_exit_4),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
