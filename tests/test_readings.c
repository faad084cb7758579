/* Claim tests of the readings (design.md §7 E0, E1):
 *  - the Mech* macros come from the hard-core figure stand: the frozen
 *    figure_stats.tsv is regrown from its seeds (hard-core c = 0.5, 3.5 m,
 *    L = 36 m) and the claim's value equals the regrown stand's statistic
 *    exactly, while the gate is judged on the lattice ablation;
 *  - the E0 readings table: frozen/readings/summary.tsv is recomputed from
 *    the frozen run tables with the registry's computing functions
 *    (readings_compute) and must agree bit for bit; a changed value is
 *    caught naming file, line and field. */
#include "testutil.h"
#include "unstated.h"
#include "teacher.h"
#include "claims.h"
#include "estimator.h"
#include "exp_common.h"
#include "paths.h"
#include "readings.h"
#include "stand_grow.h"
#include "tsv.h"

static void test_figure_stand_macros_come_from_the_hard_core_stand(void **s)
{
    (void)s;
    claims c;
    assert_int_equal(claims_registry(&c), CS_OK);
    const claim_row *row = claims_find(&c, "MechOn");
    assert_non_null(row);
    assert_string_equal(row->source, "frozen/mechanism/figure_stats.tsv");
    claim_result r;
    claims_eval(row, &r);
    assert_int_equal(r.status, VERDICT_PASS);
    /* the stand shown: hard-core, c = EXP_FIG_C, d = 3.5 m, L = 36 m, seed "fig/mechanism" */
    stand *sd;
    assert_int_equal(stand_alloc(&sd, stems_hardcore, 3.5, EXP_FIG_L, EXP_FIG_C, "fig/mechanism", 0), CS_OK);
    double *rr = malloc(sd->s->n * CROWN_NSEC * sizeof *rr);
    teacher_params p;
    teacher_params_default(&p);
    assert_int_equal(stand_grow(sd, &p, NULL, rr, NULL, NULL), CS_OK);
    double k1 = exp_stand_k1(sd, rr);
    free(rr);
    stand_free(sd);
    printf("MechOn: observed %.17g, regrown figure stand %.17g\n", r.value, k1);
    ASSERT_EXACT(r.value, k1);
    /* the gate is judged on the lattice ablation, whose value differs */
    tsv *t;
    assert_int_equal(tsv_read("frozen/mechanism/ablation.tsv", &t), CS_OK);
    long lr = tsv_find(t, "arm", "both_on");
    assert_true(lr >= 0);
    double lat;
    assert_int_equal(tsv_double(t, (size_t)lr, "k1_m", &lat), CS_OK);
    tsv_free(t);
    printf("MechOn: lattice %.17g; gate detail: %s\n", lat, r.gate_detail);
    assert_true(lat != k1);
    assert_non_null(strstr(r.gate_detail, "judged on the lattice"));
    assert_non_null(strstr(r.where, "figure stand"));
    claims_free(&c);
}

static void test_readings_summary_recomputes_from_the_run_tables(void **s)
{
    (void)s;
    claims c;
    assert_int_equal(claims_registry(&c), CS_OK);
    size_t n = readings_count();
    readings_row *rows = calloc(n, sizeof *rows);
    assert_int_equal(readings_compute(&c, "frozen/readings", rows), CS_OK);
    cs_status st = readings_check("frozen/readings/summary.tsv", rows, n);
    if (st) printf("%s\n", cs_errmsg());
    assert_int_equal(st, CS_OK);
    /* mutual-36m is the adopted reading: its Elong equals the claim's */
    const claim_row *row = claims_find(&c, "Elong");
    claim_result r;
    claims_eval(row, &r);
    for (size_t i = 0; i < n; i++)
        if (!strcmp(rows[i].quantity, "Elong") && !strcmp(rows[i].reading, "mutual-36m")) {
            printf("Elong mutual-36m: observed %.17g, claim %.17g\n", rows[i].value, r.value);
            ASSERT_EXACT(rows[i].value, r.value);
        }
    /* a changed value is named */
    rows[3].value += 1e-9;
    st = readings_check("frozen/readings/summary.tsv", rows, n);
    assert_int_equal(st, CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "summary.tsv:"));
    assert_non_null(strstr(cs_errmsg(), "'value'"));
    free(rows);
    claims_free(&c);
}

static void test_reading_switches_parse_strictly(void **s)
{
    (void)s;
    exp_reading r;
    assert_int_equal(exp_reading_parse(NULL, NULL, &r), CS_OK);
    assert_int_equal(r.one_sided, 0);
    assert_int_equal(r.layout, EXP_LAYOUT_4M_ON_36M);
    assert_int_equal(exp_reading_parse("teacher-1", "5m-on-60m", &r), CS_OK);
    assert_int_equal(r.one_sided, 1);
    assert_int_equal(r.layout, EXP_LAYOUT_5M_ON_60M);
    assert_int_equal(exp_reading_parse(NULL, "4m-on-36m", &r), CS_OK);
    assert_int_equal(r.layout, EXP_LAYOUT_4M_ON_36M);
    exp_reading narrow = {.layout = EXP_LAYOUT_4M_ON_36M}, wide = {.layout = EXP_LAYOUT_5M_ON_60M};
    ASSERT_EXACT(exp_field_d(&narrow), 4.0);
    ASSERT_EXACT(exp_field_L(&narrow), 36.0);
    ASSERT_EXACT(exp_field_d(&wide), 5.0);
    ASSERT_EXACT(exp_field_L(&wide), 60.0);
    ASSERT_EXACT(exp_field_d(NULL), 4.0);
    /* a sensitivity variant: one choice moved, every other the design's */
    assert_int_equal(exp_reading_parse(NULL, NULL, &r), CS_OK);
    assert_int_equal(exp_reading_vary("field_d=3.5", &r), CS_OK);
    assert_int_equal(r.varied, 1);
    ASSERT_EXACT(exp_field_d(&r), 3.5);
    ASSERT_EXACT(exp_field_L(&r), 36.0);
    ASSERT_EXACT(exp_fig_c(&r), EXP_FIG_C);
    assert_int_equal(exp_nres(&r), 48);
    ASSERT_EXACT(r.var.crowns.R_scale, 4.0);
    assert_int_equal(exp_reading_vary("growth_N=32", &r), CS_OK);
    assert_int_equal(exp_nres(&r), 32);
    ASSERT_EXACT(exp_field_d(&r), 4.0);
    {
        exp_reading sr;
        teacher_params tp;
        assert_int_equal(exp_reading_parse(NULL, NULL, &sr), CS_OK);
        EXP_TEACHER_PARAMS(&sr, &tp);
        ASSERT_EXACT(tp.start_frac, 0.05);
        assert_int_equal(exp_reading_vary("start=0.1", &sr), CS_OK);
        EXP_TEACHER_PARAMS(&sr, &tp);
        ASSERT_EXACT(tp.start_frac, 0.1);
        assert_int_equal(tp.nres, 48);
    }
    assert_int_equal(exp_reading_vary("growth_N=32.5", &r), CS_EINPUT);
    assert_int_equal(exp_reading_vary("crown_X=3", &r), CS_EINPUT);
    assert_int_equal(exp_reading_vary("crown_R", &r), CS_EINPUT);
    assert_int_equal(exp_reading_vary("crown_R=-1", &r), CS_EINPUT);
    exp_reading rw;
    assert_int_equal(exp_reading_parse(NULL, "5m-on-60m", &rw), CS_OK);
    assert_int_equal(exp_reading_vary("field_L=44", &rw), CS_EINPUT);
    /* every choice of the sensitivity list is a valid switch at each of its values */
    size_t nc;
    const unstated_choice *uc = unstated_list(&nc);
    for (size_t i = 0; i < nc; i++)
        for (int k = 0; k < uc[i].nvalues; k++) {
            char spec[64];
            snprintf(spec, sizeof spec, "%s=%.17g", uc[i].name, uc[i].values[k]);
            exp_reading v;
            assert_int_equal(exp_reading_parse(NULL, NULL, &v), CS_OK);
            assert_int_equal(exp_reading_vary(spec, &v), CS_OK);
            if (strcmp(uc[i].name, "dieback"))
                assert_true(k < uc[i].nvalues / 2 ? uc[i].values[k] < uc[i].ours : uc[i].values[k] > uc[i].ours);
        }
    assert_int_equal(exp_reading_parse("teacher-2-arc", NULL, &r), CS_OK);
    assert_int_equal(r.dieback, TEACHER_DIEBACK_NEIGHBOURS);
    assert_int_equal(r.one_sided, 0);
    assert_int_equal(exp_reading_parse("teacher-2-target", NULL, &r), CS_OK);
    assert_int_equal(r.dieback, TEACHER_DIEBACK_TARGET);
    {
        prov pt;
        char *av[] = {"x"};
        exp_prov_begin(&pt, "test", &r, 1, av);
        assert_string_equal(pt.teacher_version, "teacher-2-target");
    }
    /* the one-sided die-back as a sensitivity unit: the reading teacher-1 */
    assert_int_equal(exp_reading_parse(NULL, NULL, &r), CS_OK);
    assert_int_equal(exp_reading_vary("dieback=3", &r), CS_OK);
    assert_int_equal(r.one_sided, 1);
    assert_int_equal(r.dieback, TEACHER_DIEBACK_OWN);
    {
        prov pt;
        char *av[] = {"x"};
        exp_prov_begin(&pt, "test", &r, 1, av);
        assert_string_equal(pt.teacher_version, "teacher-1");
    }
    assert_int_equal(exp_reading_vary("dieback=4", &r), CS_EINPUT);
    assert_int_equal(exp_reading_parse("teacher-2-arcs", NULL, &r), CS_EINPUT);
    assert_int_equal(exp_reading_parse("teacher-2x", NULL, &r), CS_EINPUT);
    assert_int_equal(exp_reading_parse("teacher-3", NULL, &r), CS_EINPUT);
    assert_int_equal(exp_reading_parse(NULL, "3m-on-36m", &r), CS_EINPUT);
    /* the provenance names the reading that ran */
    prov p;
    char *argv[] = {"x"};
    exp_reading one = {.one_sided = 1, .layout = EXP_LAYOUT_5M_ON_60M};
    exp_prov_begin(&p, "test", &one, 1, argv);
    assert_string_equal(p.teacher_version, "teacher-1");
    assert_string_equal(p.experiment, "test");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_figure_stand_macros_come_from_the_hard_core_stand),
        cmocka_unit_test(test_readings_summary_recomputes_from_the_run_tables),
        cmocka_unit_test(test_reading_switches_parse_strictly),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
