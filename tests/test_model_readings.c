/* Tests for src/claims/model_readings.c: the generator readings table from
 * constructed per-reading run tables (medians over seeds, relative improvement,
 * exact Wilcoxon p, probe ratios, extrapolation advantage, parameters and
 * steps/s from the run tables' provenance); a reading that has not run has no row. */
#include "testutil.h"
#include "model_readings.h"
#include <sys/stat.h>

static void put(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

static void test_table_from_constructed_runs(void **s)
{
    (void)s;
    const char *root = tu_tmpdir("model_readings");
    char p[700], cmd[1200];
    snprintf(cmd, sizeof cmd, "mkdir -p %s/paper-reading/main %s/paper-reading/extrapolation", root, root);
    assert_int_equal(system(cmd), 0);
    /* 3 seeds: joint 0.1 0.3 0.2, indep 0.5 0.7 0.6, shuffled joint 0.4 0.35 0.4
     * (own ratios 4, 1.17, 2: two seeds pass main.gate's 1.3 on their own) */
    snprintf(p, sizeof p, "%s/paper-reading/main/runs.tsv", root);
    put(p, "seed\tarm\tprobe\terror\n"
           "1\tjoint\tgenerated\t0.1\n1\tjoint\tshuffled\t0.4\n1\tindep\tgenerated\t0.5\n"
           "2\tjoint\tgenerated\t0.3\n2\tjoint\tshuffled\t0.35\n2\tindep\tgenerated\t0.7\n"
           "3\tjoint\tgenerated\t0.2\n3\tjoint\tshuffled\t0.4\n3\tindep\tgenerated\t0.6\n");
    snprintf(p, sizeof p, "%s/paper-reading/extrapolation/runs.tsv", root);
    put(p, "seed\tarm\tspacing\tw1\n1\tjoint\t3\t0.1\n1\tjoint\t7.5\t0.3\n1\tindep\t3\t0.2\n1\tindep\t7.5\t0.4\n");
    snprintf(p, sizeof p, "%s/paper-reading/main/baselines.tsv", root);
    put(p, "spacing\tsplit\tdirection_blind_w1\n4\tunseen\t0.7\n5\tunseen\t0.8\n6\tunseen\t0.9\n3\textrap\t0.1\n");
    snprintf(p, sizeof p, "%s/paper-reading/main/run_s01_joint.tsv", root);
    put(p, "# model: T 24 P 24 width 64 blocks 3 heads 4 mlp 256 joint 1 pair 0 params 159000 reading paper\n"
           "# train_time: train_s 300 steps_per_s 49 (this invocation)\nseed\n1\n");
    snprintf(p, sizeof p, "%s/paper-reading/main/run_s01_indep.tsv", root);
    put(p, "# train_time: train_s 300 steps_per_s 51 (this invocation)\nseed\n1\n");
    model_readings_row rows[4];
    size_t n = 0;
    assert_int_equal(model_readings_compute(root, rows, &n), CS_OK);
    assert_int_equal(n, 1);
    const model_readings_row *r = &rows[0];
    assert_string_equal(r->reading, "paper");
    assert_string_equal(r->role, "gated");
    assert_int_equal(r->seeds, 3);
    assert_int_equal(r->params, 159000);
    ASSERT_NEAR(r->joint, 0.2, 1e-12);
    ASSERT_NEAR(r->indep, 0.6, 1e-12);
    ASSERT_NEAR(r->blind, 0.8, 1e-12);
    ASSERT_NEAR(r->rel, 2.0 / 3.0, 1e-12);
    ASSERT_NEAR(r->p, 0.25, 1e-12); /* 3 seeds, all one sign: 2 / 2^3 */
    ASSERT_NEAR(r->shuf_joint, 2.0, 1e-12);
    assert_int_equal(r->coupled, 2);
    assert_true(isnan(r->shuf_indep) && isnan(r->rot_joint));
    ASSERT_NEAR(r->ex_lo, 0.5, 1e-12);
    ASSERT_NEAR(r->ex_hi, 0.25, 1e-12);
    ASSERT_NEAR(r->steps_per_s, 50, 1e-12);
    /* the training speed is written as a provenance line, never as a data
     * column: the data rows of a rerun must equal the frozen ones */
    char out[600];
    snprintf(out, sizeof out, "%s/summary.tsv", root);
    assert_int_equal(model_readings_write(out, root, rows, n, 0, NULL), CS_OK);
    FILE *f = fopen(out, "r");
    assert_non_null(f);
    char line[4096];
    int meta = 0, cols = 0;
    while (fgets(line, sizeof line, f)) {
        if (!strncmp(line, "# steps_per_s_paper: 50 ", 24)) meta = 1;
        if (!strncmp(line, "reading\t", 8)) cols = strstr(line, "steps_per_s") == NULL ? 1 : -1;
    }
    fclose(f);
    assert_int_equal(meta, 1);
    assert_int_equal(cols, 1);
    /* the written table checks against the rows it came from; one changed cell
     * is refused, naming the file, the line and the column */
    assert_int_equal(model_readings_check(out, rows, n), CS_OK);
    char cmd2[1400];
    snprintf(cmd2, sizeof cmd2, "sed -i 's/\\t0.59999999999999998\\t/\\t0.61\\t/' %s", out);
    assert_int_equal(system(cmd2), 0);
    assert_int_equal(model_readings_check(out, rows, n), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "summary.tsv:"));
    assert_non_null(strstr(cs_errmsg(), "'indep'"));
    /* a seed missing a probe row is refused, naming the file */
    snprintf(p, sizeof p, "%s/paper-reading/main/runs.tsv", root);
    put(p, "seed\tarm\tprobe\terror\n1\tjoint\tgenerated\t0.1\n1\tjoint\tshuffled\t0.4\n1\tindep\tgenerated\t0.5\n"
           "2\tjoint\tgenerated\t0.3\n2\tindep\tgenerated\t0.7\n");
    assert_int_equal(model_readings_compute(root, rows, &n), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "runs.tsv"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_table_from_constructed_runs),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
