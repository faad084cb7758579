/* Claim tests of the E0 sensitivity (design.md §7 E0 "sensitivity") and of
 * the attribution column of the comparison (design.md §9 "Agreement"):
 *  - frozen/sensitivity/summary.tsv is recomputed from the frozen unit tables
 *    with the registry's computing functions (sens_compute) and agrees bit
 *    for bit; a changed value is caught naming file, line and field;
 *  - the centre run reproduces the frozen full run exactly where its stand
 *    counts are the full run's (the figure stand, E5/E6, the E3 baselines);
 *  - a variant reads a table from the centre only where its choice cannot
 *    change it, and its unit.tsv says so;
 *  - the make units (src/base/manifest.h) are the list of unstated.c;
 *  - attrib_judge on constructed summaries: within 10 %, a reading that
 *    reaches, a span that brackets, unexplained, untested. */
#include "testutil.h"
#include "attrib.h"
#include "claims.h"
#include "paths.h"
#include "sens.h"
#include "tsv.h"
#include "unstated.h"
#include <stdlib.h>
#include <string.h>

static claims g_c;

static void test_summary_recomputes_from_the_unit_tables(void **s)
{
    (void)s;
    size_t n = sens_count();
    sens_row *rows = calloc(n, sizeof *rows);
    cs_status st = sens_compute(&g_c, PATHS_SENS_DIR, rows);
    if (st) printf("%s\n", cs_errmsg());
    assert_int_equal(st, CS_OK);
    st = sens_check(PATHS_SENS_SUMMARY, rows, n);
    if (st) printf("%s\n", cs_errmsg());
    assert_int_equal(st, CS_OK);
    /* a changed value is named */
    rows[5].value += 1e-9;
    assert_int_equal(sens_check(PATHS_SENS_SUMMARY, rows, n), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "field 'value'"));
    free(rows);
}

/* Quantities whose units run at the full run's counts and seeds: the centre
 * row equals the frozen claim exactly. The E3 reference levels are measured at
 * evaluation volume 16-stands, that of the pair extension's first verdicts:
 * they are compared with those claims (PairSixteenStandsMainIso, PairSixteenStandsMainNoise),
 * not with the readings' at 96-stands (design.md §8). */
static void test_centre_equals_the_full_run_where_counts_agree(void **s)
{
    (void)s;
    static const char *same[] = {"MechOn",       "MechCoupOff", "MechCoverOn", "CalibDieback",      "Elong",
                                 "AnisoLattice", "JitterStar",  "JitterAniso", "HardcoreOvershoot", "PcCoupled",
                                 "PcContacted",  "MainIso",     "MainNoise"};
    size_t n = sens_count();
    sens_row *rows = calloc(n, sizeof *rows);
    assert_int_equal(sens_compute(&g_c, PATHS_SENS_DIR, rows), CS_OK);
    for (size_t k = 0; k < sizeof same / sizeof *same; k++) {
        char macro[64];
        snprintf(macro, sizeof macro, "%s%s", strncmp(same[k], "Main", 4) ? "" : "PairSixteenStands", same[k]);
        const claim_row *row = claims_find(&g_c, macro);
        assert_non_null(row);
        claim_result r;
        claims_eval(row, &r);
        assert_int_equal(r.status, VERDICT_PASS);
        int found = 0;
        for (size_t i = 0; i < n; i++)
            if (!strcmp(rows[i].quantity, same[k]) && !strcmp(rows[i].choice, UNSTATED_CENTRE)) {
                if (rows[i].value != r.value)
                    printf("%s: centre %.17g, frozen claim %.17g\n", same[k], rows[i].value, r.value);
                ASSERT_EXACT(rows[i].value, r.value);
                found = 1;
            }
        assert_true(found);
    }
    free(rows);
}

static void test_variants_read_the_centre_only_where_untouched(void **s)
{
    (void)s;
    size_t nc;
    const unstated_choice *ch = unstated_list(&nc);
    for (size_t i = 0; i < nc; i++)
        for (int k = 0; k < ch[i].nvalues; k++) {
            char dir[64], path[300];
            unstated_dirname(&ch[i], ch[i].values[k], dir, sizeof dir);
            snprintf(path, sizeof path, "%s/%s/unit.tsv", PATHS_SENS_DIR, dir);
            tsv *t;
            cs_status st = tsv_read(path, &t);
            if (st) printf("%s\n", cs_errmsg());
            assert_int_equal(st, CS_OK);
            assert_true(tsv_nrows(t) > 10);
            for (size_t r = 0; r < tsv_nrows(t); r++) {
                const char *tab = tsv_str(t, r, "table"), *where = tsv_str(t, r, "folder");
                assert_non_null(tab);
                assert_non_null(where);
                int touched = unstated_touches(&ch[i], tab);
                if (!strcmp(where, "failed")) { assert_true(touched); continue; } /* a finding, with its note */
                assert_string_equal(where, touched ? "here" : UNSTATED_CENTRE);
                snprintf(path, sizeof path, "%s/%s/%s", PATHS_SENS_DIR, touched ? dir : UNSTATED_CENTRE, tab);
                if (!strstr(tab, "figure_crowns")) { /* figure crowns are not frozen (make freeze) */
                    FILE *f = fopen(path, "r");
                    if (!f) printf("missing %s\n", path);
                    assert_non_null(f);
                    fclose(f);
                }
            }
            tsv_free(t);
        }
}

static void test_make_units_are_the_list(void **s)
{
    (void)s;
    FILE *f = fopen("src/base/manifest.h", "r");
    assert_non_null(f);
    static char buf[200000];
    size_t len = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[len] = '\0';
    char *a = strstr(buf, "UNIT(sensitivity, \"summary.tsv\", \"$(foreach u,");
    assert_non_null(a);
    a = strstr(a, "$(foreach u,") + strlen("$(foreach u,");
    char *e = strchr(a, ',');
    assert_non_null(e);
    *e = '\0';
    /* the units: centre, then every (choice, value) of unstated.c, each once */
    char want[4096];
    size_t o = (size_t)snprintf(want, sizeof want, "%s", UNSTATED_CENTRE);
    size_t nc;
    const unstated_choice *ch = unstated_list(&nc);
    for (size_t i = 0; i < nc; i++)
        for (int k = 0; k < ch[i].nvalues; k++) {
            char d[64];
            unstated_dirname(&ch[i], ch[i].values[k], d, sizeof d);
            o += (size_t)snprintf(want + o, sizeof want - o, " %s", d);
        }
    assert_string_equal(a, want);
}

static void push(attrib_data *d, const char *q, const char *unit, double x, double v, int sens)
{
    d->v = realloc(d->v, (d->n + 1) * sizeof *d->v);
    attrib_value *a = &d->v[d->n++];
    memset(a, 0, sizeof *a);
    snprintf(a->quantity, sizeof a->quantity, "%s", q);
    snprintf(a->unit, sizeof a->unit, "%s", unit);
    a->x = x;
    a->value = v;
    a->sens = sens;
}

static void judge(const attrib_data *d, const char *macro, const char *ref, double value, attrib_result *out)
{
    claim_row row;
    memset(&row, 0, sizeof row);
    snprintf(row.macro, sizeof row.macro, "%s", macro);
    snprintf(row.kind, sizeof row.kind, "measured");
    snprintf(row.reference, sizeof row.reference, "%s", ref);
    claim_result res;
    memset(&res, 0, sizeof res);
    res.status = VERDICT_PASS;
    res.value = value;
    attrib_judge(d, &row, &res, out);
}

static void test_attribution_rules(void **s)
{
    (void)s;
    attrib_data d = {0};
    push(&d, "A", "cardinal-one-sided-60m", NAN, 0.50, 0);     /* a reading within 10 % of 0.52 */
    push(&d, "B", "cardinal-one-sided-60m", NAN, 2.0, 0);
    push(&d, "B", "centre", NAN, 1.0, 1);
    push(&d, "B", "crown_R", 3, 0.8, 1);
    push(&d, "B", "crown_R", 5, 1.2, 1);    /* span 0.8..1.2 brackets 1.1 */
    push(&d, "B", "lobing", 0.1, 0.9, 1);
    push(&d, "B", "lobing", 0.3, 0.95, 1);  /* 0.9..1.0: neither near 1.1 nor around it */
    push(&d, "C", "centre", NAN, 1.0, 1);
    push(&d, "C", "crown_R", 3, 0.9, 1);
    push(&d, "C", "crown_R", 5, 1.05, 1);
    attrib_result r;
    judge(&d, "A", "0.52", 0.9, &r);
    assert_int_equal(r.kind, ATTRIB_EXPLAINED);
    assert_string_equal(r.by, "reading cardinal-one-sided-60m");
    judge(&d, "A", "0.52", 0.53, &r);
    assert_int_equal(r.kind, ATTRIB_WITHIN);
    judge(&d, "B", "1.1", 0.5, &r);
    assert_int_equal(r.kind, ATTRIB_EXPLAINED);
    assert_string_equal(r.by, "crown_R");
    judge(&d, "C", "2.0", 1.0, &r);         /* 1.05 is 47 % away, no bracket */
    assert_int_equal(r.kind, ATTRIB_UNEXPLAINED);
    judge(&d, "D", "2.0", 1.0, &r);         /* nothing measured it */
    assert_int_equal(r.kind, ATTRIB_UNTESTED);
    attrib_counts k = {3, 1, 2, 1, 2, 1};
    char line[600];
    attrib_line(&k, 0, line, sizeof line);
    assert_non_null(strstr(line, "1 of 3 measured numbers within 10 %"));
    assert_non_null(strstr(line, "1 attributed"));
    assert_non_null(strstr(line, "2 unexplained (1 of them"));
    free(d.v);
}

/* One cheap unit end to end: a figure choice runs only the figure steps into
 * its folder and names the centre for every other table; a unit that is not
 * in the list is a usage error. */
static void test_a_figure_unit_runs_only_its_tables(void **s)
{
    (void)s;
    static char out[65536];
    char dir[] = "/tmp/crownshy_sens_XXXXXX";
    assert_non_null(mkdtemp(dir));
    char args[512];
    snprintf(args, sizeof args, "sensitivity-run --unit fig_hardcore_0.7 --stands 1 --out %s/fig_hardcore_0.7", dir);
    int rc = tu_run_cli("", args, out, sizeof out);
    if (rc) printf("%s\n", out);
    assert_int_equal(rc, 0);
    char path[600];
    snprintf(path, sizeof path, "%s/fig_hardcore_0.7/unit.tsv", dir);
    tsv *t;
    assert_int_equal(tsv_read(path, &t), CS_OK);
    size_t here = 0;
    for (size_t r = 0; r < tsv_nrows(t); r++) here += !strcmp(tsv_str(t, r, "folder"), "here");
    assert_int_equal(here, 2); /* the figure stand and the point-cloud stands */
    tsv_free(t);
    snprintf(path, sizeof path, "%s/fig_hardcore_0.7/mechanism/figure_stats.tsv", dir);
    FILE *f = fopen(path, "r");
    assert_non_null(f);
    fclose(f);
    snprintf(path, sizeof path, "%s/fig_hardcore_0.7/mechanism/sweep.tsv", dir);
    assert_null(fopen(path, "r"));
    snprintf(args, sizeof args, "sensitivity-run --unit crown_R_3.3 --out %s/x", dir);
    assert_int_equal(tu_run_cli("", args, out, sizeof out), 2);
    assert_non_null(strstr(out, "no unit 'crown_R_3.3'"));
    snprintf(args, sizeof args, "rm -rf %s", dir);
    assert_int_equal(system(args), 0);
}

int main(void)
{
    if (claims_registry(&g_c) != CS_OK) { fprintf(stderr, "%s\n", cs_errmsg()); return 1; }
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_summary_recomputes_from_the_unit_tables),
        cmocka_unit_test(test_centre_equals_the_full_run_where_counts_agree),
        cmocka_unit_test(test_variants_read_the_centre_only_where_untouched),
        cmocka_unit_test(test_make_units_are_the_list),
        cmocka_unit_test(test_attribution_rules),
        cmocka_unit_test(test_a_figure_unit_runs_only_its_tables),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    claims_free(&g_c);
    return rc;
}
