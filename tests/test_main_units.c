/* E3/E4 units at smoke scale (design.md §8): a unit writes the clearance samples
 * behind every W1 of its table and its final weights; `crownshy main-redraw`
 * draws the same samples from the weights alone, bit for bit; every W1 of the
 * table is est_w1 of its samples (claim_main_samples_check). Runs
 * build/crownshy from the repository root (it reads gates/). */
#include "testutil.h"
#include "claims.h"

static char *data_rows(const char *path)
{
    FILE *f = fopen(path, "r");
    if (!f) fail_msg("cannot open %s", path);
    size_t cap = 1 << 20, n = 0;
    char *b = malloc(cap), line[4096];
    b[0] = '\0';
    while (fgets(line, sizeof line, f)) {
        if (line[0] == '#') continue;
        size_t l = strlen(line);
        if (n + l + 1 > cap) { cap *= 2; b = realloc(b, cap); }
        memcpy(b + n, line, l + 1);
        n += l;
    }
    fclose(f);
    return b;
}

static void test_unit_samples_redraw_bit_for_bit_and_recompute_w1(void **s)
{
    (void)s;
    const char *dir = tu_tmpdir("main_units");
    char args[4096], out[8192];
    for (int a = 0; a < 2; a++) {
        const char *arm = a ? "indep" : "joint";
        snprintf(args, sizeof args, "main-run --seed 3 --arm %s --scale smoke --epochs 2 --ckpt %s/c_%s.ckpt "
                 "--samples %s/main/samples_s03_%s.tsv --weights %s/main/weights_s03_%s.ckpt --out %s/main/run_s03_%s.tsv",
                 arm, dir, arm, dir, arm, dir, arm, dir, arm);
        if (tu_run_cli("OPENBLAS_NUM_THREADS=1 ", args, out, sizeof out) != 0) fail_msg("main-run: %s", out);
        snprintf(args, sizeof args, "main-redraw --weights %s/main/weights_s03_%s.ckpt --seed 3 --arm %s --scale smoke --out %s/redraw_%s.tsv",
                 dir, arm, arm, dir, arm);
        if (tu_run_cli("OPENBLAS_NUM_THREADS=1 ", args, out, sizeof out) != 0) fail_msg("main-redraw: %s", out);
        char p1[600], p2[600];
        snprintf(p1, sizeof p1, "%s/main/samples_s03_%s.tsv", dir, arm);
        snprintf(p2, sizeof p2, "%s/redraw_%s.tsv", dir, arm);
        char *x = data_rows(p1), *y = data_rows(p2);
        assert_true(strlen(x) > 1000);
        assert_string_equal(x, y);
        free(x); free(y);
        /* the weights of the other arm are refused */
        snprintf(args, sizeof args, "main-redraw --weights %s/main/weights_s03_%s.ckpt --seed 3 --arm %s --scale smoke --out %s/bad.tsv",
                 dir, arm, a ? "joint" : "indep", dir);
        assert_int_equal(tu_run_cli("", args, out, sizeof out), 3);
    }
    char msg[1024];
    int nchecked = 0;
    if (claim_main_samples_check(dir, 3, msg, sizeof msg, &nchecked) != CS_OK) fail_msg("%s", msg);
    assert_int_equal(nchecked, 2 * 5 * 3); /* 2 arms x 5 spacings x 3 probes */
    /* one changed sample changes a W1: the check names the row */
    char p[600], cmd[2600];
    snprintf(p, sizeof p, "%s/main/samples_s03_joint.tsv", dir);
    snprintf(cmd, sizeof cmd, "awk -F'\\t' 'BEGIN{OFS=\"\\t\"} !/^#/ && $4==\"generated\" && !done {$5=$5+0.5; done=1} {print}' %s > %s.x && mv %s.x %s", p, p, p, p);
    assert_int_equal(system(cmd), 0);
    assert_int_equal(claim_main_samples_check(dir, 3, msg, sizeof msg, &nchecked), CS_EINVARIANT);
    assert_non_null(strstr(msg, "run_s03_joint.tsv"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_unit_samples_redraw_bit_for_bit_and_recompute_w1),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
