/* cli_model: the model commands of the CLI (design.md §8, §10): train and sample
 * on toy stands, and the trainer benchmark. Only the CLI decides how the
 * process dies. */
#include "cli.h"
#include "estimator.h"
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
    long steps = 2000, batch = 64, width = 64, depth = 3, heads = 4, mlp = 256, seed = 1, stands = 8, every = 200, pair = 0;
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
    const opts_cmd c = {"train", "[options]", "Train the flow-matching generator on toy stands (lattice stands with circular\n"
                        "crowns of a toy teacher, patch.h): a check of the trainer and its checkpoints. The\n"
                        "study's training runs are the E3/E4 units (main-run).", o, sizeof o / sizeof *o, 0, 0};
    int rc = opts_parse(&c, argc, argv, NULL, NULL);
    if (rc) return opts_exit_code(rc);
    int joint = !strcmp(arm, "joint");
    model_cfg cfg = model_cfg_reference(PATCH_NCOND);
    cfg.C = (int)width; cfg.L = (int)depth; cfg.H = (int)heads; cfg.F = (int)mlp; cfg.joint = joint; cfg.pair = (int)pair;
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
        for (int k = 0; k < nchk; k++) patch_set_radii(ps, k, ps->x1 + (size_t)k * PATCH_T * PATCH_P, rr + (size_t)k * PATCH_T * PATCH_P);
        st = patch_clearance_check(est_clearance, ps->px, ps->py, rr, nchk, &diff);
        free(rr);
        if (st) { patch_set_free(ps); return cli_fail("train", st); }
        fprintf(stderr, "clearance check: batched vs canonical estimator on %d patches, max |diff| %.2g m\n", nchk, diff);
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
    const opts_cmd c = {"sample", "--ckpt FILE [options]", "Generate crowns with a trained checkpoint and compare their focal clearances with the toy teacher's.",
                        o, sizeof o / sizeof *o, 0, 0};
    int rc = opts_parse(&c, argc, argv, NULL, NULL);
    if (rc) return opts_exit_code(rc);
    if (!ckpt) { opts_usage_error("sample", "--ckpt is required"); return 2; }
    model *m;
    double scale;
    cs_status st = train_load_model(ckpt, &m, (int)n, &scale);
    if (st) return cli_fail("sample", st);
    patch_set *ps;
    /* held-out toy stands: seeds far from any training seed */
    if ((st = toy_data(&ps, (n + 63) / 64, d, 900000 + (unsigned long)seed, scale))) { model_free(m); return cli_fail("sample", st); }
    const size_t TP = PATCH_T * PATCH_P;
    float *x = malloc(sizeof(float) * n * TP);
    double *rg = malloc(sizeof(double) * n * TP), *rt = malloc(sizeof(double) * n * TP);
    double *gg = malloc(sizeof(double) * n * 3), *gt = malloc(sizeof(double) * n * 3);
    gsl_rng *g = gsl_rng_alloc(gsl_rng_mt19937);
    if (!x || !rg || !rt || !gg || !gt || !g) st = cs_err(CS_ENOMEM, "out of memory");
    if (!st) { gsl_rng_set(g, (unsigned long)seed); st = model_sample(m, g, (int)n, ps->feat, ps->cond, (int)steps, x); }
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
        fprintf(stderr, "sample: %ld patches, %ld Euler steps, mean |clearance error| %.4f m\n", n, steps, e / (3.0 * n));
    }
    free(x); free(rg); free(rt); free(gg); free(gt);
    if (g) gsl_rng_free(g);
    patch_set_free(ps);
    model_free(m);
    return st ? cli_fail("sample", st) : 0;
}

int cli_cmd_bench_model(int argc, char **argv)
{
    long repeats = 5, steps = 20, batch = 64;
    const opt_spec o[] = {
        {"repeats", OPT_LONG, &repeats, 1, 15, "timed repeats, the median is reported (default 5)"},
        {"steps", OPT_LONG, &steps, 1, 1e9, "training steps per repeat (default 20)"},
        {"batch", OPT_LONG, &batch, 1, 4096, "patches per step (default 64)"},
    };
    const opts_cmd c = {"bench-model", "[options]", "Trainer steps/s at the reference configuration of design.md §10 (set OPENBLAS_NUM_THREADS=1).",
                        o, sizeof o / sizeof *o, 0, 0};
    int rc = opts_parse(&c, argc, argv, NULL, NULL);
    if (rc) return opts_exit_code(rc);
    model_cfg cfg = model_cfg_reference(PATCH_NCOND);
    train_bench_result r;
    cs_status st = train_bench(&cfg, (int)batch, (int)steps, (int)repeats, &r);
    if (st) return cli_fail("bench-model", st);
    const char *thr = getenv("OPENBLAS_NUM_THREADS");
    printf("model bench: 3 blocks, width 64, 4 heads, MLP 256, batch %ld x 24 tokens, OPENBLAS_NUM_THREADS=%s, median of %d\n",
           batch, thr ? thr : "(unset)", r.repeats);
    printf("trainer_steps_per_s\t%.2f\n", r.steps_per_s);
    printf("trainer_step_ms\t%.3f\n", r.step_ms_median);
    printf("model_gflops\t%.2f\n", r.model_gflops);
    printf("sgemm_gflops\t%.2f\n", r.sgemm_gflops);
    printf("gemm_fma_gflops\t%.2f\n", r.gemm_fma_gflops);
    printf("gemm_path\t%s\n", gemm_isa_name());
    printf("model_to_sgemm_ratio\t%.3f\n", r.ratio);
    printf("goals: >= 55 steps/s, ratio >= 0.60: %s\n", r.steps_per_s >= 55 && r.ratio >= 0.6 ? "met" : "not met");
    /* design.md §10: the pair-aware model at the same configuration,
     * in the same run; its rate against the same run's gemm_fma rate (the
     * fused product the model runs on) and sgemm rate */
    train_bench_result rp;
    cfg.pair = 1;
    st = train_bench(&cfg, (int)batch, (int)steps, (int)repeats, &rp);
    if (st) return cli_fail("bench-model", st);
    printf("pair model bench: the same configuration with standardised features and pair-aware attention\n");
    printf("pair_trainer_steps_per_s\t%.2f\n", rp.steps_per_s);
    printf("pair_trainer_step_ms\t%.3f\n", rp.step_ms_median);
    printf("pair_model_gflops\t%.2f\n", rp.model_gflops);
    printf("pair_gemm_fma_gflops\t%.2f\n", rp.gemm_fma_gflops);
    printf("pair_model_to_gemm_fma_ratio\t%.3f\n", rp.model_gflops / rp.gemm_fma_gflops);
    printf("pair_model_to_sgemm_ratio\t%.3f\n", rp.ratio);
    printf("pair_to_base_step_time\t%.3f\n", rp.step_ms_median / r.step_ms_median);
    printf("goal: pair model >= 55 steps/s: %s\n", rp.steps_per_s >= 55 ? "met" : "not met");
    return 0;
}

