/* cli_model: the model commands of the CLI (design.md §8, §10): train and sample
 * on toy stands, and the trainer benchmark. Only the CLI decides how the
 * process dies. */
#include "cli.h"
#include "estimator.h"
#include "mainrun.h"
#include "gate.h"
#include "mainset.h"
#include "paths.h"
#include "speed.h"
#include "gemm.h"
#include "model.h"
#include "opts.h"
#include "patch.h"
#include "train.h"
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>


/* Toy data until the teacher supplies stands: patches of toy stands (patch.h). */
static cs_status toy_data(patch_set **out, long nstands, double d, unsigned long seed, double scale)
{
    patch_set *ps;
    cs_status st = patch_set_alloc(&ps, (int)(64 * nstands));
    if (!st) st = patch_set_add_toy(ps, (int)nstands, d, seed);
    if (!st) st = patch_set_standardise(ps, scale > 0 ? scale : patch_set_rms(ps));
    if (st) { patch_set_free(ps); return st; }
    *out = ps;
    return CS_OK;
}

int cli_cmd_train(int argc, char **argv)
{
    const char *arm = "joint", *ckpt = NULL;
    long steps = 2000, batch = 64, width = 64, depth = 3, heads = 4, mlp = 256, seed = 1, stands = 8, every = 200,
         pair = 0;
    double lr = 2e-3, d = 4.5;
    const opt_spec o[] = {
        {"arm", OPT_CHOICE, &arm, 0, 0, "joint (attention across the patch) or indep (each token alone; default joint)", .choices = CLI_ARMS},
        {"steps", OPT_LONG, &steps, 1, 1e9, "optimiser steps (default 2000)"},
        {"batch", OPT_LONG, &batch, 1, 4096, "patches per step (default 64)"},
        {"lr", OPT_DOUBLE, &lr, 1e-12, 10, "peak learning rate (default 2e-3)"},
        {"width", OPT_LONG, &width, 1, 4096, "model width (default 64)"},
        {"depth", OPT_LONG, &depth, 1, 64, "transformer blocks (default 3)"},
        {"heads", OPT_LONG, &heads, 1, 64, "attention heads (default 4)"},
        {"mlp", OPT_LONG, &mlp, 1, 16384, "MLP width (default 256)"},
        {"pair", OPT_LONG, &pair, 0, 1, "1: pair-aware model with standardised features (design.md §8; default 0)"},
        {"seed", OPT_LONG, &seed, 0, 4294967295.0, "run seed: init/batch/noise streams use 3s+1, 3s+2, 3s+3 (default 1)"},
        {"stands", OPT_LONG, &stands, 1, 100000, "toy training stands, 64 patches each (default 8)"},
        {"spacing", OPT_DOUBLE, &d, 0.1, 100, "toy stand spacing in m (default 4.5)"},
        {"ckpt", OPT_STR, &ckpt, 0, 0, "checkpoint file; resumed from when it exists (default none)"},
        {"ckpt-every", OPT_LONG, &every, 0, 1e9, "steps between checkpoints (default 200)"},
    };
    const opts_cmd c = {"train",
                        "[options]",
                        "Train the flow-matching generator on toy stands (lattice stands with circular\n"
                        "crowns of a toy teacher, patch.h): a check of the trainer and its checkpoints. The\n"
                        "study's training runs are the E3/E4 units (main-run).",
                        o,
                        sizeof o / sizeof *o,
                        0,
                        0};
    int rc = opts_parse(&c, argc, argv, NULL, NULL);
    if (rc) return opts_exit_code(rc);
    int joint = !strcmp(arm, "joint");
    model_cfg cfg = model_cfg_reference(PATCH_NCOND);
    cfg.C = (int)width;
    cfg.L = (int)depth;
    cfg.H = (int)heads;
    cfg.F = (int)mlp;
    cfg.joint = joint;
    cfg.pair = (int)pair;
    cs_status st = model_cfg_check(&cfg);
    if (st) { opts_usage_error("train", "%s", cs_errmsg()); return 2; }
    patch_set *ps;
    if ((st = toy_data(&ps, stands, d, 1000 + 1000 * (unsigned long)seed, 0))) return cli_fail("train", st);
    /* design.md §5 / paper §4.3: the batched clearance estimator must agree with
     * the canonical one before any training; abort on mismatch. */
    {
        int nchk = ps->n < 16 ? ps->n : 16;
        double *rr = malloc(sizeof(double) * nchk * PATCH_T * PATCH_P), diff = 0;
        if (!rr) { patch_set_free(ps); return cli_fail("train", cs_err(CS_ENOMEM, "out of memory")); }
        for (int k = 0; k < nchk; k++)
            patch_set_radii(ps, k, ps->x1 + (size_t)k * PATCH_T * PATCH_P, rr + (size_t)k * PATCH_T * PATCH_P);
        st = patch_clearance_check(est_clearance, ps->px, ps->py, rr, nchk, &diff);
        free(rr);
        if (st) { patch_set_free(ps); return cli_fail("train", st); }
        fprintf(stderr, "clearance check: batched vs canonical estimator on %d patches, max |diff| %.2g m\n", nchk,
                diff);
    }
    train_opts opt = train_opts_default();
    opt.steps = steps; opt.batch = (int)batch; opt.lr = lr;
    opt.seed_init = 3 * seed + 1; opt.seed_batch = 3 * seed + 2; opt.seed_noise = 3 * seed + 3;
    train *t;
    if ((st = train_alloc(&t, &cfg, ps, &opt))) { patch_set_free(ps); return cli_fail("train", st); }
    if (ckpt && access(ckpt, F_OK) == 0) {
        if ((st = train_load(t, ckpt))) { train_free(t); patch_set_free(ps); return cli_fail("train", st); }
        fprintf(stderr, "resumed from %s at step %ld\n", ckpt, t->step);
    }
    fprintf(stderr, "train: %s arm, %zu parameters, %d patches (scale %.4g m), %ld steps of %d\n",
            joint ? "joint" : "indep", t->m->nparams, ps->n, ps->scale, steps, t->B);
    st = train_run(t, steps, ckpt, every, stderr);
    double l = NAN;
    if (!st) st = train_eval_loss(t, ps, 4, 12345, &l);
    if (!st) printf("final step %ld  train loss %.6f  eval loss %.6f\n", t->step, t->loss, l);
    train_free(t);
    patch_set_free(ps);
    return st ? cli_fail("train", st) : 0;
}

int cli_cmd_sample(int argc, char **argv)
{
    const char *ckpt = NULL;
    long n = 16, seed = 1, steps = 100;
    double d = 4.5;
    const opt_spec o[] = {
        {"ckpt", OPT_STR, &ckpt, 0, 0, "checkpoint written by crownshy train (required)"},
        {"n", OPT_LONG, &n, 1, 4096, "patches to generate from held-out toy stands (default 16)"},
        {"euler", OPT_LONG, &steps, 1, 100000, "Euler steps (default 100)"},
        {"seed", OPT_LONG, &seed, 0, 4294967295.0, "noise seed (default 1)"},
        {"spacing", OPT_DOUBLE, &d, 0.1, 100, "toy stand spacing in m (default 4.5)"},
    };
    const opts_cmd c = {
        "sample",
        "--ckpt FILE [options]",
        "Generate crowns with a trained checkpoint and compare their focal clearances with the toy teacher's.",
        o,
        sizeof o / sizeof *o,
        0,
        0};
    int rc = opts_parse(&c, argc, argv, NULL, NULL);
    if (rc) return opts_exit_code(rc);
    if (!ckpt) { opts_usage_error("sample", "--ckpt is required"); return 2; }
    model *m;
    double scale;
    cs_status st = train_load_model(ckpt, &m, (int)n, &scale);
    if (st) return cli_fail("sample", st);
    patch_set *ps;
    /* held-out toy stands: seeds far from any training seed */
    if ((st = toy_data(&ps, (n + 63) / 64, d, 900000 + (unsigned long)seed, scale))) {
        model_free(m);
        return cli_fail("sample", st);
    }
    const size_t TP = PATCH_T * PATCH_P;
    float *x = malloc(sizeof(float) * n * TP);
    double *rg = malloc(sizeof(double) * n * TP), *rt = malloc(sizeof(double) * n * TP);
    double *gg = malloc(sizeof(double) * n * 3), *gt = malloc(sizeof(double) * n * 3);
    gsl_rng *g = gsl_rng_alloc(gsl_rng_mt19937);
    if (!x || !rg || !rt || !gg || !gt || !g) st = cs_err(CS_ENOMEM, "out of memory");
    if (!st) {
        gsl_rng_set(g, (unsigned long)seed);
        st = model_sample(m, g, (int)n, ps->feat, ps->cond, (int)steps, x);
    }
    if (!st) {
        for (long k = 0; k < n; k++) {
            patch_set_radii(ps, (int)k, x + k * TP, rg + k * TP);
            patch_set_radii(ps, (int)k, ps->x1 + k * TP, rt + k * TP);
        }
        st = patch_focal_clearances(ps->px, ps->py, rg, (int)n, 3, gg);
        if (!st) st = patch_focal_clearances(ps->px, ps->py, rt, (int)n, 3, gt);
    }
    if (!st) {
        printf("patch\tk\tclearance_true_m\tclearance_generated_m\n");
        double e = 0;
        for (long k = 0; k < n; k++)
            for (int j = 0; j < 3; j++) {
                printf("%ld\t%d\t%.6f\t%.6f\n", k, j + 1, gt[k * 3 + j], gg[k * 3 + j]);
                e += fabs(gt[k * 3 + j] - gg[k * 3 + j]);
            }
        fprintf(stderr, "sample: %ld patches, %ld Euler steps, mean |clearance error| %.4f m\n", n, steps,
                e / (3.0 * n));
    }
    free(x); free(rg); free(rt); free(gg); free(gt);
    if (g) gsl_rng_free(g);
    patch_set_free(ps);
    model_free(m);
    return st ? cli_fail("sample", st) : 0;
}

/* ---- bench-model (design.md §10) ------------------------------------------------ */
static void print_stat(const char *key, speed_stat s, const char *fmt)
{
    printf("%s\t", key);
    printf(fmt, s.med);
    printf("\t[");
    printf(fmt, s.lo);
    printf(", ");
    printf(fmt, s.hi);
    printf("]\n");
}

/* Prints a goal and its verdict; returns 1 when it is met. */
static int goal(const char *what, double value, double min, const char *fmt)
{
    char v[64], m[64];
    snprintf(v, sizeof v, fmt, value);
    snprintf(m, sizeof m, fmt, min);
    printf("goal\t%s >= %s\t%s\t%s\n", what, m, v, value >= min ? "PASS" : "FAIL");
    return value >= min;
}

/* E3+E4 as run by the manifest's units (src/base/manifest.h): seeds x (joint, independent) pair-model
 * units, each training epochs x steps per epoch and sampling every eval
 * spacing under three probes; two units at a time on the 2-core machine. */
static cs_status projection(const speed_result *r, double *wall_min, double *unit_j, double *unit_i, long *steps,
                            int *nunits)
{
    mainrun_plan pl;
    mainset_design ds;
    double seeds;
    cs_status st = mainrun_plan_get("full", &pl);
    if (!st) st = mainset_design_get(&ds);
    if (!st) st = gate_read_value(PATHS_GATE("main"), "seeds", 0, &seeds);
    if (st) return st;
    const long npatch = mainrun_train_patches(&ds, &pl); /* volume 16-stands */
    *steps = (long)pl.epochs * ((npatch + pl.batch - 1) / pl.batch);
    const double euler_calls = (double)(ds.nunseen + ds.nextrap) * MAINSET_NPROBE *
                               ((pl.gen_patches + r->batch - 1) / r->batch) * pl.euler;
    *unit_j = (*steps * r->ms[SPEED_PAIR].med + euler_calls * r->ms[SPEED_PAIR_SAMPLE].med) / 1e3;
    *unit_i = (*steps * r->ms[SPEED_PAIR_INDEP].med + euler_calls * r->ms[SPEED_PAIR_INDEP_SAMPLE].med) / 1e3;
    *nunits = 2 * (int)seeds;
    *wall_min = seeds * (*unit_j + *unit_i) / 2.0 / 60.0;
    return CS_OK;
}

static int bench_path(gemm_isa isa, const model_cfg *cfg, long batch, long rounds, long steps, int *failed)
{
    gemm_set_isa(isa);
    speed_result r;
    cs_status st = speed_run(cfg, (int)batch, (int)rounds, (int)steps, &r);
    if (st) return cli_fail("bench-model", st);
    printf("path\t%s\n", gemm_isa_name());
    print_stat(isa == GEMM_AVX512 ? "fma_peak_gflops_512bit"
               : isa == GEMM_AVX2 ? "fma_peak_gflops_256bit"
                                  : "fma_peak_gflops_scalar",
               r.peak, "%.1f");
    if (isa == GEMM_AVX512) print_stat("fma_peak_gflops_256bit", r.peak256, "%.1f");
    for (int i = 0; i < SPEED_NITEMS; i++) {
        char k[64];
        snprintf(k, sizeof k, "%s_gflops", speed_name((speed_what)i));
        print_stat(k, r.item[i].rate, "%.1f");
        snprintf(k, sizeof k, "%s_of_peak", speed_name((speed_what)i));
        print_stat(k, r.item[i].frac, "%.3f");
        snprintf(k, sizeof k, "%s_ms", speed_name((speed_what)i));
        print_stat(k, r.ms[i], "%.3f");
    }
    const double sps = 1e3 / r.ms[SPEED_PLAIN].med, psps = 1e3 / r.ms[SPEED_PAIR].med;
    printf("plain_train_steps_per_s\t%.2f\npair_train_steps_per_s\t%.2f\n", sps, psps);
    printf("pair_to_plain_step_time\t%.3f\n", r.ms[SPEED_PAIR].med / r.ms[SPEED_PLAIN].med);
    /* one goal per figure, each against this path's peak measured beside it;
     * sgemm is printed as a yardstick and judges nothing (which kernel
     * OpenBLAS picks on a given core is its choice, not ours) */
    int ok = goal("own product, fraction of this path's FMA peak", r.item[SPEED_PRODUCT].frac.med, SPEED_GOAL_PRODUCT,
                  "%.3f");
    ok &= goal("pair model training, fraction of this path's FMA peak", r.item[SPEED_PAIR].frac.med, SPEED_GOAL_TRAIN,
               "%.3f");
    ok &= goal("plain model training, fraction of this path's FMA peak", r.item[SPEED_PLAIN].frac.med, SPEED_GOAL_TRAIN,
               "%.3f");
    ok &= goal("pair model sampling (joint arm), fraction of this path's FMA peak", r.item[SPEED_PAIR_SAMPLE].frac.med,
               SPEED_GOAL_SAMPLE, "%.3f");
    ok &= goal("pair model sampling (independent arm), fraction of this path's FMA peak",
               r.item[SPEED_PAIR_INDEP_SAMPLE].frac.med, SPEED_GOAL_SAMPLE, "%.3f");
    double wall, uj, ui;
    long nsteps;
    int nunits;
    if ((st = projection(&r, &wall, &uj, &ui, &nsteps, &nunits))) return cli_fail("bench-model", st);
    /* these rates x these counts: the whole study's cost is study_cost.sh's */
    printf("projected E3+E4 on this path: %d pair-model units (%ld training steps + evaluation each; joint %.0f s, "
           "independent %.0f s), "
           "two at a time: %.1f min (budget 60 min; CPU time, the teacher's part of a unit left out)\n",
           nunits, nsteps, uj, ui, wall);
    printf("pair_unit_s\tjoint %.17g\tindep %.17g\n", uj, ui);
    *failed += !ok;
    return 0;
}

int cli_cmd_bench_model(int argc, char **argv)
{
    long repeats = 7, steps = 16, batch = 64;
    const char *path = "all";
    const opt_spec o[] = {
        {"repeats", OPT_LONG, &repeats, 1, 15, "rounds, medians and ranges over them are reported (default 7)"},
        {"steps", OPT_LONG, &steps, 1, 1e9, "consecutive training or Euler steps per measurement, after untimed ones on the same model (default 16)"},
        {"batch", OPT_LONG, &batch, 1, 4096, "patches per step (default 64)"},
        {"path", OPT_STR, &path, 0, 0, "all (every vector path this CPU has, widest first), avx512, avx2 or scalar (default all)"},
    };
    const opts_cmd c = {"bench-model", "[options]",
                        "Model speed at the reference configuration of design.md §10 against the core's FMA peak\n"
                        "measured beside every rate, on each gemm path (set OPENBLAS_NUM_THREADS=1).",
                        o, sizeof o / sizeof *o, 0, 0};
    int rc = opts_parse(&c, argc, argv, NULL, NULL);
    if (rc) return opts_exit_code(rc);
    gemm_isa list[3];
    int n = 0;
    if (!strcmp(path, "all")) {
        if (gemm_isa_available(GEMM_AVX512)) list[n++] = GEMM_AVX512;
        if (gemm_isa_available(GEMM_AVX2)) list[n++] = GEMM_AVX2;
        if (!n) list[n++] = GEMM_SCALAR;
    } else {
        gemm_isa want = !strcmp(path, "avx512") ? GEMM_AVX512 : !strcmp(path, "avx2") ? GEMM_AVX2
                      : !strcmp(path, "scalar") ? GEMM_SCALAR : GEMM_AUTO;
        if (want == GEMM_AUTO) {
            opts_usage_error("bench-model", "--path: must be all, avx512, avx2 or scalar, not '%s'", path);
            return 2;
        }
        if (!gemm_isa_available(want)) {
            opts_usage_error("bench-model", "--path %s: this CPU does not have it", path);
            return 2;
        }
        list[n++] = want;
    }
    model_cfg cfg = model_cfg_reference(PATCH_NCOND);
    const char *thr = getenv("OPENBLAS_NUM_THREADS");
    printf(
        "model bench: %d blocks, width %d, %d heads, MLP %d, batch %ld x %d tokens, OPENBLAS_NUM_THREADS=%s;\n"
        "median [min, max] of %ld rounds; each rate as a fraction of the FMA peak measured just before and after it\n",
        cfg.L, cfg.C, cfg.H, cfg.F, batch, cfg.T, thr ? thr : "(unset)", repeats);
    int failed = 0;
    for (int k = 0; k < n; k++) {
        rc = bench_path(list[k], &cfg, batch, repeats, steps, &failed);
        if (rc) return rc;
    }
    gemm_set_isa(GEMM_AUTO);
    printf("bench-model: %d of %d paths meet every goal\n", n - failed, n);
    return 0;
}
