/* Claim tests: one cmocka test per row of the claim tables (named
 * claim_<Macro>). Each recomputes its claim from frozen/ with the library
 * code the pipeline used, and checks it against paper/numbers.tex: the value
 * text, and the gate verdict the paper states. A claim whose experiment has
 * not been frozen must appear as \pending in numbers.tex, with a reason.
 * An honest gate FAIL is consistent (the paper must say FAIL); it is verify,
 * not this test, that reports the failed gate. A measured claim's 95 %
 * interval is recomputed from its replicates and must equal
 * paper/intervals.tsv bit for bit. */
#include "testutil.h"
#include "claims.h"
#include "verify.h"
#include "agree.h"
#include "paths.h"

static numbers_tex g_nt;
static interval_table g_it;

static void claim_test(void **state)
{
    const claim_row *row = *state;
    claim_result r;
    claims_eval(row, &r);
    char msg[1200];
    verdict v = verify_consistent(row, &r, &g_nt, msg, sizeof msg);
    if (v == VERDICT_FAIL) fail_msg("%s", msg);
    if (v == VERDICT_PENDING && !r.why[0]) fail_msg("%s pending without a reason", row->macro);
    if (r.status == VERDICT_PASS && !r.text[0]) fail_msg("%s computed but empty", row->macro);
    if (r.status == VERDICT_PASS && strcmp(row->format, "text") && !isfinite(r.value))
        fail_msg("%s: non-finite value %.17g", row->macro, r.value);
    /* its 95 % interval recomputed from the replicates, bit for bit (design.md §6.1) */
    claim_interval ci;
    if (interval_eval(&g_it, row, &r, &ci) != CS_OK) fail_msg("%s: interval: %s", row->macro, cs_errmsg());
    if (agree_check_interval(PATHS_INTERVALS_OUT, row, &ci, msg, sizeof msg) == VERDICT_FAIL) fail_msg("%s", msg);
    if (!strcmp(row->kind, "measured") && r.status == VERDICT_PASS && !ci.has && !ci.why[0])
        fail_msg("%s: measured, computed, without an interval and without a reason", row->macro);
}

/* Every W1 of the frozen E3/E4 run tables and of the baselines recomputed
 * from the frozen samples behind it (design.md §8), bit for bit: 12 seeds x 2
 * arms x 5 spacings x 3 probes, and 5 spacings x 4 baseline W1. */
static void frozen_samples_give_every_w1(void **state)
{
    (void)state;
    char msg[2600];
    int n = 0;
    if (claim_main_samples_check("frozen/extension-pair-16-stands", 64, msg, sizeof msg, &n) != CS_OK)
        fail_msg("%s", msg);
    assert_int_equal(n, 12 * 2 * 5 * 3 + 5 * 4);
}

/* `test_claims MACRO` (or `make test-claim MACRO=...`) runs that claim's test
 * alone, named claim_MACRO as in audit/claims.tsv's test column. */
int main(int argc, char **argv)
{
    claims c;
    char filter[96];
    if (argc > 1) {
        snprintf(filter, sizeof filter, "claim_%s", argv[1]);
        cmocka_set_test_filter(filter);
    }
    if (claims_registry(&c) != CS_OK) { fprintf(stderr, "%s\n", cs_errmsg()); return 1; }
    if (numbers_read("paper/numbers.tex", &g_nt) != CS_OK) { fprintf(stderr, "%s\n", cs_errmsg()); return 1; }
    if (interval_table_load(PATHS_INTERVALS, &g_it) != CS_OK) { fprintf(stderr, "%s\n", cs_errmsg()); return 1; }
    if (argc > 1) {
        size_t k = 0;
        while (k < c.n && strcmp(c.rows[k].macro, argv[1])) k++;
        if (k == c.n) { fprintf(stderr, "test_claims: no claim %s in the claim tables\n", argv[1]); return 1; }
    }
    struct CMUnitTest *t = calloc(c.n + 1, sizeof *t);
    char (*names)[80] = calloc(c.n, sizeof *names);
    for (size_t i = 0; i < c.n; i++) {
        snprintf(names[i], sizeof names[i], "claim_%s", c.rows[i].macro);
        t[i].name = names[i];
        t[i].test_func = claim_test;
        t[i].initial_state = &c.rows[i];
    }
    t[c.n].name = "frozen_samples_give_every_w1";
    t[c.n].test_func = frozen_samples_give_every_w1;
    int rc = _cmocka_run_group_tests("claims", t, c.n + 1, NULL, NULL);
    free(t); free(names);
    numbers_free(&g_nt);
    interval_table_free(&g_it);
    claims_free(&c);
    return rc;
}
