/* Tests of the claim intervals (src/agree/interval.c, agree.c; design.md
 * §6.1): every measured claim has a stated method; one perturbed replicate
 * row changes a claim's interval and fails the claim test's check, naming
 * the claim; replicates that do not give the claim's value are refused; the
 * statement table is checked against the code; the agreement classes. */
#include "testutil.h"
#include "agree.h"
#include "claims.h"
#include "paths.h"
#include <unistd.h>

static claims g_c;
static interval_table g_it;

/* Copy src to dst, adding delta to the double in column col of the data row
 * whose first fields start with `key` (tab-separated prefix). */
static void perturb_copy(const char *src, const char *dst, const char *key, int col, double delta)
{
    FILE *in = fopen(src, "r"), *out = fopen(dst, "w");
    assert_non_null(in);
    assert_non_null(out);
    char line[8192];
    int done = 0;
    while (fgets(line, sizeof line, in)) {
        if (!done && line[0] != '#' && !strncmp(line, key, strlen(key))) {
            char *f[64] = {0};
            int n = 0;
            line[strcspn(line, "\n")] = '\0';
            for (char *p = strtok(line, "\t"); p && n < 64; p = strtok(NULL, "\t")) f[n++] = p;
            assert_true(col < n);
            char v[64];
            snprintf(v, sizeof v, "%.17g", strtod(f[col], NULL) + delta);
            f[col] = v;
            for (int i = 0; i < n; i++) fprintf(out, "%s%s", i ? "\t" : "", f[i]);
            fputc('\n', out);
            done = 1;
        } else fputs(line, out);
    }
    fclose(in);
    fclose(out);
    assert_true(done);
}

/* Evaluate macro with its source (and, when given, the replicates of its
 * statement) replaced; the interval and the claim test's verdict. */
static verdict eval_with(const char *macro, const char *source, const char *replicates, claim_interval *ci, char *msg,
                         size_t n)
{
    const claim_row *orig = claims_find(&g_c, macro);
    assert_non_null(orig);
    claim_row row = *orig;
    if (source) snprintf(row.source, sizeof row.source, "%s", source);
    interval_table t = g_it;
    interval_spec *specs = malloc(g_it.n * sizeof *specs);
    memcpy(specs, g_it.s, g_it.n * sizeof *specs);
    t.s = specs;
    if (replicates)
        for (size_t i = 0; i < t.n; i++)
            if (!strcmp(specs[i].function, row.function))
                snprintf(specs[i].replicates, sizeof specs[i].replicates, "%s", replicates);
    claim_result r;
    claims_eval(&row, &r);
    if (r.status != VERDICT_PASS) fail_msg("%s from %s: %s", macro, row.source, r.why);
    cs_status st = interval_eval(&t, &row, &r, ci);
    free(specs);
    if (st) { snprintf(msg, n, "%s", cs_errmsg()); return VERDICT_FAIL; }
    return agree_check_interval(PATHS_INTERVALS_OUT, orig, ci, msg, n);
}

static void test_every_measured_claim_has_a_stated_method(void **s)
{
    (void)s;
    for (size_t i = 0; i < g_c.n; i++) {
        if (strcmp(g_c.rows[i].kind, "measured")) continue;
        if (!interval_table_find(&g_it, g_c.rows[i].function))
            fail_msg("%s: %s has no row in %s", g_c.rows[i].macro, g_c.rows[i].function, PATHS_INTERVALS);
    }
}

static void test_frozen_replicates_give_the_generated_intervals(void **s)
{
    (void)s;
    claim_interval ci;
    char msg[1600];
    assert_int_equal(eval_with("Elong", NULL, NULL, &ci, msg, sizeof msg), VERDICT_PASS);
    assert_true(ci.has);
    assert_string_equal(ci.unit, "stand");
    assert_int_equal(ci.n, 28);
    assert_true(ci.lo <= ci.hi);
}

/* The seed bootstrap on the frozen E3 run table of
 * frozen/extension-pair-16-stands/main/ (whatever reading the registry's
 * MainJoint points at): the interval of the frozen rows, written as
 * `crownshy numbers` writes it, against the interval of the rows with one
 * seed changed. */
static void test_one_perturbed_seed_fails_the_claim_test_naming_it(void **s)
{
    (void)s;
    const char *tmp = "build/test_interval_runs.tsv", *ref_tsv = "build/test_interval_ref.tsv";
    /* seed 4's joint error, a little higher but keeping its rank: the median (the claim) stays,
     * the lower end of the interval (an average of order statistics it enters) moves */
    perturb_copy("frozen/extension-pair-16-stands/main/runs.tsv", tmp, "4\tjoint\tgenerated", 3, 0.0003);
    const claim_row *orig = claims_find(&g_c, "MainJoint");
    assert_non_null(orig);
    claim_row row = *orig;
    snprintf(row.source, sizeof row.source, "frozen/extension-pair-16-stands/main/runs.tsv");
    claim_result r;
    claims_eval(&row, &r);
    assert_int_equal(r.status, VERDICT_PASS);
    claim_interval ref, ci;
    assert_int_equal(interval_eval(&g_it, &row, &r, &ref), CS_OK);
    claims one = {&row, 1};
    assert_int_equal(agree_write_intervals(ref_tsv, &one, &ref), CS_OK);
    char msg[1600];
    assert_int_equal(agree_check_interval(ref_tsv, &row, &ref, msg, sizeof msg), VERDICT_PASS);
    snprintf(row.source, sizeof row.source, "%s", tmp);
    claim_result again;
    claims_eval(&row, &again);
    assert_int_equal(again.status, VERDICT_PASS);
    ASSERT_EXACT(again.value, r.value);
    assert_int_equal(interval_eval(&g_it, &row, &again, &ci), CS_OK);
    assert_true(ci.lo != ref.lo || ci.hi != ref.hi);
    assert_int_equal(agree_check_interval(ref_tsv, &row, &ci, msg, sizeof msg), VERDICT_FAIL);
    assert_non_null(strstr(msg, "MainJoint"));
    unlink(tmp);
    unlink(ref_tsv);
}

static void test_one_perturbed_replicate_stand_fails_the_claim_test_naming_it(void **s)
{
    (void)s;
    /* a replicate stand, not the figure's own: the claim's value is unchanged, its interval is not */
    const char *tmp = "build/test_interval_stands.tsv";
    perturb_copy("frozen/replicates/figure_stands.tsv", tmp, "mechanism\tboth_on\t3.5\t7\t", 6, -0.2);
    claim_interval ci, ref;
    char msg[1600];
    assert_int_equal(eval_with("MechOn", NULL, NULL, &ref, msg, sizeof msg), VERDICT_PASS);
    assert_int_equal(eval_with("MechOn", NULL, tmp, &ci, msg, sizeof msg), VERDICT_FAIL);
    assert_true(ci.lo != ref.lo);
    assert_non_null(strstr(msg, "MechOn"));
    unlink(tmp);
}

static void test_replicates_that_miss_the_claim_value_are_refused(void **s)
{
    (void)s;
    /* the figure stand's own row (stand 0) changed: the replicates no longer give the claim */
    const char *tmp = "build/test_interval_own.tsv";
    perturb_copy("frozen/replicates/figure_stands.tsv", tmp, "mechanism\tboth_on\t3.5\t0\t", 6, 0.01);
    claim_interval ci;
    char msg[1600];
    assert_int_equal(eval_with("MechOn", NULL, tmp, &ci, msg, sizeof msg), VERDICT_FAIL);
    assert_non_null(strstr(msg, "MechOn"));
    assert_non_null(strstr(msg, "not the data the claim rests on"));
    unlink(tmp);
}

/* The E2 claims and the E1 sweep's count rest on tables that pool 8 stands
 * per row; the per-stand rows beside each pooled table (<table>_stands,
 * _sectors, sweep_trees) are their replicate units. For each claim: the
 * stand bootstrap over the frozen rows is the generated interval, a copy of
 * the rows gives it too, and the copy with one per-stand row changed fails
 * the claim's test, naming it. */
static const struct { const char *macro, *table, *key; int col; double delta; } stand_cases[] = {
    {"IrredRespLo", "perturb_field_stands.tsv", "6.5\t2\t", 3, -1.0},
    {"IrredTrainRespLo", "perturb_train_stands.tsv", "6.5\t2\t", 3, -1.0},
    {"IrredRespHi", "perturb_field_stands.tsv", "3\t5\t", 3, -1.0},
    {"IrredRespShrink", "refine_field_sectors.tsv", "384\t5.5\t1\t2\t7\t", 5, 0.01},
    {"IrredTrainShrink", "refine_train_sectors.tsv", "384\t5.5\t1\t2\t7\t", 5, 0.01},
    {"IrredStepShrink", "refine_field_sectors.tsv", "384\t3\t4\t1\t0\t", 6, 0.001},
    {"IrredSteps", "reduction_field_sectors.tsv", "4.5\t3\t", 4, 0.05},
    {"IrredMiss", "reduction_field_sectors.tsv", "6.5\t6\t", 4, -0.05},
    {"IrredTrainSteps", "reduction_train_sectors.tsv", "4.5\t3\t", 4, 0.05},
    {"MechHits", "sweep_trees.tsv", "0.089999999999999997\t3.5\t0\t", 7, -0.02},
};

/* Copy src to dst unchanged. */
static void plain_copy(const char *src, const char *dst)
{
    char cmd[3000];
    snprintf(cmd, sizeof cmd, "cp '%s' '%s'", src, dst);
    assert_int_equal(system(cmd), 0);
}

static void test_pooled_claims_get_a_stand_bootstrap(void **s)
{
    (void)s;
    for (size_t i = 0; i < sizeof stand_cases / sizeof *stand_cases; i++) {
        const char *macro = stand_cases[i].macro;
        const claim_row *row = claims_find(&g_c, macro);
        assert_non_null(row);
        claim_interval ci;
        char msg[1600];
        if (eval_with(macro, NULL, NULL, &ci, msg, sizeof msg) != VERDICT_PASS) fail_msg("%s: %s", macro, msg);
        if (!ci.has) fail_msg("%s: no interval (%s)", macro, ci.why);
        assert_string_equal(ci.unit, "stand");
        assert_string_equal(ci.method, "bootstrap");
        assert_int_equal(ci.n, 8);
        assert_true(ci.lo <= ci.hi);
        /* the pooled table and its per-stand rows, copied side by side */
        const char *dir = tu_tmpdir("interval_stands");
        const char *slash = strrchr(row->source, '/');
        char src[700], rows[1400], copy[1400], copy_rows[1400];
        snprintf(src, sizeof src, "%s", row->source);
        snprintf(rows, sizeof rows, "%.*s/%s", (int)(slash - row->source), row->source, stand_cases[i].table);
        snprintf(copy, sizeof copy, "%s%s", dir, slash);
        snprintf(copy_rows, sizeof copy_rows, "%s/%s", dir, stand_cases[i].table);
        plain_copy(src, copy);
        plain_copy(rows, copy_rows);
        claim_interval same;
        if (eval_with(macro, copy, NULL, &same, msg, sizeof msg) != VERDICT_PASS)
            fail_msg("%s from the copy: %s", macro, msg);
        ASSERT_EXACT(same.lo, ci.lo);
        ASSERT_EXACT(same.hi, ci.hi);
        perturb_copy(rows, copy_rows, stand_cases[i].key, stand_cases[i].col, stand_cases[i].delta);
        claim_interval bad;
        if (eval_with(macro, copy, NULL, &bad, msg, sizeof msg) != VERDICT_FAIL)
            fail_msg("%s: one changed row of %s did not fail its claim test", macro, stand_cases[i].table);
        if (!strstr(msg, macro)) fail_msg("%s: the failure does not name the claim: %s", macro, msg);
    }
}

/* The stand bootstrap rests on which stand responded, not only on the pooled
 * counts: one missed response moved from stand 2 to stand 5 at 6.5 m (stand
 * 5 also misses one at 5.5 m) keeps every pooled row and the claim, and
 * moves the interval; the claim test fails, naming the claim. */
static void test_a_moved_response_changes_the_interval_not_the_claim(void **s)
{
    (void)s;
    const char *dir = tu_tmpdir("interval_moved");
    char src[200], mid[200], rows[200];
    snprintf(src, sizeof src, "%.100s/perturb_field.tsv", dir);
    snprintf(mid, sizeof mid, "%.100s/moved.tsv", dir);
    snprintf(rows, sizeof rows, "%.100s/perturb_field_stands.tsv", dir);
    plain_copy("frozen/irreducibility/perturb_field.tsv", src);
    perturb_copy("frozen/irreducibility/perturb_field_stands.tsv", mid, "6.5\t2\t4\t2\t", 3, 1.0);
    perturb_copy(mid, rows, "6.5\t5\t4\t4\t", 3, -1.0);
    claim_interval ref, ci;
    char msg[1600];
    assert_int_equal(eval_with("IrredRespLo", NULL, NULL, &ref, msg, sizeof msg), VERDICT_PASS);
    const claim_row *orig = claims_find(&g_c, "IrredRespLo");
    claim_row row = *orig;
    snprintf(row.source, sizeof row.source, "%s", src);
    claim_result r0, r;
    claims_eval(orig, &r0);
    claims_eval(&row, &r);
    assert_int_equal(r.status, VERDICT_PASS);
    ASSERT_EXACT(r.value, r0.value);
    assert_int_equal(eval_with("IrredRespLo", src, NULL, &ci, msg, sizeof msg), VERDICT_FAIL);
    assert_true(ci.has);
    assert_true(ci.lo != ref.lo || ci.hi != ref.hi);
    assert_non_null(strstr(msg, "IrredRespLo"));
    assert_non_null(strstr(msg, "the replicates it rests on changed"));
}

static void test_a_misstated_method_is_refused(void **s)
{
    (void)s;
    const claim_row *row = claims_find(&g_c, "Elong");
    claim_result r;
    claims_eval(row, &r);
    interval_table t = g_it;
    interval_spec *specs = malloc(g_it.n * sizeof *specs);
    memcpy(specs, g_it.s, g_it.n * sizeof *specs);
    t.s = specs;
    for (size_t i = 0; i < t.n; i++)
        if (!strcmp(specs[i].function, "claim_field_elong")) snprintf(specs[i].unit, sizeof specs[i].unit, "seed");
    claim_interval ci;
    assert_int_equal(interval_eval(&t, row, &r, &ci), CS_EINVARIANT);
    assert_non_null(strstr(cs_errmsg(), "claim_field_elong"));
    free(specs);
}

static void test_agreement_classes(void **s)
{
    (void)s;
    claim_row row = {0};
    snprintf(row.macro, sizeof row.macro, "Toy");
    snprintf(row.kind, sizeof row.kind, "measured");
    snprintf(row.reference, sizeof row.reference, "1.00");
    snprintf(row.format, sizeof row.format, "%%.2f");
    claim_result res = {0};
    res.status = VERDICT_PASS;
    res.value = 1.5;
    claim_interval ci = {0};
    ci.has = 1;
    ci.lo = 0.9;
    ci.hi = 1.6;
    agree_result a;
    agree_judge(NULL, &row, &res, &ci, &a);
    assert_int_equal(a.kind, AGREE_INSIDE);
    ci.lo = 1.2;
    attrib_data none = {0};
    agree_judge(&none, &row, &res, &ci, &a);
    assert_int_equal(a.kind, AGREE_UNEXPLAINED);
    /* a reading at 1.1 shifts [1.2, 1.6] by -0.4 onto the paper's 1.00 */
    attrib_value v = {0};
    snprintf(v.quantity, sizeof v.quantity, "Toy");
    snprintf(v.unit, sizeof v.unit, "toy-reading");
    v.value = 1.1;
    attrib_data one = {&v, 1, 1, 0};
    agree_judge(&one, &row, &res, &ci, &a);
    assert_int_equal(a.kind, AGREE_REACHED);
    assert_non_null(strstr(a.by, "toy-reading"));
    ci.has = 0;
    agree_judge(&one, &row, &res, &ci, &a);
    assert_int_equal(a.kind, AGREE_NOINTERVAL);
}

/* "Reached" is one alternative that reaches the number while every other
 * number of the same experiment that agrees today stays in agreement, at the
 * same fraction of the choice (attrib_reached). Toy (1.5 in [1.2, 1.6],
 * paper 1.00) and Other (2.0 in [1.9, 2.1], paper 2.05, inside) share a
 * section; crown_R 3 moves Toy to 1.1 (reached from t = 0.5) but Other to
 * 2.4 (out beyond t = 0.375); crown_R 5 moves Toy to 1.1 and Other to 2.1. */
/* Two claims of one section: Toy 1.5 in [1.2, 1.6] (paper 1.00) and Other
 * 2.0 in [1.9, 2.1] (paper other_ref); the sensitivity values: the centre,
 * crown_R 3 moving Toy to 1.1 and Other to other_r3, crown_R 5 moving Toy to
 * 1.1 and Other to other_r5; d holds the centre and crown_R 3 until a test
 * lets it see crown_R 5 too (d.n = 6). */
typedef struct {
    claims c;
    claim_row rows[2];
    claim_result res[2];
    claim_interval ci[2];
    attrib_value v[6];
    attrib_data d;
} toy_fixture;

static void toy_fixture_make(toy_fixture *x, const char *other_ref, double other_r3, double other_r5)
{
    memset(x, 0, sizeof *x);
    claim_row *rows = x->rows;
    static const char *mac[2] = {"Toy", "Other"};
    const char *ref[2] = {"1.00", other_ref};
    for (int i = 0; i < 2; i++) {
        snprintf(rows[i].macro, sizeof rows[i].macro, "%s", mac[i]);
        snprintf(rows[i].kind, sizeof rows[i].kind, "measured");
        snprintf(rows[i].reference, sizeof rows[i].reference, "%s", ref[i]);
        snprintf(rows[i].format, sizeof rows[i].format, "%%.2f");
        snprintf(rows[i].source, sizeof rows[i].source, "nowhere/x.tsv");
        snprintf(rows[i].section, sizeof rows[i].section, "3.2");
    }
    x->c.rows = rows;
    x->c.n = 2;
    claim_result *res = x->res;
    res[0].status = res[1].status = VERDICT_PASS;
    res[0].value = 1.5;
    res[1].value = 2.0;
    claim_interval *ci = x->ci;
    ci[0].has = ci[1].has = 1;
    ci[0].lo = 1.2; ci[0].hi = 1.6;
    ci[1].lo = 1.9; ci[1].hi = 2.1;
    attrib_value *v = x->v;
    const struct { const char *q, *u; double x, val; } in[6] = {
        {"Toy", "centre", NAN, 1.5}, {"Other", "centre", NAN, 2.0}, {"Toy", "crown_R", 3, 1.1}, {"Other", "crown_R", 3, other_r3},
        {"Toy", "crown_R", 5, 1.1}, {"Other", "crown_R", 5, other_r5}};
    for (int i = 0; i < 6; i++) {
        snprintf(v[i].quantity, sizeof v[i].quantity, "%s", in[i].q);
        snprintf(v[i].unit, sizeof v[i].unit, "%s", in[i].u);
        v[i].x = in[i].x;
        v[i].value = in[i].val;
        v[i].sens = 1;
    }
    x->d = (attrib_data){v, 4, 0, 1};
}

/* Toy judged: every check is of Toy; Other only constrains which alternative may reach it. */
static void toy_judge(const toy_fixture *x, agree_result *a)
{
    agree_judge(&x->d, &x->rows[0], &x->res[0], &x->ci[0], a);
}

/* Bound to both claims, crown_R 3 alone leaves Toy unexplained for the reason
 * why_r3 names; seeing crown_R 5 too, Toy is reached by it. */
static void toy_reached_by_r5_only(toy_fixture *x, const char *why_r3)
{
    agree_result a;
    attrib_bind(&x->d, &x->c, x->res, x->ci);
    toy_judge(x, &a);
    assert_int_equal(a.kind, AGREE_UNEXPLAINED);
    assert_non_null(strstr(a.by, why_r3));
    x->d.n = 6;
    toy_judge(x, &a);
    assert_int_equal(a.kind, AGREE_REACHED);
    assert_string_equal(a.by, "crown_R 5");
}

static void test_reached_keeps_the_experiment_in_agreement(void **s)
{
    (void)s;
    toy_fixture x;
    toy_fixture_make(&x, "2.05", 2.4, 2.1);
    agree_result a;
    toy_judge(&x, &a); /* unbound: nothing else constrained */
    assert_int_equal(a.kind, AGREE_REACHED);
    toy_reached_by_r5_only(&x, "crown_R 3 (moves Other out)");
    /* a value the alternative could not compute constrains nothing */
    x.v[5].value = NAN;
    toy_judge(&x, &a);
    assert_int_equal(a.kind, AGREE_REACHED);
}

/* A number outside agreement today may not be moved further from the
 * paper's value by the alternative that reaches another (attrib_reached):
 * Other 2.0 in [1.9, 2.1], paper 2.5 (outside); crown_R 3 moves it to 1.6
 * (further off: Toy not reached), crown_R 5 to 2.3 (closer: reached). */
static void test_reached_moves_no_other_number_further_off(void **s)
{
    (void)s;
    toy_fixture x;
    toy_fixture_make(&x, "2.5", 1.6, 2.3);
    x.d.have_gensens = 1; /* a fixture: no training choice to add */
    toy_reached_by_r5_only(&x, "crown_R 3 (moves Other further off)");
}

/* A generator training choice joins the alternatives through its claims: the
 * row computed by the same function on <root>/generator-sensitivity/<choice>/
 * whose params name the paper reading's row (of) is that number under the
 * choice, moved from ours by a fraction; a row of another function is not,
 * nor one naming no row, whatever its macro. */
static void test_training_choices_join_the_alternatives(void **s)
{
    (void)s;
    claims c = {0};
    claim_row rows[5];
    memset(rows, 0, sizeof rows);
    static const char *mac[5] = {"Ratio", "GenStandsRatio", "GenStandsJoint", "Joint", "GenWidthRatio"};
    static const char *src[5] = {
        "frozen/paper-reading/main/run_s*_*.tsv", "frozen/generator-sensitivity/stands-x4/main/run_s*_*.tsv",
        "frozen/generator-sensitivity/stands-x4/main/run_s*_*.tsv", "frozen/paper-reading/main/run_s*_*.tsv",
        "frozen/generator-sensitivity/width-x2/main/run_s*_*.tsv"};
    static const char *fn[5] = {"f_ratio", "f_ratio", "f_other", "f_joint", "f_ratio"};
    static const char *of[5] = {NULL, "Ratio", "Joint", NULL, NULL};
    for (int i = 0; i < 5; i++) {
        if (of[i]) { rows[i].param.set = PARAM_OF; snprintf(rows[i].param.of, sizeof rows[i].param.of, "%s", of[i]); }
        snprintf(rows[i].macro, sizeof rows[i].macro, "%s", mac[i]);
        snprintf(rows[i].kind, sizeof rows[i].kind, i == 0 || i == 3 ? "measured" : "probe");
        snprintf(rows[i].reference, sizeof rows[i].reference, i == 0 ? "2.50" : i == 3 ? "0.415" : "-");
        snprintf(rows[i].format, sizeof rows[i].format, "%%.2f");
        snprintf(rows[i].source, sizeof rows[i].source, "%s", src[i]);
        snprintf(rows[i].function, sizeof rows[i].function, "%s", fn[i]);
        snprintf(rows[i].section, sizeof rows[i].section, "5.1");
    }
    c.rows = rows;
    c.n = 5;
    claim_result res[5] = {{0}};
    const double val[5] = {1.03, 6.13, 0.07, 0.411, 2.2};
    for (int i = 0; i < 5; i++) { res[i].status = VERDICT_PASS; res[i].value = val[i]; }
    claim_interval ci[5] = {{0}};
    ci[0].has = 1; ci[0].lo = 1.02; ci[0].hi = 1.05;
    attrib_data d = {0};
    attrib_bind(&d, &c, res, ci);
    assert_int_equal(d.n, 1);
    assert_string_equal(d.v[0].quantity, "Ratio");
    assert_string_equal(d.v[0].unit, "training stands-x4");
    assert_int_equal(d.v[0].sens, 2);
    if (d.v[0].value != 6.13) fail_msg("value %.17g, expected %.17g", d.v[0].value, 6.13);
    attrib_bind(&d, &c, res, ci); /* bound twice: added once */
    assert_int_equal(d.n, 1);
    agree_result a;
    agree_judge(&d, &rows[0], &res[0], &ci[0], &a);
    assert_int_equal(a.kind, AGREE_REACHED);
    assert_string_equal(a.by, "training stands-x4");
    attrib_free(&d);
}

int main(void)
{
    if (claims_registry(&g_c) != CS_OK || interval_table_load(PATHS_INTERVALS, &g_it) != CS_OK) {
        fprintf(stderr, "%s\n", cs_errmsg());
        return 1;
    }
    const struct CMUnitTest t[] = {
        cmocka_unit_test(test_every_measured_claim_has_a_stated_method),
        cmocka_unit_test(test_reached_moves_no_other_number_further_off),
        cmocka_unit_test(test_training_choices_join_the_alternatives),
        cmocka_unit_test(test_frozen_replicates_give_the_generated_intervals),
        cmocka_unit_test(test_one_perturbed_seed_fails_the_claim_test_naming_it),
        cmocka_unit_test(test_one_perturbed_replicate_stand_fails_the_claim_test_naming_it),
        cmocka_unit_test(test_replicates_that_miss_the_claim_value_are_refused),
        cmocka_unit_test(test_pooled_claims_get_a_stand_bootstrap),
        cmocka_unit_test(test_a_moved_response_changes_the_interval_not_the_claim),
        cmocka_unit_test(test_a_misstated_method_is_refused),
        cmocka_unit_test(test_agreement_classes),
        cmocka_unit_test(test_reached_keeps_the_experiment_in_agreement),
    };
    int rc = cmocka_run_group_tests(t, NULL, NULL);
    interval_table_free(&g_it);
    claims_free(&g_c);
    return rc;
}
