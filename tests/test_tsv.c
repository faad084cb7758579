/* Tests for src/base/tsv.c: provenance, round-trip of doubles, and errors that
 * name file, line and field (design.md §9, §11). */
#include "testutil.h"
#include "tsv.h"

static const char *fixture(const char *name, const char *text)
{
    static char path[600];
    snprintf(path, sizeof path, "%s/%s", tu_tmpdir(name), "t.tsv");
    tu_write(path, text);
    return path;
}

static void test_reads_meta_header_and_cells(void **s)
{
    (void)s;
    const char *p = fixture(
        "tsv_read", "# experiment: mechanism\n# seeds: 1..8\nbeta\tspacing\tk1\n0.06\t3.5\t0.25\n0.09\t4.5\t-1e-3\n");
    tsv *t = NULL;
    assert_int_equal(tsv_read(p, &t), CS_OK);
    assert_string_equal(tsv_meta(t, "experiment"), "mechanism");
    assert_string_equal(tsv_meta(t, "seeds"), "1..8");
    assert_null(tsv_meta(t, "absent"));
    assert_int_equal(tsv_nrows(t), 2);
    assert_int_equal(tsv_ncols(t), 3);
    double v;
    assert_int_equal(tsv_double(t, 1, "k1", &v), CS_OK);
    ASSERT_EXACT(v, -1e-3);
    assert_int_equal(tsv_line(t, 1), 5);
    assert_int_equal(tsv_find(t, "spacing", "4.5"), 1);
    assert_int_equal(tsv_find(t, "spacing", "9"), -1);
    tsv_free(t);
}

static void test_round_trip_is_bit_exact(void **s)
{
    (void)s;
    const char *dir = tu_tmpdir("tsv_rt");
    char path[600];
    snprintf(path, sizeof path, "%s/sub/x.tsv", dir);
    const double xs[] = {0.1, 1.0 / 3.0, -2.5e-17, 123456789.123456789, 5e-324};
    tsv_writer *w;
    assert_int_equal(tsv_writer_open(&w, path), CS_OK);
    tsv_writer_meta(w, "experiment", "%s", "rt");
    tsv_writer_columns(w, "i\tx");
    for (int i = 0; i < 5; i++) { tsv_writer_long(w, i); tsv_writer_dbl(w, xs[i]); tsv_writer_endrow(w); }
    assert_int_equal(tsv_writer_commit(w), CS_OK);
    tsv *t;
    assert_int_equal(tsv_read(path, &t), CS_OK);
    for (int i = 0; i < 5; i++) {
        double v; long k;
        assert_int_equal(tsv_double(t, i, "x", &v), CS_OK);
        assert_int_equal(tsv_long(t, i, "i", &k), CS_OK);
        ASSERT_EXACT(v, xs[i]);
        assert_int_equal(k, i);
    }
    tsv_free(t);
}

static void test_uncommitted_write_leaves_no_file(void **s)
{
    (void)s;
    const char *dir = tu_tmpdir("tsv_abort");
    char path[600], tmp[700];
    snprintf(path, sizeof path, "%s/y.tsv", dir);
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    tsv_writer *w;
    assert_int_equal(tsv_writer_open(&w, path), CS_OK);
    tsv_writer_columns(w, "a");
    tsv_writer_dbl(w, 1.0);
    tsv_writer_endrow(w);
    struct stat st;
    assert_int_not_equal(stat(path, &st), 0); /* not visible before commit */
    tsv_writer_abort(w);
    assert_int_not_equal(stat(path, &st), 0);
    assert_int_not_equal(stat(tmp, &st), 0);
}

static void test_non_number_names_file_line_field(void **s)
{
    (void)s;
    const char *p = fixture("tsv_nan", "a\tw1\n1\t2\n3\tabc\n");
    tsv *t;
    assert_int_equal(tsv_read(p, &t), CS_OK);
    double v;
    assert_int_equal(tsv_double(t, 1, "w1", &v), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "t.tsv:3:"));
    assert_non_null(strstr(cs_errmsg(), "'w1'"));
    assert_non_null(strstr(cs_errmsg(), "abc"));
    tsv_free(t);
}

static void test_nonfinite_rejected_by_default(void **s)
{
    (void)s;
    const char *p = fixture("tsv_inf", "a\nnan\ninf\n");
    tsv *t;
    assert_int_equal(tsv_read(p, &t), CS_OK);
    double v;
    assert_int_equal(tsv_double(t, 0, "a", &v), CS_EINPUT);
    assert_int_equal(tsv_double_nf(t, 1, "a", &v), CS_OK);
    assert_true(isinf(v));
    tsv_free(t);
}

static void test_missing_field_names_column(void **s)
{
    (void)s;
    const char *p = fixture("tsv_missing", "a\tb\n1\t2\n");
    tsv *t;
    assert_int_equal(tsv_read(p, &t), CS_OK);
    double v;
    assert_int_equal(tsv_double(t, 0, "k3", &v), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "'k3'"));
    assert_non_null(strstr(cs_errmsg(), "t.tsv"));
    tsv_free(t);
}

static void test_truncated_line_is_rejected_with_line(void **s)
{
    (void)s;
    const char *p = fixture("tsv_trunc", "# experiment: x\na\tb\tc\n1\t2\t3\n4\t5\n");
    tsv *t = NULL;
    assert_int_equal(tsv_read(p, &t), CS_EINPUT);
    assert_null(t);
    assert_non_null(strstr(cs_errmsg(), "t.tsv:4:"));
    assert_non_null(strstr(cs_errmsg(), "field 'c'"));
}

static void test_missing_file_is_input_error(void **s)
{
    (void)s;
    tsv *t = NULL;
    assert_int_equal(tsv_read("build/test-tmp/does/not/exist.tsv", &t), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "exist.tsv"));
}

static void test_empty_file_is_input_error(void **s)
{
    (void)s;
    const char *p = fixture("tsv_empty", "# experiment: x\n");
    tsv *t = NULL;
    assert_int_equal(tsv_read(p, &t), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "header"));
}

static void test_no_final_newline_is_truncation(void **s)
{
    (void)s;
    /* A file cut mid-write lacks its final newline: reject rather than read a partial number. */
    const char *p = fixture("tsv_nonl", "a\tb\n1\t2\n3\t4");
    tsv *t = NULL;
    assert_int_equal(tsv_read(p, &t), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "t.tsv:3:"));
}

static void test_bad_meta_line_rejected(void **s)
{
    (void)s;
    const char *p = fixture("tsv_meta", "# no separator here\na\n1\n");
    tsv *t = NULL;
    assert_int_equal(tsv_read(p, &t), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "t.tsv:1:"));
}

static void test_text_cell_missing_column_names_field(void **s)
{
    (void)s;
    const char *p = fixture("tsv_text", "level\taniso_median\n0.04\t1.5\n");
    tsv *t;
    assert_int_equal(tsv_read(p, &t), CS_OK);
    const char *v = NULL;
    assert_int_equal(tsv_text(t, 0, "level", &v), CS_OK);
    assert_string_equal(v, "0.04");
    assert_int_equal(tsv_text(t, 0, "arm", &v), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "t.tsv:2:"));
    assert_non_null(strstr(cs_errmsg(), "'arm'"));
    tsv_free(t);
}

/* Regression (make fuzz, libFuzzer crash in tsv_read): a row with more fields
 * than the header was reported after the table had been freed. */
static void test_extra_field_is_rejected_without_use_after_free(void **s)
{
    (void)s;
    const char *p = fixture("tsv_extra", "# experiment: x\na\tb\n1\t2\t3\n");
    tsv *t = NULL;
    assert_int_equal(tsv_read(p, &t), CS_EINPUT);
    assert_null(t);
    assert_non_null(strstr(cs_errmsg(), "t.tsv:3: 3 fields, header has 2"));
}

/* The crash input itself, kept as found. */
static void test_fuzz_crash_input_is_clean_error(void **s)
{
    (void)s;
    tsv *t = NULL;
    assert_int_equal(tsv_read("tests/data/fuzz/tsv-crash-extra-field.tsv", &t), CS_EINPUT);
    assert_null(t);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_reads_meta_header_and_cells),
        cmocka_unit_test(test_round_trip_is_bit_exact),
        cmocka_unit_test(test_uncommitted_write_leaves_no_file),
        cmocka_unit_test(test_non_number_names_file_line_field),
        cmocka_unit_test(test_nonfinite_rejected_by_default),
        cmocka_unit_test(test_missing_field_names_column),
        cmocka_unit_test(test_truncated_line_is_rejected_with_line),
        cmocka_unit_test(test_missing_file_is_input_error),
        cmocka_unit_test(test_empty_file_is_input_error),
        cmocka_unit_test(test_no_final_newline_is_truncation),
        cmocka_unit_test(test_bad_meta_line_rejected),
        cmocka_unit_test(test_text_cell_missing_column_names_field),
        cmocka_unit_test(test_extra_field_is_rejected_without_use_after_free),
        cmocka_unit_test(test_fuzz_crash_input_is_clean_error),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
