/* Tests for src/base/opts.c: the one table-driven option parser (getopt_long
 * underneath): strict numbers, ranges, unknown options, missing values,
 * positional counts, --name=value, and argv left in its order. Messages are
 * checked per command in test_cli_opts.c. */
#include "testutil.h"
#include "opts.h"

static long n_stands;
static double beta;
static const char *out;
static int flag;
static const opt_spec OPTS[] = {
    {"stands", OPT_LONG, &n_stands, 1, 10000, "stands per cell"},
    {"beta", OPT_DOUBLE, &beta, 0, 0.99, "die-back"},
    {"out", OPT_STR, &out, 0, 0, "output directory"},
    {"quiet", OPT_FLAG, &flag, 0, 0, "no progress"},
};
static const opts_cmd CMD = {"toy", "[options] UNIT", NULL, OPTS, 4, 1, 1};

static void reset(void) { n_stands = 8; beta = -7.25; out = "none"; flag = 0; }

static int parse(int argc, char **argv, char **pos, int *np)
{
    reset();
    return opts_parse(&CMD, argc, argv, pos, np);
}

static void test_values_parse_and_positional_is_returned(void **s)
{
    (void)s;
    char *a[] = {"toy", "--stands", "12", "unit-a", "--beta=0.0625", "--out", "dir", "--quiet"};
    char *pos[8];
    int np = -1;
    assert_int_equal(parse(8, a, pos, &np), OPTS_OK);
    assert_int_equal(n_stands, 12);
    ASSERT_EXACT(beta, 0.0625);
    assert_string_equal(out, "dir");
    assert_int_equal(flag, 1);
    assert_int_equal(np, 1);
    assert_string_equal(pos[0], "unit-a");
    /* the caller's argv keeps its order (provenance quotes it) */
    assert_string_equal(a[3], "unit-a");
    assert_string_equal(a[4], "--beta=0.0625");
}

static void test_bad_numbers_are_usage_errors(void **s)
{
    (void)s;
    const char *bad[][2] = {{"--stands", "abc"}, {"--stands", ""}, {"--stands", "12x"}, {"--stands", "0"},
                            {"--stands", "10001"}, {"--stands", "99999999999999999999"}, {"--beta", "abc"},
                            {"--beta", ""}, {"--beta", "1.5"}, {"--beta", "-0.01"}, {"--beta", "nan"},
                            {"--beta", "inf"}, {"--beta", "1e400"}, {"--beta", "0.1 "}};
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        char *a[] = {"toy", (char *)bad[i][0], (char *)bad[i][1], "u"};
        char *pos[4];
        int r = parse(4, a, pos, NULL);
        if (r != OPTS_USAGE) fail_msg("%s '%s': observed %d, expected OPTS_USAGE", bad[i][0], bad[i][1], r);
    }
    /* the target keeps its value when the input is refused */
    assert_int_equal(n_stands, 8);
}

static void test_range_ends_are_accepted(void **s)
{
    (void)s;
    char *a[] = {"toy", "--stands", "10000", "--beta", "0.99", "u"}, *pos[6];
    assert_int_equal(parse(6, a, pos, NULL), OPTS_OK);
    assert_int_equal(n_stands, 10000);
    ASSERT_EXACT(beta, 0.99);
}

static void test_unknown_option_and_missing_value(void **s)
{
    (void)s;
    char *unknown[] = {"toy", "--stand-count", "3", "u"}, *missing[] = {"toy", "u", "--out"},
         *shortopt[] = {"toy", "-x", "u"};
    char *pos[4];
    assert_int_equal(parse(4, unknown, pos, NULL), OPTS_USAGE);
    assert_int_equal(parse(3, missing, pos, NULL), OPTS_USAGE);
    assert_int_equal(parse(3, shortopt, pos, NULL), OPTS_USAGE);
}

static void test_positional_count_is_enforced(void **s)
{
    (void)s;
    char *none[] = {"toy", "--stands", "3"}, *two[] = {"toy", "u", "v"};
    char *pos[3];
    assert_int_equal(parse(3, none, pos, NULL), OPTS_USAGE);
    assert_int_equal(parse(3, two, pos, NULL), OPTS_USAGE);
}

static void test_help_either_spelling(void **s)
{
    (void)s;
    char *a1[] = {"toy", "--stands", "abc", "--help"}, *a2[] = {"toy", "-h"};
    char *pos[4];
    FILE *keep = stdout;
    stdout = fopen("/dev/null", "w");
    int rc_help = parse(2, a2, pos, NULL);
    /* --help before a bad value is not reached: the value error comes first */
    int rc_usage = parse(4, a1, pos, NULL);
    fclose(stdout);
    stdout = keep;
    assert_int_equal(rc_help, OPTS_HELP);
    assert_int_equal(rc_usage, OPTS_USAGE);
    assert_int_equal(opts_exit_code(OPTS_HELP), 0);
    assert_int_equal(opts_exit_code(OPTS_USAGE), 2);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_values_parse_and_positional_is_returned),
        cmocka_unit_test(test_bad_numbers_are_usage_errors),
        cmocka_unit_test(test_range_ends_are_accepted),
        cmocka_unit_test(test_unknown_option_and_missing_value),
        cmocka_unit_test(test_positional_count_is_enforced),
        cmocka_unit_test(test_help_either_spelling),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
