/* Tests for src/base/cs.c: exit-code mapping and the non-aborting GSL handler. */
#include "testutil.h"
#include "cs.h"
#include <gsl/gsl_sf_log.h>
#include <gsl/gsl_errno.h>

static void test_exit_codes_follow_spec(void **s)
{
    (void)s;
    assert_int_equal(cs_exit_code(CS_OK), 0);
    assert_int_equal(cs_exit_code(CS_EFAIL), 1);
    assert_int_equal(cs_exit_code(CS_EUSAGE), 2);
    assert_int_equal(cs_exit_code(CS_EINPUT), 3);
}

static void test_err_records_message_and_returns_status(void **s)
{
    (void)s;
    cs_status st = cs_err(CS_EINPUT, "%s:%d: field '%s'", "x.tsv", 7, "value");
    assert_int_equal(st, CS_EINPUT);
    assert_string_equal(cs_errmsg(), "x.tsv:7: field 'value'");
}

static void test_gsl_error_is_reported_not_aborted(void **s)
{
    (void)s;
    cs_gsl_install();
    cs_errclear();
    gsl_sf_result r;
    int rc = gsl_sf_log_e(-1.0, &r); /* domain error: default handler would abort */
    assert_int_not_equal(rc, GSL_SUCCESS);
    assert_non_null(strstr(cs_errmsg(), "GSL error"));
}

/* A message that wraps the previous one (cs_err(st, "%s ...", cs_errmsg()))
 * keeps it: the cause survives each layer that adds its context. */
static void test_err_wraps_the_previous_message(void **state)
{
    (void)state;
    cs_err(CS_EINPUT, "ckpt: truncated at byte %d", 17);
    assert_int_equal(cs_err(CS_EINPUT, "%s (delete the checkpoint to restart this run)", cs_errmsg()), CS_EINPUT);
    assert_string_equal(cs_errmsg(), "ckpt: truncated at byte 17 (delete the checkpoint to restart this run)");
    cs_err(CS_EIO, "%s: %s", "outer", cs_errmsg());
    assert_string_equal(cs_errmsg(), "outer: ckpt: truncated at byte 17 (delete the checkpoint to restart this run)");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_exit_codes_follow_spec),
        cmocka_unit_test(test_err_records_message_and_returns_status),
        cmocka_unit_test(test_gsl_error_is_reported_not_aborted),
        cmocka_unit_test(test_err_wraps_the_previous_message),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
