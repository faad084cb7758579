/* Tests for src/base/gate.c: parsing the preregistered gate files and judging. */
#include "testutil.h"
#include "gate.h"

static const char *fixture(const char *name, const char *text)
{
    static char path[600];
    snprintf(path, sizeof path, "%s/%s", tu_tmpdir(name), "x.gate");
    tu_write(path, text);
    return path;
}

static void test_parses_every_shipped_gate(void **s)
{
    (void)s;
    const char *names[] = {"mechanism", "irreducibility", "main", "extrapolation", "field", "anisotropy"};
    for (int i = 0; i < 6; i++) {
        char p[128];
        snprintf(p, sizeof p, "gates/%s.gate", names[i]);
        gate *g = NULL;
        if (gate_load(p, &g) != CS_OK) fail_msg("%s: %s", p, cs_errmsg());
        gate_free(g);
    }
}

static void test_values_and_lines(void **s)
{
    (void)s;
    gate *g;
    assert_int_equal(gate_load("gates/mechanism.gate", &g), CS_OK);
    double v;
    assert_int_equal(gate_value(g, "cover_min", 0, &v), CS_OK);
    ASSERT_EXACT(v, 0.80);
    assert_int_equal(gate_count(g, "dieback_sweep"), 4);
    assert_int_equal(gate_value(g, "dieback_sweep", 3, &v), CS_OK);
    ASSERT_EXACT(v, 0.09);
    assert_int_equal(gate_value(g, "overlap_max_m", 0, &v), CS_OK);
    ASSERT_EXACT(v, 1e-9);
    assert_true(gate_line(g, "cover_min") > 3);
    gate_free(g);
}

static void test_absent_key_names_file_and_key(void **s)
{
    (void)s;
    gate *g;
    assert_int_equal(gate_load("gates/main.gate", &g), CS_OK);
    double v;
    assert_int_equal(gate_value(g, "no_such_key", 0, &v), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "main.gate"));
    assert_non_null(strstr(cs_errmsg(), "no_such_key"));
    assert_int_equal(gate_value(g, "seeds", 1, &v), CS_EINPUT);
    gate_free(g);
}

static void test_non_number_names_line_and_field(void **s)
{
    (void)s;
    const char *p = fixture("gate_nan", "# c\nalpha 1 2\nbeta 0.5 zz\n");
    gate *g = NULL;
    assert_int_equal(gate_load(p, &g), CS_EINPUT);
    assert_null(g);
    assert_non_null(strstr(cs_errmsg(), "x.gate:3:"));
    assert_non_null(strstr(cs_errmsg(), "'beta'"));
    assert_non_null(strstr(cs_errmsg(), "zz"));
}

static void test_missing_value_is_error(void **s)
{
    (void)s;
    const char *p = fixture("gate_missing", "alpha 1\nbeta\n");
    gate *g = NULL;
    assert_int_equal(gate_load(p, &g), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "x.gate:2:"));
    assert_non_null(strstr(cs_errmsg(), "'beta'"));
}

static void test_duplicate_key_is_error(void **s)
{
    (void)s;
    const char *p = fixture("gate_dup", "alpha 1\nalpha 2\n");
    gate *g = NULL;
    assert_int_equal(gate_load(p, &g), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "x.gate:2:"));
}

static void test_truncated_file_is_error(void **s)
{
    (void)s;
    const char *p = fixture("gate_trunc", "alpha 1\nbeta 0.");
    gate *g = NULL;
    assert_int_equal(gate_load(p, &g), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "x.gate:2:"));
}

static void test_missing_file_is_error(void **s)
{
    (void)s;
    gate *g = NULL;
    assert_int_equal(gate_load("gates/nope.gate", &g), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "nope.gate"));
}

static void test_judge(void **s)
{
    (void)s;
    assert_int_equal(gate_judge(GATE_GE, 0.20, 0.20, 0), VERDICT_PASS);
    assert_int_equal(gate_judge(GATE_GE, 0.19999, 0.20, 0), VERDICT_FAIL);
    assert_int_equal(gate_judge(GATE_LT, 0.05, 0.05, 0), VERDICT_FAIL);
    assert_int_equal(gate_judge(GATE_LT, 0.049, 0.05, 0), VERDICT_PASS);
    assert_int_equal(gate_judge(GATE_IN, 2.0, 0.5, 2.0), VERDICT_PASS);
    assert_int_equal(gate_judge(GATE_IN, 2.01, 0.5, 2.0), VERDICT_FAIL);
    assert_int_equal(gate_judge(GATE_OUT, 31.3, 0.5, 2.0), VERDICT_PASS);
    assert_int_equal(gate_judge(GATE_OUT, 1.0, 0.5, 2.0), VERDICT_FAIL);
    assert_int_equal(gate_judge(GATE_GE, NAN, 0.2, 0), VERDICT_FAIL);
    assert_int_equal(gate_judge(GATE_TRUE, 1, 0, 0), VERDICT_PASS);
    assert_int_equal(gate_judge(GATE_TRUE, 0, 0, 0), VERDICT_FAIL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_parses_every_shipped_gate),
        cmocka_unit_test(test_values_and_lines),
        cmocka_unit_test(test_absent_key_names_file_and_key),
        cmocka_unit_test(test_non_number_names_line_and_field),
        cmocka_unit_test(test_missing_value_is_error),
        cmocka_unit_test(test_duplicate_key_is_error),
        cmocka_unit_test(test_truncated_file_is_error),
        cmocka_unit_test(test_missing_file_is_error),
        cmocka_unit_test(test_judge),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
