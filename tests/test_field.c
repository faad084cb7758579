/* Tests for src/forest/field.c (raw field table loader, summary, reference table)
 * and the pure helpers of src/forest/fieldsim.c. The fixture
 * tests/data/field_synthetic.tsv is SYNTHETIC (invented for tests). */
#include "testutil.h"
#include "field.h"
#include "fieldsim.h"
#include "exp_common.h"
#include "estimator.h"

#define FIXTURE "tests/data/field_synthetic.tsv"

static const char *write_table(const char *name, const char *body)
{
    static char path[600];
    snprintf(path, sizeof path, "%s/t.tsv", tu_tmpdir(name));
    tu_write(path, body);
    return path;
}

static void test_direction_words(void **s)
{
    (void)s;
    assert_int_equal(field_direction("E"), EST_E);
    assert_int_equal(field_direction("north"), EST_N);
    assert_int_equal(field_direction("WEST"), EST_W);
    assert_int_equal(field_direction("s"), EST_S);
    assert_int_equal(field_direction("NE"), -1);
    assert_int_equal(field_direction(""), -1);
}

static void test_fixture_loads_three_trees(void **s)
{
    (void)s;
    field_table ft;
    assert_int_equal(field_table_load(FIXTURE, &ft), CS_OK);
    assert_int_equal(ft.n, 3);
    assert_string_equal(ft.id[2], "t3");
    ASSERT_EXACT(ft.gap[0][EST_W], 0.8);
    ASSERT_EXACT(ft.gap[2][EST_N], 0.0);
    field_table_free(&ft);
}

static void test_fixture_summary(void **s)
{
    (void)s;
    field_table ft;
    assert_int_equal(field_table_load(FIXTURE, &ft), CS_OK);
    field_summary sum;
    assert_int_equal(field_summarize((const double (*)[4])ft.gap, ft.n, &sum), CS_OK);
    assert_int_equal(sum.trees, 3);
    assert_int_equal(sum.measurements, 12);
    /* tree means 0.6, 1.0, 0.25 */
    ASSERT_NEAR(sum.tree_mean_median, 0.6, 1e-15);
    /* sorted gaps 0 .2 .3 .4 .5 .6 .6 .8 1 1 1 1: q25 = .375, q75 = 1 */
    ASSERT_NEAR(sum.spread, 0.625, 1e-15);
    /* t3 has a zero gap: excluded; ratios 2.0 and 1.0 */
    assert_int_equal(sum.aniso_excluded, 1);
    assert_int_equal(sum.aniso_trees, 2);
    ASSERT_NEAR(sum.aniso_median, 1.5, 1e-15);
    field_table_free(&ft);
}

static void test_duplicate_direction_names_line(void **s)
{
    (void)s;
    const char *p =
        write_table("field_dup", "tree\tdirection\tclearance_m\na\tE\t1\na\tN\t1\na\tW\t1\na\teast\t1\na\tS\t1\n");
    field_table ft;
    assert_int_equal(field_table_load(p, &ft), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "t.tsv:5:"));
    assert_non_null(strstr(cs_errmsg(), "'direction'"));
    assert_non_null(strstr(cs_errmsg(), "already"));
}

static void test_missing_direction_names_tree(void **s)
{
    (void)s;
    const char *p = write_table("field_miss", "tree\tdirection\tclearance_m\na\tE\t1\na\tN\t1\na\tW\t1\n");
    field_table ft;
    assert_int_equal(field_table_load(p, &ft), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "t.tsv:2:"));
    assert_non_null(strstr(cs_errmsg(), "no S measurement"));
}

static void test_bad_direction_word(void **s)
{
    (void)s;
    const char *p = write_table("field_word", "tree\tdirection\tclearance_m\na\tNE\t1\n");
    field_table ft;
    assert_int_equal(field_table_load(p, &ft), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "t.tsv:2: field 'direction'"));
}

static void test_non_numeric_clearance(void **s)
{
    (void)s;
    const char *p = write_table("field_num", "tree\tdirection\tclearance_m\na\tE\tabc\n");
    field_table ft;
    assert_int_equal(field_table_load(p, &ft), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "t.tsv:2: field 'clearance_m'"));
}

static void test_missing_column(void **s)
{
    (void)s;
    const char *p = write_table("field_col", "tree\tdir\tclearance_m\na\tE\t1\n");
    field_table ft;
    assert_int_equal(field_table_load(p, &ft), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "field 'direction'"));
}

static void test_reference_table_values(void **s)
{
    (void)s;
    double v;
    int line = 0;
    assert_int_equal(field_reference_get(FIELD_REFERENCE_PATH, "trees", &v, &line), CS_OK);
    ASSERT_EXACT(v, 23);
    assert_true(line > 1);
    assert_int_equal(field_reference_get(FIELD_REFERENCE_PATH, "measurements", &v, NULL), CS_OK);
    ASSERT_EXACT(v, 92);
    assert_int_equal(field_reference_get(FIELD_REFERENCE_PATH, "no_such", &v, NULL), CS_EINPUT);
}

static void test_interp_bracketed(void **s)
{
    (void)s;
    double x[3] = {0.1, 0.2, 0.3}, y[3] = {0.5, 0.7, 0.9}, xi;
    int br;
    assert_int_equal(fs_interp_target(x, y, 3, 0.75, &xi, &br), CS_OK);
    assert_int_equal(br, 1);
    ASSERT_NEAR(xi, 0.225, 1e-15);
    ASSERT_EXACT(fs_round_step(xi, 0.01), 0.23);
}

static void test_interp_not_bracketed_takes_nearest_end(void **s)
{
    (void)s;
    double x[3] = {0.1, 0.2, 0.3}, y[3] = {0.5, 0.7, 0.9}, xi;
    int br;
    assert_int_equal(fs_interp_target(x, y, 3, 1.5, &xi, &br), CS_OK);
    assert_int_equal(br, 0);
    ASSERT_EXACT(xi, 0.3);
}

static void test_fraction_text(void **s)
{
    (void)s;
    char b[32];
    fs_fraction_text(-0.9, b, sizeof b);
    assert_string_equal(b, "-9/10");
    fs_fraction_text(1.0, b, sizeof b);
    assert_string_equal(b, "1");
    fs_fraction_text(33.0 / 35.0, b, sizeof b);
    assert_string_equal(b, "33/35");
}

static void test_trees_roundtrip_and_tamper(void **s)
{
    (void)s;
    const char *dir = tu_tmpdir("fs_roundtrip");
    fs_trees t;
    fs_trees_init(&t);
    stand *sd;
    assert_int_equal(stand_alloc(&sd, stems_lattice, 5.0, 60.0, 0.04, "test/fieldsim", 0), CS_OK);
    double worst = 0;
    assert_int_equal(exp_field_grow_append(sd, NULL, 0.16, 1, 0.04, 0, &t, &worst), CS_OK);
    stand_free(sd);
    assert_true(t.n > 30);
    assert_true(worst <= 1e-9);
    fs_summary sm;
    assert_int_equal(fs_group(&t, 1, 0.04, &sm), CS_OK);
    char sp[700], tp[700];
    snprintf(sp, sizeof sp, "%s/x.tsv", dir);
    fs_trees_path(sp, tp, sizeof tp);
    tsv_writer *w;
    assert_int_equal(tsv_writer_open(&w, tp), CS_OK);
    fs_trees_write(w, &t);
    assert_int_equal(tsv_writer_commit(w), CS_OK);
    assert_int_equal(tsv_writer_open(&w, sp), CS_OK);
    tsv_writer_columns(w, FS_SUMMARY_COLUMNS);
    fs_summary_write_row(w, 1, 0.04, 0.16, 0, &sm);
    assert_int_equal(tsv_writer_commit(w), CS_OK);
    tsv *st;
    fs_trees back;
    assert_int_equal(fs_load_checked(sp, &st, &back), CS_OK);
    assert_int_equal(back.n, t.n);
    tsv_free(st);
    fs_trees_free(&back);
    /* tamper with the summary's spread: the check names the file and field */
    fs_summary bad = sm;
    bad.f.spread += 1e-3;
    assert_int_equal(tsv_writer_open(&w, sp), CS_OK);
    tsv_writer_columns(w, FS_SUMMARY_COLUMNS);
    fs_summary_write_row(w, 1, 0.04, 0.16, 0, &bad);
    assert_int_equal(tsv_writer_commit(w), CS_OK);
    assert_int_equal(fs_load_checked(sp, &st, &back), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "x.tsv:2: field 'spread'"));
    fs_trees_free(&t);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_direction_words),
        cmocka_unit_test(test_fixture_loads_three_trees),
        cmocka_unit_test(test_fixture_summary),
        cmocka_unit_test(test_duplicate_direction_names_line),
        cmocka_unit_test(test_missing_direction_names_tree),
        cmocka_unit_test(test_bad_direction_word),
        cmocka_unit_test(test_non_numeric_clearance),
        cmocka_unit_test(test_missing_column),
        cmocka_unit_test(test_reference_table_values),
        cmocka_unit_test(test_interp_bracketed),
        cmocka_unit_test(test_interp_not_bracketed_takes_nearest_end),
        cmocka_unit_test(test_fraction_text),
        cmocka_unit_test(test_trees_roundtrip_and_tamper),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
