/* Tests for the claim framework (src/claims/claims.c, src/audit/verify.c, src/audit/audit.c):
 * malformed registries, tampered numbers.tex, gate judgement in claims. */
#include "testutil.h"
#include "claims.h"
#include "verify.h"
#include "audit.h"
#include "paths.h"

static const char *HDR = "macro\tkind\tsource\tfunction\tgate\ttest\tsection\tformat\treference\tparams\n";

static const char *registry(const char *name, const char *rows)
{
    static char path[600];
    char buf[4096];
    snprintf(buf, sizeof buf, "# what: test registry\n%s%s", HDR, rows);
    tu_write_in(path, sizeof path, tu_tmpdir(name), "claims.tsv", buf);
    return path;
}

/* The claim tables and the committed registry file agree: the file is the
 * tables' print byte for byte, and read back it gives the rows the tables
 * give (fields, typed params, lines). A row edited on either side fails. */
static void test_registry_file_is_the_tables_print(void **s)
{
    (void)s;
    if (claims_registry_check(PATHS_CLAIMS)) fail_msg("%s", cs_errmsg());
    claims t, f;
    if (claims_registry(&t)) fail_msg("%s", cs_errmsg());
    if (claims_load(PATHS_CLAIMS, &f)) fail_msg("%s", cs_errmsg());
    assert_int_equal(t.n, f.n);
    for (size_t r = 0; r < t.n; r++) {
        const claim_row *a = &t.rows[r], *b = &f.rows[r];
        if (strcmp(a->macro, b->macro) || strcmp(a->kind, b->kind) || strcmp(a->source, b->source) ||
            strcmp(a->function, b->function) || strcmp(a->gate_reg, b->gate_reg) || strcmp(a->gate, b->gate) ||
            strcmp(a->test, b->test) || strcmp(a->section, b->section) || strcmp(a->format, b->format) ||
            strcmp(a->reference, b->reference) || memcmp(&a->param, &b->param, sizeof a->param) || a->line != b->line)
            fail_msg("%s:%d: row %s of the claim tables and the file disagree", PATHS_CLAIMS, b->line, b->macro);
    }
    claims_free(&t);
    claims_free(&f);
}

/* A copy of the print with one row's reference edited is named at that line. */
static void test_registry_check_names_the_edited_line(void **s)
{
    (void)s;
    char *text;
    size_t len;
    if (claims_registry_text(&text, &len)) fail_msg("%s", cs_errmsg());
    char *row = strstr(text, "\nMechOverlap\t");
    assert_non_null(row);
    int line = 2;
    for (const char *p = text; p < row; p++) line += *p == '\n';
    char *ref = strstr(row, "\t0.00\t");
    assert_non_null(ref);
    ref[4] = '1';
    char path[600], want[64];
    tu_write_in(path, sizeof path, tu_tmpdir("reg_print"), "claims.tsv", text);
    free(text);
    assert_int_equal(claims_registry_check(path), CS_EINVARIANT);
    snprintf(want, sizeof want, "claims.tsv:%d:", line);
    assert_non_null(strstr(cs_errmsg(), want));
    assert_non_null(strstr(cs_errmsg(), "MechOverlap"));
}

static void test_registry_rejects_unknown_kind(void **s)
{
    (void)s;
    const char *p =
        registry("reg_kind", "MainSeeds\tguess\tgates/main.gate\tclaim_design_main_seeds\t-\tt\t4.4\t%.0f\t12\t-\n");
    claims c;
    assert_int_equal(claims_load(p, &c), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "claims.tsv:3:"));
    assert_non_null(strstr(cs_errmsg(), "'kind'"));
}

static void test_registry_rejects_duplicate_macro(void **s)
{
    (void)s;
    const char *p = registry("reg_dup",
        "MainSeeds\tdesign\tgates/main.gate\tclaim_design_main_seeds\t-\tt\t4.4\t%.0f\t12\t-\n"
        "MainSeeds\tdesign\tgates/main.gate\tclaim_design_main_seeds\t-\tt\t4.4\t%.0f\t12\t-\n");
    claims c;
    assert_int_equal(claims_load(p, &c), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "claims.tsv:4:"));
    assert_non_null(strstr(cs_errmsg(), "duplicate"));
}

static void test_registry_rejects_bad_gate_reference(void **s)
{
    (void)s;
    const char *p = registry(
        "reg_gate", "MainSeeds\tdesign\tgates/main.gate\tclaim_design_main_seeds\tmain:seeds\tt\t4.4\t%.0f\t12\t-\n");
    claims c;
    assert_int_equal(claims_load(p, &c), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "'gate'"));
}

/* A probe row is measured but never gated. */
static void test_registry_rejects_gated_probe_row(void **s)
{
    (void)s;
    const char *p =
        registry("reg_probe", "MainRotJoint\tprobe\tfrozen/extension-pair-16-stands/main/"
                              "runs.tsv\tclaim_main_probe\tmain.gate:shuffle_ratio_min\tt\t5.1\t%.3f\t-\t-\n");
    claims c;
    assert_int_equal(claims_load(p, &c), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "'gate'"));
    assert_non_null(strstr(cs_errmsg(), "probe"));
    p = registry("reg_probe_ok", "MainRotJoint\tprobe\tfrozen/extension-pair-16-stands/main/"
                                 "runs.tsv\tclaim_main_probe\t-\tt\t5.1\t%.3f\t-\t-\n");
    assert_int_equal(claims_load(p, &c), CS_OK);
    claims_free(&c);
}

static void test_registry_rejects_truncated_row(void **s)
{
    (void)s;
    const char *p = registry("reg_trunc", "MainSeeds\tdesign\tgates/main.gate\n");
    claims c;
    assert_int_equal(claims_load(p, &c), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "claims.tsv:3:"));
    assert_non_null(strstr(cs_errmsg(), "'function'"));
}

/* The params column: a fixed set of keys, each value of its key's type;
 * anything else names the file, the line and the field. */
static void test_registry_rejects_bad_params(void **s)
{
    (void)s;
    static const char *bad[][2] = {
        {"colour=red", "unknown key 'colour'"},
        {"bound=middle", "bound='middle' is not one of lo, hi"},
        {"bound=lo;bound=hi", "key 'bound' given twice"},
        {"scale=1e", "scale='1e' is not one finite number"},
        {"spacing=inf", "spacing='inf' is not one finite number"},
        {"arm", "'arm' is not key=value"},
        {"arm=joint;", "empty pair"},
        {"column=k2 m", "column='k2 m' is not a name"},
        {"of=Main2", "of='Main2' is not a macro name"},
        {"of=NoSuchClaim", "of=NoSuchClaim names no row of the registry"},
        {"of=MainSeeds", "of=MainSeeds names the row itself"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        char rows[400];
        snprintf(rows, sizeof rows,
                 "MainSeeds\tdesign\tgates/main.gate\tclaim_design_main_seeds\t-\tt\t4.4\t%%.0f\t12\t%s\n", bad[i][0]);
        const char *p = registry("reg_params", rows);
        claims c;
        if (claims_load(p, &c) != CS_EINPUT) fail_msg("params '%s' accepted", bad[i][0]);
        const char *m = cs_errmsg();
        if (!strstr(m, "claims.tsv:3: field 'params'") || !strstr(m, bad[i][1]))
            fail_msg("params '%s': message '%s', expected '%s'", bad[i][0], m, bad[i][1]);
    }
    /* the typed fields of a good cell */
    const char *p = registry("reg_params_ok",
                             "MainSeeds\tdesign\tgates/main.gate\tclaim_design_main_seeds\t-\tt\t4.4\t%.0f\t12\t-\n"
                             "Toy\tprobe\tx.tsv\tclaim_sens_abroff\t-\tt\t4.4\t%.2f\t-\tarm=indep;probe=rotated;bound=hi;stat=range;column=k2_m;of=MainSeeds;x=6;scale=100;spacing=6.5\n");
    claims c;
    assert_int_equal(claims_load(p, &c), CS_OK);
    const claim_params *q = &c.rows[1].param;
    assert_int_equal(c.rows[0].param.set, 0);
    assert_int_equal(q->set, PARAM_ARM | PARAM_PROBE | PARAM_BOUND | PARAM_STAT | PARAM_COLUMN | PARAM_OF | PARAM_X |
                                 PARAM_SCALE | PARAM_SPACING);
    assert_int_equal(q->arm, ARM_INDEP);
    assert_int_equal(q->probe, PROBE_ROTATED);
    assert_int_equal(q->bound, BOUND_HI);
    assert_int_equal(q->stat, STAT_RANGE);
    assert_string_equal(q->column, "k2_m");
    assert_string_equal(q->of, "MainSeeds");
    if (q->x != 6.0 || q->scale != 100.0 || q->spacing != 6.5)
        fail_msg("x %.17g scale %.17g spacing %.17g, expected 6, 100, 6.5", q->x, q->scale, q->spacing);
    claims_free(&c);
}

/* What a row computes is its params, not its macro: one toy row, the same
 * macro, evaluated with bound=lo and with bound=hi over one table gives its
 * lowest and its highest value (0.25 and 1.75, which cannot coincide);
 * without the bound it fails naming its line, never a default. */
static void test_params_not_the_macro_choose_the_bound(void **s)
{
    (void)s;
    char src[600], rows[1200];
    tu_write_in(src, sizeof src, tu_tmpdir("reg_bound"), "sweep.tsv", "beta\tk1_m\n0\t1.75\n0.5\t9\n0\t0.25\n0\t1\n");
    static const struct { const char *params; verdict status; double want; } k[] = {
        {"bound=lo", VERDICT_PASS, 0.25}, {"bound=hi", VERDICT_PASS, 1.75}, {"-", VERDICT_FAIL, NAN}};
    for (size_t i = 0; i < sizeof k / sizeof *k; i++) {
        snprintf(rows, sizeof rows, "SensAbrOffLo\tprobe\t%s\tclaim_sens_abroff\t-\tt\tE0\t%%.2f\t-\t%s\n", src,
                 k[i].params);
        claims c;
        assert_int_equal(claims_load(registry("reg_bound_reg", rows), &c), CS_OK);
        claim_result r;
        claims_eval(&c.rows[0], &r);
        if (r.status != k[i].status)
            fail_msg("params %s: status %s (%s), expected %s", k[i].params, verdict_name(r.status), r.why,
                     verdict_name(k[i].status));
        if (k[i].status == VERDICT_PASS && r.value != k[i].want)
            fail_msg("params %s: observed %.17g, expected %.17g", k[i].params, r.value, k[i].want);
        if (k[i].status == VERDICT_FAIL && (!strstr(r.why, ":3: field 'params'") || !strstr(r.why, "needs bound")))
            fail_msg("params %s: '%s' does not name the row's line and the missing key", k[i].params, r.why);
        claims_free(&c);
    }
}

/* MainSeeds as a design row: its value is the one gates/main.gate holds (12), read and then contradicted below. */
static const claim_row design_seeds = {.macro = "MainSeeds",
                                       .kind = "design",
                                       .source = "gates/main.gate",
                                       .function = "claim_design_main_seeds",
                                       .gate = "-",
                                       .format = "%.0f"};

/* numbers.tex holding text, in the scratch folder build/test-tmp/<name>, read into nt. */
static cs_status numbers_from(const char *name, const char *text, numbers_tex *nt)
{
    char p[600];
    tu_write_in(p, sizeof p, tu_tmpdir(name), "numbers.tex", text);
    return numbers_read(p, nt);
}

static void test_design_claim_reads_gate_value(void **s)
{
    (void)s;
    claim_result r;
    claims_eval(&design_seeds, &r);
    assert_int_equal(r.status, VERDICT_PASS);
    assert_string_equal(r.text, "12");
    assert_non_null(strstr(r.where, "gates/main.gate:"));
}

static void test_unimplemented_function_is_pending_with_reason(void **s)
{
    (void)s;
    claim_row row = {.macro = "MainRel",
                     .kind = "measured",
                     .source = "frozen/extension-pair-16-stands/main/runs.tsv",
                     .function = "claim_no_such_fn",
                     .gate = "-",
                     .format = "%.1f"};
    claim_result r;
    claims_eval(&row, &r);
    assert_int_equal(r.status, VERDICT_PENDING);
    assert_non_null(strstr(r.why, "claim_no_such_fn"));
}

static void test_tampered_numbers_value_is_named(void **s)
{
    (void)s;
    numbers_tex nt;
    assert_int_equal(numbers_from("nt_tamper", "% x\n\\newcommand{\\MainSeeds}{11}\n", &nt), CS_OK);
    claim_result r;
    claims_eval(&design_seeds, &r);
    char msg[1200];
    assert_int_equal(verify_consistent(&design_seeds, &r, &nt, msg, sizeof msg), VERDICT_FAIL);
    assert_non_null(strstr(msg, "MainSeeds"));
    assert_non_null(strstr(msg, "numbers.tex:2"));
    assert_non_null(strstr(msg, "'11'"));
    numbers_free(&nt);
}

/* A registered frozen file that is missing is a failure, never PENDING
 * (deleting a failing experiment's files must not hide it). */
static void test_missing_registered_source_fails(void **s)
{
    (void)s;
    numbers_tex nt;
    assert_int_equal(numbers_from("nt_pending", "\\newcommand{\\MainRel}{53.6}\n", &nt), CS_OK);
    claim_row row = {.macro = "MainRel",
                     .kind = "measured",
                     .source = "frozen/extension-pair-16-stands/main/none.tsv",
                     .function = "claim_design_main_seeds",
                     .gate = "-",
                     .format = "%.1f"};
    claim_result r;
    claims_eval(&row, &r);
    assert_int_equal(r.status, VERDICT_FAIL);
    assert_non_null(strstr(r.why, "registered frozen file missing"));
    assert_non_null(strstr(r.why, "frozen/extension-pair-16-stands/main/none.tsv"));
    char msg[1200];
    assert_int_equal(verify_consistent(&row, &r, &nt, msg, sizeof msg), VERDICT_FAIL);
    numbers_free(&nt);
}

static void test_truncated_numbers_tex_is_input_error(void **s)
{
    (void)s;
    numbers_tex nt;
    assert_int_equal(numbers_from("nt_trunc", "\\newcommand{\\MainRel}{\\pending{Mai\n", &nt), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "numbers.tex:1:"));
    assert_non_null(strstr(cs_errmsg(), "MainRel"));
}

static void test_gate_failure_is_consistent_but_fails_verify(void **s)
{
    (void)s;
    /* A claim whose value fails its gate: consistent with a paper that says
     * FAIL, and a failure for verify. */
    numbers_tex nt;
    const char *tex = "\\newcommand{\\MainRel}{12.0}\n\\newcommand{\\MainRelGate}{FAIL}\n";
    assert_int_equal(numbers_from("gate_fail", tex, &nt), CS_OK);
    claim_row row = {.macro = "MainRel",
                     .kind = "measured",
                     .source = "x",
                     .function = "f",
                     .gate = "main.gate:rel_improvement_min",
                     .format = "%.1f"};
    claim_result r;
    memset(&r, 0, sizeof r);
    r.status = VERDICT_PASS;
    claim_set_value(&row, &r, 12.0);
    claim_judge(&row, &r, GATE_GE, 0.12);
    assert_int_equal(r.gate, VERDICT_FAIL);
    char msg[1200];
    assert_int_equal(verify_consistent(&row, &r, &nt, msg, sizeof msg), VERDICT_PASS);
    assert_int_equal(verify_claim(&row, &r, &nt, msg, sizeof msg), VERDICT_FAIL);
    assert_non_null(strstr(msg, "main.gate:rel_improvement_min"));
    numbers_free(&nt);
}

static void test_negative_zero_prints_unsigned(void **s)
{
    (void)s;
    claim_row row = {.format = "%.2f"};
    claim_result r = {0};
    claim_set_value(&row, &r, -0.0000001);
    assert_string_equal(r.text, "0.00");
    claim_row row2 = {.format = "%+.3f"};
    claim_set_value(&row2, &r, -0.0001);
    assert_string_equal(r.text, "0.000");
    claim_set_value(&row2, &r, 0.364);
    assert_string_equal(r.text, "+0.364");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_registry_rejects_unknown_kind),
        cmocka_unit_test(test_registry_rejects_duplicate_macro),
        cmocka_unit_test(test_registry_rejects_bad_gate_reference),
        cmocka_unit_test(test_registry_rejects_gated_probe_row),
        cmocka_unit_test(test_registry_rejects_truncated_row),
        cmocka_unit_test(test_registry_rejects_bad_params),
        cmocka_unit_test(test_params_not_the_macro_choose_the_bound),
        cmocka_unit_test(test_design_claim_reads_gate_value),
        cmocka_unit_test(test_unimplemented_function_is_pending_with_reason),
        cmocka_unit_test(test_tampered_numbers_value_is_named),
        cmocka_unit_test(test_missing_registered_source_fails),
        cmocka_unit_test(test_truncated_numbers_tex_is_input_error),
        cmocka_unit_test(test_gate_failure_is_consistent_but_fails_verify),
        cmocka_unit_test(test_negative_zero_prints_unsigned),
        cmocka_unit_test(test_registry_file_is_the_tables_print),
        cmocka_unit_test(test_registry_check_names_the_edited_line),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
