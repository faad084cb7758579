/* The write-up's hidden render (design.md §9): the text pdftotext reads back
 * may hold a digit only inside a listed name and no verdict word in any case;
 * each finding names its word and page. The hidden numbers.tex carries the
 * same macros as the shown one. Synthetic texts and claims; tests/tamper.sh
 * renders a tampered copy of the package through verify. */
#include "testutil.h"
#include "audit_render.h"
#include <unistd.h>

/* FAIL items of one scan, joined into buf; returns the count. */
static size_t scan(const char *text, char *buf, size_t n)
{
    checklist cl = {0};
    size_t bad = render_scan_text(text, "paper/main.tex", &cl);
    buf[0] = '\0';
    for (size_t i = 0; i < cl.n; i++) {
        size_t l = strlen(buf);
        snprintf(buf + l, n - l, "%s\n", cl.items[i].msg);
    }
    checklist_free(&cl);
    return bad;
}

/* Fails unless the scan of text finds exactly want findings, listing those it found. */
static void expect_findings(const char *text, size_t want)
{
    char msg[4096];
    size_t bad = scan(text, msg, sizeof msg);
    if (bad != want) fail_msg("observed %zu finding(s), expected %zu: %s", bad, want, msg);
}

static void test_digit_named_with_its_page(void **state)
{
    (void)state;
    char msg[4096];
    size_t bad = scan("The stand HIDDEN m wide.\fSpacing 3.5 m here.\n", msg, sizeof msg);
    if (bad != 1 || !strstr(msg, "'3.5' on page 2")) fail_msg("observed %zu finding(s): %s", bad, msg);
}

static void test_digit_inside_a_word(void **state)
{
    (void)state;
    /* a number glued to a word or a hidden value is still a number */
    expect_findings("x13 HIDDEN45 10^-6\n", 3);
}

static void test_listed_names_pass(void **state)
{
    (void)state;
    expect_findings("(E3), W1; AVX-512, AVX2 and SHA-256: \xe2\x80\x9cteacher-2\xe2\x80\x9d. Wasserstein-1.\n", 0);
}

static void test_listed_name_with_a_suffix_fails(void **state)
{
    (void)state;
    expect_findings("E3.5 W12 AVX-5120\n", 3);
}

static void test_verdict_words_any_case(void **state)
{
    (void)state;
    char msg[4096];
    size_t bad = scan("The gate: PASS. Another: fail, a third (Pending) and NOTREP.\n", msg, sizeof msg);
    if (bad != 4 || !strstr(msg, "the verdict word 'PASS'") || !strstr(msg, "'Pending'"))
        fail_msg("observed %zu finding(s), expected 4: %s", bad, msg);
}

static void test_prose_words_pass(void **state)
{
    (void)state;
    expect_findings("It passes over the data; the passed test and a bypass; HIDDEN HIDDEN.\n", 0);
}

/* The hidden numbers.tex defines every claim and gate macro the shown one
 * does, each printing the hidden word, and the helpers in both forms. */
static void test_hidden_numbers_same_macros(void **state)
{
    (void)state;
    claim_row rows[2];
    claim_result res[2];
    memset(rows, 0, sizeof rows);
    memset(res, 0, sizeof res);
    snprintf(rows[0].macro, sizeof rows[0].macro, "MainRel");
    snprintf(rows[0].gate, sizeof rows[0].gate, "main.gate:rel_improvement_min");
    snprintf(rows[1].macro, sizeof rows[1].macro, "MainJoint");
    snprintf(rows[1].gate, sizeof rows[1].gate, "-");
    res[0].status = res[1].status = VERDICT_PASS;
    snprintf(res[0].text, sizeof res[0].text, "47.6");
    snprintf(res[1].text, sizeof res[1].text, "0.411");
    res[0].gate = VERDICT_PASS;
    claims C = {rows, 2};
    char dir[] = "/tmp/cs_render_XXXXXX", shown[128], hidden[128];
    assert_non_null(mkdtemp(dir));
    snprintf(shown, sizeof shown, "%s/shown.tex", dir);
    snprintf(hidden, sizeof hidden, "%s/hidden.tex", dir);
    assert_int_equal(claims_write_numbers(shown, &C, res, 0), CS_OK);
    assert_int_equal(claims_write_numbers(hidden, &C, res, 1), CS_OK);
    numbers_tex a, b;
    assert_int_equal(numbers_read(shown, &a), CS_OK);
    assert_int_equal(numbers_read(hidden, &b), CS_OK);
    assert_int_equal(a.n, 3);
    assert_int_equal(b.n, a.n);
    for (size_t i = 0; i < a.n; i++) {
        assert_string_equal(a.name[i], b.name[i]);
        if (strcmp(b.value[i], "\\hiddenvalue{}")) fail_msg("%s hidden as '%s'", b.name[i], b.value[i]);
    }
    assert_string_equal(numbers_get(&a, "MainRelGate", NULL), "PASS");
    numbers_free(&a);
    numbers_free(&b);
    FILE *f = fopen(hidden, "r");
    char buf[8192];
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[n] = '\0';
    /* a branch prints both its sides in the render */
    assert_non_null(strstr(buf, "\\newcommand\\ifpass[3]{#2 \\hiddenvalue{} #3}"));
    assert_non_null(strstr(buf, "\\renewcommand\\thesection{\\hiddenvalue}"));
    unlink(shown);
    unlink(hidden);
    rmdir(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_digit_named_with_its_page),
        cmocka_unit_test(test_digit_inside_a_word),
        cmocka_unit_test(test_listed_names_pass),
        cmocka_unit_test(test_listed_name_with_a_suffix_fails),
        cmocka_unit_test(test_verdict_words_any_case),
        cmocka_unit_test(test_prose_words_pass),
        cmocka_unit_test(test_hidden_numbers_same_macros),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
