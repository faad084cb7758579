/* The documentation audit (design.md §9): a page states a measured number only
 * through a generated region; a typed one, a stale region, an unknown marker,
 * an exemption comment or a broken relative link fails naming page and line;
 * docs_refresh rewrites stale regions. Synthetic claims, pages in a scratch
 * folder; tests/docs.sh does the same on a copy of the package through verify. */
#include "testutil.h"
#include "audit_docs.h"
#include "docs_render.h"
#include "audit_paper.h"

static claim_row rows[3];
static claim_result res[3];
static claims C = {rows, 3};

static void setup_claims(void)
{
    memset(rows, 0, sizeof rows);
    memset(res, 0, sizeof res);
    const char *m[3] = {"MainRel", "MainJoint", "Seeds"}, *k[3] = {"measured", "measured", "design"};
    const char *g[3] = {"main.gate:rel_improvement_min", "-", "-"}, *ref[3] = {"53.6", "0.415", "12"};
    double v[3] = {91.3, 0.0514, 12};
    const char *t[3] = {"91.3", "0.051", "12"};
    for (int i = 0; i < 3; i++) {
        snprintf(rows[i].macro, sizeof rows[i].macro, "%s", m[i]);
        snprintf(rows[i].kind, sizeof rows[i].kind, "%s", k[i]);
        snprintf(rows[i].gate, sizeof rows[i].gate, "%s", g[i]);
        snprintf(rows[i].reference, sizeof rows[i].reference, "%s", ref[i]);
        res[i].status = VERDICT_PASS;
        res[i].value = v[i];
        snprintf(res[i].text, sizeof res[i].text, "%s", t[i]);
        res[i].gate = i == 0 ? VERDICT_PASS : VERDICT_PENDING;
    }
}

/* FAIL items of one page, joined into buf. */
static size_t check(const char *path, char *buf, size_t n)
{
    checklist cl = {0};
    size_t bad = docs_check_page(path, &C, res, &cl);
    buf[0] = '\0';
    for (size_t i = 0; i < cl.n; i++) {
        size_t l = strlen(buf);
        if (cl.items[i].v == VERDICT_FAIL) snprintf(buf + l, n - l, "%s\n", cl.items[i].msg);
    }
    checklist_free(&cl);
    return bad;
}

static void test_clean_page_passes(void **state)
{
    setup_claims();
    const char *d = tu_tmpdir("docs_clean");
    char p[600], out[4096];
    snprintf(p, sizeof p, "%s/other.md", d);
    tu_write(p, "x\n");
    snprintf(p, sizeof p, "%s/page.md", d);
    tu_write(p, "Relative improvement <!--MainRel-->91.3<!--/--> % (paper <!--MainRelPaper-->53.6<!--/-->, gate "
                "<!--MainRelGate-->PASS<!--/-->), 12 seeds,\n"
                "syntax `<!--MainJoint-->...<!--/-->` (a code span: literal), version 1.2.0, host 127.0.0.1, ratio "
                "2.5, see [the other page](other.md#top) and [web](https://example.org).\n");
    size_t bad = check(p, out, sizeof out);
    if (bad) print_error("%s", out);
    assert_int_equal(bad, 0);
}

static void test_typed_number_fails_naming_line(void **state)
{
    setup_claims();
    const char *d = tu_tmpdir("docs_typed");
    char p[600], out[4096];
    snprintf(p, sizeof p, "%s/page.md", d);
    /* ours (0.051 rounds 0.0514) on line 2, the paper's (53.6) on line 3 */
    tu_write(p, "fine\nthe joint error is 0.051 m\nthe paper says **53.6** %\n");
    assert_int_equal(check(p, out, sizeof out), 2);
    char want[700];
    snprintf(want, sizeof want, "%s:2: '0.051' typed by hand", p);
    assert_non_null(strstr(out, want));
    assert_non_null(strstr(out, "claim: MainJoint"));
    snprintf(want, sizeof want, "%s:3: '53.6' typed by hand", p);
    assert_non_null(strstr(out, want));
    assert_non_null(strstr(out, "the reference paper's value 53.6; write <!--MainRelPaper-->53.6<!--/-->"));
    assert_non_null(strstr(out, "write <!--MainJoint-->0.051<!--/-->"));
}

static void test_stale_marker_and_block_fail_and_refresh(void **state)
{
    setup_claims();
    const char *d = tu_tmpdir("docs_stale");
    char p[600], out[4096];
    snprintf(p, sizeof p, "%s/page.md", d);
    tu_write(p,
             "a\n<!-- findings: generated -->\nold text\n<!-- /findings -->\nvalue <!--MainJoint-->0.099<!--/--> m\n");
    size_t bad = check(p, out, sizeof out);
    assert_true(bad >= 1);
    char want[700];
    snprintf(want, sizeof want, "%s:3 differs from a fresh generation", p);
    assert_non_null(strstr(out, want));
    /* the rendering fills the block and the marker */
    char *fresh;
    assert_int_equal(docs_render(p, &C, res, &fresh), CS_OK);
    assert_non_null(strstr(fresh, "**1 reproduced, 0 not reproduced, 0 pending**"));
    if (!strstr(fresh, "| `gates/main.gate` | 1")) print_error("%s", fresh);
    assert_non_null(strstr(fresh, "| `gates/main.gate` | 1 | 0 | 0 | `MainRel` 91.3 / 53.6 |"));
    assert_non_null(strstr(fresh, "<!--MainJoint-->0.051<!--/--> m"));
    free(fresh);
    /* the block alone fixed: the marker line is named, with its claim */
    tu_write(p, "a\n<!-- findings -->\n<!-- /findings -->\nvalue <!--MainJoint-->0.099<!--/--> m\n");
    char *f2;
    assert_int_equal(docs_render(p, &C, res, &f2), CS_OK);
    FILE *f = fopen(p, "w");
    char *nl = strstr(f2, "<!--MainJoint-->");
    fprintf(f, "%.*s<!--MainJoint-->0.099<!--/--> m\n", (int)(nl - f2), f2);
    fclose(f);
    free(f2);
    check(p, out, sizeof out);
    assert_non_null(strstr(out, "claim: MainJoint"));
}

/* a differing line of a generated file is named by the claim whose whole
 * name it holds, never by a shorter claim name inside a longer one */
static void test_generated_line_names_its_whole_claim(void **state)
{
    claim_row duo[2];
    memset(duo, 0, sizeof duo);
    snprintf(duo[0].macro, sizeof duo[0].macro, "MainRel");
    snprintf(duo[1].macro, sizeof duo[1].macro, "PairMainRel");
    claims c_duo = {duo, 2};
    char name[80];
    paper_line_claim(&c_duo, "\\newcommand{\\PairMainRel}{91.0}", name, sizeof name);
    assert_string_equal(name, "PairMainRel");
    paper_line_claim(&c_duo, "\\texttt{PairMainRel} & measured & 53.6 & 91.0\\\\", name, sizeof name);
    assert_string_equal(name, "PairMainRel");
    paper_line_claim(&c_duo, "\\newcommand{\\MainRelGate}{PASS}", name, sizeof name);
    assert_string_equal(name, "MainRel");
    paper_line_claim(&c_duo, "MainRelative\tstand\trange", name, sizeof name);
    assert_string_equal(name, "");
}

/* the findings show a gated claim as its gate judged it: a ratio formed from
 * the shown value is printed beside it; a percent of the judged fraction is not */
static void test_findings_show_the_judged_quantity(void **state)
{
    setup_claims();
    snprintf(rows[0].format, sizeof rows[0].format, "%%.1f");
    res[0].has_observed = 1;
    res[0].gate_observed = 0.913;
    snprintf(res[0].gate_detail, sizeof res[0].gate_detail, "0.913 >= 0.2");
    const char *d = tu_tmpdir("docs_judged");
    char p[600];
    snprintf(p, sizeof p, "%s/page.md", d);
    tu_write(p, "<!-- findings -->\n<!-- /findings -->\n");
    char *fresh;
    assert_int_equal(docs_render(p, &C, res, &fresh), CS_OK);
    if (!strstr(fresh, "`MainRel` 91.3 / 53.6 |")) fail_msg("percent of the judged fraction annotated: %s", fresh);
    free(fresh);
    res[0].gate_observed = 0.521288;
    snprintf(res[0].gate_detail, sizeof res[0].gate_detail, "0.521288 <= 0.5; joint 0.41 < direction-blind 0.79");
    assert_int_equal(docs_render(p, &C, res, &fresh), CS_OK);
    if (!strstr(fresh, "`MainRel` 91.3 (judged 0.521 <= 0.5) / 53.6 |")) fail_msg("judged ratio not shown: %s", fresh);
    free(fresh);
}

static void test_unknown_marker_exemption_and_link_fail(void **state)
{
    setup_claims();
    const char *d = tu_tmpdir("docs_bad");
    char p[600], out[4096];
    snprintf(p, sizeof p, "%s/page.md", d);
    tu_write(p, "x <!--NoSuchClaim-->1<!--/-->\n");
    assert_int_equal(check(p, out, sizeof out), 1);
    assert_non_null(strstr(out, ":1: marker <!--NoSuchClaim--> names no claim"));
    tu_write(p, "ok\n<!-- audit: nocheck -->\nsee [missing](nowhere/README.md)\n");
    assert_int_equal(check(p, out, sizeof out), 2);
    assert_non_null(strstr(out, "page.md:2: comment"));
    assert_non_null(strstr(out, "page.md:3: link to 'nowhere/README.md'"));
    tu_write(p, "<!-- findings -->\nno end\n");
    assert_int_equal(check(p, out, sizeof out), 1);
    assert_non_null(strstr(out, "page.md:1: <!-- findings... has no closing"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_clean_page_passes),
        cmocka_unit_test(test_typed_number_fails_naming_line),
        cmocka_unit_test(test_stale_marker_and_block_fail_and_refresh),
        cmocka_unit_test(test_unknown_marker_exemption_and_link_fail),
        cmocka_unit_test(test_findings_show_the_judged_quantity),
        cmocka_unit_test(test_generated_line_names_its_whole_claim),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
