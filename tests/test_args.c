/* Tests for src/args.c: --help/-h detection, value lookup, and the check that
 * names an unknown option or a missing value (exit code 2). */
#include "testutil.h"
#include "args.h"

static void test_help_is_detected_either_spelling(void **s)
{
    (void)s;
    char *a1[] = {"cmd", "--out", "x", "--help"}, *a2[] = {"cmd", "-h"}, *a3[] = {"cmd", "--out", "x"};
    assert_int_equal(args_help(4, a1, "usage: a\n"), 1);
    assert_int_equal(args_help(2, a2, "usage: b"), 1);
    assert_int_equal(args_help(3, a3, "usage: c\n"), 0);
}

static void test_value_of_present_and_absent_options(void **s)
{
    (void)s;
    char *a[] = {"cmd", "--seed", "07", "--arm", "joint"};
    assert_string_equal(args_value(5, a, "--seed", NULL), "07");
    assert_string_equal(args_value(5, a, "--arm", NULL), "joint");
    assert_string_equal(args_value(5, a, "--scale", "full"), "full");
    assert_null(args_value(5, a, "--out", NULL));
}

static void test_check_accepts_known_pairs(void **s)
{
    (void)s;
    static const char *known[] = {"--seed", "--arm", NULL};
    char *a[] = {"cmd", "--seed", "1", "--arm", "indep"};
    assert_int_equal(args_check("main-run", 5, a, known), 0);
    assert_int_equal(args_check("main-run", 1, a, known), 0);
}

static void test_check_rejects_unknown_option_and_missing_value(void **s)
{
    (void)s;
    static const char *known[] = {"--seed", NULL};
    char *unknown[] = {"cmd", "--seed", "1", "--sed", "2"}, *missing[] = {"cmd", "--seed"};
    assert_int_equal(args_check("main-run", 5, unknown, known), 2);
    assert_int_equal(args_check("main-run", 2, missing, known), 2);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_help_is_detected_either_spelling),
        cmocka_unit_test(test_value_of_present_and_absent_options),
        cmocka_unit_test(test_check_accepts_known_pairs),
        cmocka_unit_test(test_check_rejects_unknown_option_and_missing_value),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
