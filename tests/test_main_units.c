/* E3/E4 units at smoke scale (design.md §8): a unit writes the clearance samples
 * behind every W1 of its table and its final weights; `crownshy main-redraw`
 * draws the same samples from the weights alone, bit for bit; every W1 of the
 * table is est_w1 of its samples (claim_main_samples_check). Runs
 * build/crownshy from the repository root (it reads gates/). */
#include "testutil.h"
#include <unistd.h>
#include "claims.h"
#include "mainrun.h"
#include "speed.h"
#include "train.h"
#include "tsv.h"

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
        snprintf(
            args, sizeof args,
            "main-redraw --weights %s/main/weights_s03_%s.ckpt --seed 3 --arm %s --scale smoke --out %s/redraw_%s.tsv",
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
        snprintf(args, sizeof args,
                 "main-redraw --weights %s/main/weights_s03_%s.ckpt --seed 3 --arm %s --scale smoke --out %s/bad.tsv",
                 dir, arm, a ? "joint" : "indep", dir);
        assert_int_equal(tu_run_cli("", args, out, sizeof out), 3);
    }
    /* comparison-dist on these two arms: every patch and source, the summary and the figure patch */
    snprintf(args, sizeof args,
             "comparison-dist --patches 5 --joint %s/main/weights_s03_joint.ckpt --indep "
             "%s/main/weights_s03_indep.ckpt --out %s",
             dir, dir, dir);
    if (tu_run_cli("OPENBLAS_NUM_THREADS=1 ", args, out, sizeof out) != 0) fail_msg("comparison-dist: %s", out);
    {
        tsv *t;
        char p[600];
        snprintf(p, sizeof p, "%s/comparison/dist_patches.tsv", dir);
        assert_int_equal(tsv_read(p, &t), CS_OK);
        assert_int_equal(tsv_nrows(t), 5 * 3 + 5 * 2); /* comparison: teacher, joint, indep; dart: teacher, joint */
        double jm[5];
        int nj = 0;
        for (size_t i = 0; i < tsv_nrows(t); i++)
            if (!strcmp(tsv_str(t, i, "probe"), "comparison") && !strcmp(tsv_str(t, i, "source"), "joint"))
                assert_int_equal(tsv_double(t, i, "median_nn_clearance_m", &jm[nj++]), CS_OK);
        tsv_free(t);
        assert_int_equal(nj, 5);
        snprintf(p, sizeof p, "%s/comparison/dist_summary.tsv", dir);
        assert_int_equal(tsv_read(p, &t), CS_OK);
        assert_int_equal(tsv_nrows(t), 5);
        int fig = atoi(tsv_meta(t, "figure_patch"));
        tsv_free(t);
        int below = 0, equal_before = 0;
        for (int k = 0; k < 5; k++) { below += jm[k] < jm[fig]; equal_before += jm[k] == jm[fig] && k < fig; }
        assert_int_equal(below + equal_before, 2); /* rank floor((5 - 1) / 2) */
        /* the figure patch's crowns, per source: its trees ringed as overlapping
         * are the overlapping count of its row in dist_patches.tsv */
        int want[3] = {-1, -1, -1};
        snprintf(p, sizeof p, "%s/comparison/dist_patches.tsv", dir);
        assert_int_equal(tsv_read(p, &t), CS_OK);
        static const char *srcs[3] = {"teacher", "joint", "indep"};
        for (size_t i = 0; i < tsv_nrows(t); i++) {
            long k, o;
            assert_int_equal(tsv_long(t, i, "patch", &k), CS_OK);
            if (k != fig || strcmp(tsv_str(t, i, "probe"), "comparison")) continue;
            assert_int_equal(tsv_long(t, i, "overlapping", &o), CS_OK);
            for (int a = 0; a < 3; a++) if (!strcmp(tsv_str(t, i, "source"), srcs[a])) want[a] = (int)o;
        }
        tsv_free(t);
        snprintf(p, sizeof p, "%s/comparison/figure_crowns.tsv", dir);
        assert_int_equal(tsv_read(p, &t), CS_OK);
        assert_int_equal(atoi(tsv_meta(t, "figure_patch")), fig);
        assert_int_equal(tsv_nrows(t), 3 * 24 * 97);
        int ringed[3] = {0, 0, 0};
        for (size_t i = 0; i < tsv_nrows(t); i += 97) {
            long tree, o;
            assert_int_equal(tsv_long(t, i, "tree", &tree), CS_OK);
            assert_int_equal(tsv_long(t, i, "overlapping", &o), CS_OK);
            ringed[tree / 24] += (int)o;
        }
        tsv_free(t);
        for (int a = 0; a < 3; a++) assert_int_equal(ringed[a], want[a]);
    }
    char msg[1024];
    int nchecked = 0;
    if (claim_main_samples_check(dir, 3, msg, sizeof msg, &nchecked) != CS_OK) fail_msg("%s", msg);
    assert_int_equal(nchecked, 2 * 5 * 3); /* 2 arms x 5 spacings x 3 probes */
    /* one changed sample changes a W1: the check names the row */
    char p[600], cmd[2600];
    snprintf(p, sizeof p, "%s/main/samples_s03_joint.tsv", dir);
    snprintf(cmd, sizeof cmd,
             "awk -F'\\t' 'BEGIN{OFS=\"\\t\"} !/^#/ && $4==\"generated\" && !done {$5=$5+0.5; done=1} {print}' %s > "
             "%s.x && mv %s.x %s",
             p, p, p, p);
    assert_int_equal(system(cmd), 0);
    assert_int_equal(claim_main_samples_check(dir, 3, msg, sizeof msg, &nchecked), CS_EINVARIANT);
    assert_non_null(strstr(msg, "run_s03_joint.tsv"));
}

/* main-eval evaluates a unit's weights without training: at volume 16-stands
 * the data rows of the unit's main-run table and samples, bit for bit,
 * recording the training record; at volume 96-stands every probe at the unseen spacings and none
 * at the extrapolation spacings, for every reading. A paper-reading unit
 * reruns to the same rows and weights. */
static void test_eval_from_weights_gives_the_unit_rows(void **s)
{
    (void)s;
    const char *dir = tu_tmpdir("main_eval");
    char args[4096], out[8192], p1[600], p2[600];
    snprintf(args, sizeof args, "main-run --reading paper --seed 2 --arm joint --scale smoke --epochs 2 "
             "--samples %s/samples_a.tsv --weights %s/w_a.ckpt --out %s/run_a.tsv", dir, dir, dir);
    if (tu_run_cli("OPENBLAS_NUM_THREADS=1 ", args, out, sizeof out) != 0) fail_msg("main-run: %s", out);
    snprintf(args, sizeof args,
             "main-eval --weights %s/w_a.ckpt --trained %s/run_a.tsv --seed 2 --arm joint --scale smoke "
             "--samples %s/samples_b.tsv --out %s/run_b.tsv",
             dir, dir, dir, dir);
    if (tu_run_cli("OPENBLAS_NUM_THREADS=1 ", args, out, sizeof out) != 0) fail_msg("main-eval: %s", out);
    const char *pairs[2][2] = {{"run_a.tsv", "run_b.tsv"}, {"samples_a.tsv", "samples_b.tsv"}};
    for (int k = 0; k < 2; k++) {
        snprintf(p1, sizeof p1, "%s/%s", dir, pairs[k][0]);
        snprintf(p2, sizeof p2, "%s/%s", dir, pairs[k][1]);
        char *x = data_rows(p1), *y = data_rows(p2);
        assert_true(strlen(x) > 100);
        assert_string_equal(x, y);
        free(x); free(y);
    }
    tsv *t;
    snprintf(p2, sizeof p2, "%s/run_b.tsv", dir);
    assert_int_equal(tsv_read(p2, &t), CS_OK);
    assert_non_null(tsv_meta(t, "trained_teacher_sha256"));
    assert_non_null(strstr(tsv_meta(t, "model"), "reading paper"));
    tsv_free(t);
    /* a re-evaluation of a re-evaluation carries the training record of the
     * run that trained, never its own wall time, commit or date */
    snprintf(args, sizeof args,
             "main-eval --weights %s/w_a.ckpt --trained %s/run_b.tsv --seed 2 --arm joint --scale smoke "
             "--out %s/run_bb.tsv",
             dir, dir, dir);
    if (tu_run_cli("OPENBLAS_NUM_THREADS=1 ", args, out, sizeof out) != 0)
        fail_msg("main-eval of an evaluation: %s", out);
    {
        tsv *ta, *tb, *tbb;
        snprintf(p1, sizeof p1, "%s/run_a.tsv", dir);
        assert_int_equal(tsv_read(p1, &ta), CS_OK);
        snprintf(p1, sizeof p1, "%s/run_b.tsv", dir);
        assert_int_equal(tsv_read(p1, &tb), CS_OK);
        snprintf(p1, sizeof p1, "%s/run_bb.tsv", dir);
        assert_int_equal(tsv_read(p1, &tbb), CS_OK);
        static const char *const kv[][2] = {
            {"wall_s", "trained_wall_s"}, {"git_commit", "trained_git_commit"}, {"date", "trained_date"}};
        for (int k = 0; k < 3; k++) {
            const char *trained = tsv_meta(ta, kv[k][0]);
            assert_non_null(trained);
            if (strcmp(tsv_meta(tb, kv[k][1]), trained))
                fail_msg("run_b %s '%s', the training run's %s '%s'", kv[k][1], tsv_meta(tb, kv[k][1]), kv[k][0],
                         trained);
            if (strcmp(tsv_meta(tbb, kv[k][1]), trained))
                fail_msg("run_bb %s '%s' (run_b's own %s '%s'), the training run's '%s'", kv[k][1],
                         tsv_meta(tbb, kv[k][1]), kv[k][0], tsv_meta(tb, kv[k][0]), trained);
        }
        tsv_free(ta); tsv_free(tb); tsv_free(tbb);
    }
    /* a rerun from scratch: the same rows and weights */
    snprintf(args, sizeof args, "main-run --reading paper --seed 2 --arm joint --scale smoke --epochs 2 "
             "--weights %s/w_c.ckpt --out %s/run_c.tsv", dir, dir);
    if (tu_run_cli("OPENBLAS_NUM_THREADS=1 ", args, out, sizeof out) != 0) fail_msg("main-run: %s", out);
    snprintf(p1, sizeof p1, "%s/run_a.tsv", dir);
    snprintf(p2, sizeof p2, "%s/run_c.tsv", dir);
    char *x = data_rows(p1), *y = data_rows(p2);
    assert_string_equal(x, y);
    free(x); free(y);
    snprintf(args, sizeof args, "cmp %s/w_a.ckpt %s/w_c.ckpt", dir, dir);
    assert_int_equal(system(args), 0);
    /* 96-stands: probes at the unseen spacings only */
    snprintf(
        args, sizeof args,
        "main-eval --volume 96-stands --weights %s/w_a.ckpt --trained %s/run_a.tsv --seed 2 --arm joint --scale smoke "
        "--out %s/run_96_stands.tsv",
        dir, dir, dir);
    if (tu_run_cli("OPENBLAS_NUM_THREADS=1 ", args, out, sizeof out) != 0) fail_msg("main-eval 96-stands: %s", out);
    snprintf(p2, sizeof p2, "%s/run_96_stands.tsv", dir);
    assert_int_equal(tsv_read(p2, &t), CS_OK);
    int unseen = 0, extrap = 0;
    for (size_t i = 0; i < tsv_nrows(t); i++) {
        if (!strcmp(tsv_str(t, i, "split"), "unseen")) unseen++;
        else { extrap++; assert_string_equal(tsv_str(t, i, "probe"), "generated"); }
    }
    assert_int_equal(unseen, 3 * 3);
    assert_int_equal(extrap, 2);
    tsv_free(t);
    /* a volume by any other name is a usage error naming the two */
    snprintf(
        args, sizeof args,
        "main-eval --volume 48-stands --weights %s/w_a.ckpt --trained %s/run_a.tsv --seed 2 --arm joint --scale smoke "
        "--out %s/bad.tsv",
        dir, dir, dir);
    assert_int_equal(tu_run_cli("", args, out, sizeof out), 2);
    assert_non_null(strstr(out, "16-stands"));
    assert_non_null(strstr(out, "96-stands"));
    /* the reading is checked against the weights */
    snprintf(args, sizeof args,
             "main-eval --reading pair --weights %s/w_a.ckpt --trained %s/run_a.tsv --seed 2 --arm joint --scale smoke "
             "--out %s/bad.tsv",
             dir, dir, dir);
    assert_int_equal(tu_run_cli("", args, out, sizeof out), 3);
    assert_non_null(strstr(out, "paper reading"));
}

/* main-redraw --cost counts the model FLOPs of the passes a redraw makes:
 * every row of the unit's run table (spacing x probe) is n_gen patches drawn
 * in chunks of the plan's batch, each chunk one forward pass per Euler step.
 * A probe or spacing the count missed, or a chunk counted at the wrong size,
 * makes the two differ. main-run --cost, before training, counts the same
 * evaluation for the model the unit's options make (a width and depth other
 * than the reference's, so that a cost ignoring them differs). */
static void test_redraw_cost_counts_every_pass_of_the_run(void **s)
{
    (void)s;
    const char *dir = tu_tmpdir("main_cost");
    char args[4096], out[8192];
    snprintf(args, sizeof args,
             "main-run --seed 4 --arm joint --scale smoke --epochs 2 --width 32 --blocks 2 --ckpt %s/c.ckpt --weights %s/w.ckpt "
             "--out %s/run.tsv",
             dir, dir, dir);
    if (tu_run_cli("OPENBLAS_NUM_THREADS=1 ", args, out, sizeof out) != 0) fail_msg("main-run: %s", out);
    snprintf(args, sizeof args, "main-redraw --weights %s/w.ckpt --seed 4 --arm joint --scale smoke --cost", dir);
    if (tu_run_cli("OPENBLAS_NUM_THREADS=1 ", args, out, sizeof out) != 0) fail_msg("main-redraw --cost: %s", out);
    double flops = 0, gflops = 0, cpu = 0;
    const char *line = strstr(out, "redraw_cost\t");
    assert_non_null(line);
    assert_int_equal(sscanf(line, "redraw_cost\tflops %lf\tgflops %lf\tcpu_s %lf", &flops, &gflops, &cpu), 3);
    mainrun_plan pl;
    assert_int_equal(mainrun_plan_get("smoke", &pl), CS_OK);
    model *m = NULL;
    double scl = 0, want = 0;
    char path[600];
    snprintf(path, sizeof path, "%s/w.ckpt", dir);
    assert_int_equal(train_load_model(path, &m, pl.batch, &scl), CS_OK);
    tsv *t;
    snprintf(path, sizeof path, "%s/run.tsv", dir);
    assert_int_equal(tsv_read(path, &t), CS_OK);
    assert_true(tsv_nrows(t) >= 6);
    for (size_t r = 0; r < tsv_nrows(t); r++) {
        double ng;
        assert_int_equal(tsv_double(t, r, "n_gen", &ng), CS_OK);
        assert_true(ng == pl.gen_patches); /* every row drew the plan's patches: the count is exact */
        for (int done = 0; done < (int)ng; done += pl.batch)
            want += pl.euler * speed_forward_flops(&m->cfg, (int)ng - done < pl.batch ? (int)ng - done : pl.batch);
    }
    tsv_free(t);
    model_free(m);
    ASSERT_NEAR(flops, want, 1e-12 * want);
    assert_true(gflops > 0 && cpu > 0);
    snprintf(args, sizeof args,
             "main-run --seed 4 --arm joint --scale smoke --epochs 2 --width 32 --blocks 2 --out %s/x.tsv --cost", dir);
    if (tu_run_cli("OPENBLAS_NUM_THREADS=1 ", args, out, sizeof out) != 0) fail_msg("main-run --cost: %s", out);
    double tf = 0, ef = 0;
    line = strstr(out, "unit_cost\t");
    assert_non_null(line);
    assert_int_equal(sscanf(line, "unit_cost\ttrain_flops %lf\teval_flops %lf", &tf, &ef), 2);
    ASSERT_NEAR(ef, want, 1e-12 * want);
    assert_true(tf > 0);
    snprintf(path, sizeof path, "%s/x.tsv", dir);
    assert_false(access(path, F_OK) == 0); /* --cost runs nothing and writes nothing */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_unit_samples_redraw_bit_for_bit_and_recompute_w1),
        cmocka_unit_test(test_eval_from_weights_gives_the_unit_rows),
        cmocka_unit_test(test_redraw_cost_counts_every_pass_of_the_run),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
