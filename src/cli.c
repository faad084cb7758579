/* crownshy: the one command-line entry point. Only this file decides how the
 * process dies; library calls return a cs_status (SPEC §11 exit codes). */
#include "cs.h"
#include "experiments.h"
#include "audit.h"
#include "claims.h"
#include "verify.h"
#include "gate.h"
#include "tsv.h"
#include "exp_main.h"
#include "exp_comp.h"
#include "exp_field.h"
#include <dirent.h>
#include "estimator.h"
#include "model.h"
#include "patch.h"
#include "train.h"
#include "gemm.h"
#include <errno.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

typedef int (*cmd_fn)(int argc, char **argv);
typedef struct { const char *name; cmd_fn fn; const char *help; } cli_cmd;

static int cmd_version(int argc, char **argv)
{
    (void)argc; (void)argv;
    puts("crownshy 0.1");
    return 0;
}

/* ---- option parsing (shared by the model commands) ---------------------------- */
typedef struct { const char *name; char type; void *dst; const char *help; } cli_opt;

/* Parse "--name value" pairs; 2 on a usage error (message printed), 1 on --help. */
static int parse_opts(const char *cmd, int argc, char **argv, const cli_opt *opts, int nopt,
                      const char *synopsis)
{
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            printf("usage: crownshy %s %s\n\noptions:\n", cmd, synopsis);
            for (int k = 0; k < nopt; k++) printf("  --%-14s %s\n", opts[k].name, opts[k].help);
            printf("\nexit codes: 0 ok, 2 usage error, 3 bad or missing input\n");
            return 1;
        }
        int k = 0;
        for (; k < nopt; k++)
            if (!strncmp(argv[i], "--", 2) && !strcmp(argv[i] + 2, opts[k].name)) break;
        if (k == nopt) { fprintf(stderr, "crownshy %s: unknown option '%s' (see --help)\n", cmd, argv[i]); return 2; }
        if (i + 1 >= argc) { fprintf(stderr, "crownshy %s: option --%s needs a value\n", cmd, opts[k].name); return 2; }
        const char *v = argv[++i];
        char *end;
        errno = 0;
        if (opts[k].type == 'l') {
            long x = strtol(v, &end, 10);
            if (errno || *end || end == v) { fprintf(stderr, "crownshy %s: --%s: not an integer: '%s'\n", cmd, opts[k].name, v); return 2; }
            *(long *)opts[k].dst = x;
        } else if (opts[k].type == 'd') {
            double x = strtod(v, &end);
            if (errno || *end || end == v || !isfinite(x)) { fprintf(stderr, "crownshy %s: --%s: not a number: '%s'\n", cmd, opts[k].name, v); return 2; }
            *(double *)opts[k].dst = x;
        } else {
            *(const char **)opts[k].dst = v;
        }
    }
    return 0;
}

static int fail(const char *cmd, cs_status st)
{
    fprintf(stderr, "crownshy %s: %s\n", cmd, cs_errmsg());
    return cs_exit_code(st);
}

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

static int cmd_train(int argc, char **argv)
{
    const char *arm = "joint", *ckpt = NULL;
    long steps = 2000, batch = 64, width = 64, depth = 3, heads = 4, mlp = 256, seed = 1, stands = 8, every = 200, pair = 0;
    double lr = 2e-3, d = 4.5;
    const cli_opt o[] = {
        {"arm", 's', &arm, "joint (attention across the patch) or independent (default joint)"},
        {"steps", 'l', &steps, "optimiser steps (default 2000)"},
        {"batch", 'l', &batch, "patches per step (default 64)"},
        {"lr", 'd', &lr, "peak learning rate (default 2e-3)"},
        {"width", 'l', &width, "model width (default 64)"},
        {"depth", 'l', &depth, "transformer blocks (default 3)"},
        {"heads", 'l', &heads, "attention heads (default 4)"},
        {"mlp", 'l', &mlp, "MLP width (default 256)"},
        {"pair", 'l', &pair, "1: pair-aware model with standardised features (SPEC §8 revision 2; default 0)"},
        {"seed", 'l', &seed, "run seed: init/batch/noise streams use 3s+1, 3s+2, 3s+3 (default 1)"},
        {"stands", 'l', &stands, "toy training stands, 64 patches each (default 8)"},
        {"spacing", 'd', &d, "toy stand spacing in m (default 4.5)"},
        {"ckpt", 's', &ckpt, "checkpoint file; resumed from when it exists (default none)"},
        {"ckpt-every", 'l', &every, "steps between checkpoints (default 200)"},
    };
    int rc = parse_opts("train", argc, argv, o, sizeof o / sizeof *o, "[options]   (trains on toy stands)");
    if (rc) return rc == 1 ? 0 : 2;
    int joint = !strcmp(arm, "joint") ? 1 : !strcmp(arm, "independent") ? 0 : -1;
    if (joint < 0) { fprintf(stderr, "crownshy train: --arm must be joint or independent, not '%s'\n", arm); return 2; }
    if (pair != 0 && pair != 1) { fprintf(stderr, "crownshy train: --pair must be 0 or 1\n"); return 2; }
    if (steps < 1 || batch < 1 || stands < 1 || stands > 100000 || seed < 0 || !(lr > 0) || !(d > 0) || every < 0) {
        fprintf(stderr, "crownshy train: steps, batch, stands, lr and spacing must be positive\n");
        return 2;
    }
    model_cfg cfg = model_cfg_reference(PATCH_NCOND);
    cfg.C = (int)width; cfg.L = (int)depth; cfg.H = (int)heads; cfg.F = (int)mlp; cfg.joint = joint; cfg.pair = (int)pair;
    cs_status st = model_cfg_check(&cfg);
    if (st) { fprintf(stderr, "crownshy train: %s\n", cs_errmsg()); return 2; }
    patch_set *ps;
    if ((st = toy_data(&ps, stands, d, 1000 + 1000 * (unsigned long)seed, 0))) return fail("train", st);
    /* SPEC §5 / paper §4.3: the batched clearance estimator must agree with
     * the canonical one before any training; abort on mismatch. */
    {
        int nchk = ps->n < 16 ? ps->n : 16;
        double *rr = malloc(sizeof(double) * nchk * PATCH_T * PATCH_P), diff = 0;
        if (!rr) { patch_set_free(ps); return fail("train", cs_err(CS_ENOMEM, "out of memory")); }
        for (int k = 0; k < nchk; k++) patch_set_radii(ps, k, ps->x1 + (size_t)k * PATCH_T * PATCH_P, rr + (size_t)k * PATCH_T * PATCH_P);
        st = patch_clearance_check(est_clearance, ps->px, ps->py, rr, nchk, &diff);
        free(rr);
        if (st) { patch_set_free(ps); return fail("train", st); }
        fprintf(stderr, "clearance check: batched vs canonical estimator on %d patches, max |diff| %.2g m\n", nchk, diff);
    }
    train_opts opt = train_opts_default();
    opt.steps = steps; opt.batch = (int)batch; opt.lr = lr;
    opt.seed_init = 3 * seed + 1; opt.seed_batch = 3 * seed + 2; opt.seed_noise = 3 * seed + 3;
    train *t;
    if ((st = train_alloc(&t, &cfg, ps, &opt))) { patch_set_free(ps); return fail("train", st); }
    if (ckpt && access(ckpt, F_OK) == 0) {
        if ((st = train_load(t, ckpt))) { train_free(t); patch_set_free(ps); return fail("train", st); }
        fprintf(stderr, "resumed from %s at step %ld\n", ckpt, t->step);
    }
    fprintf(stderr, "train: %s arm, %zu parameters, %d patches (scale %.4g m), %ld steps of %d\n",
            joint ? "joint" : "independent", t->m->nparams, ps->n, ps->scale, steps, t->B);
    st = train_run(t, steps, ckpt, every, stderr);
    double l = NAN;
    if (!st) st = train_eval_loss(t, ps, 4, 12345, &l);
    if (!st) printf("final step %ld  train loss %.6f  eval loss %.6f\n", t->step, t->loss, l);
    train_free(t);
    patch_set_free(ps);
    return st ? fail("train", st) : 0;
}

static int cmd_sample(int argc, char **argv)
{
    const char *ckpt = NULL;
    long n = 16, seed = 1, steps = 100;
    double d = 4.5;
    const cli_opt o[] = {
        {"ckpt", 's', &ckpt, "checkpoint written by crownshy train (required)"},
        {"n", 'l', &n, "patches to generate from held-out toy stands (default 16)"},
        {"euler", 'l', &steps, "Euler steps (default 100)"},
        {"seed", 'l', &seed, "noise seed (default 1)"},
        {"spacing", 'd', &d, "toy stand spacing in m (default 4.5)"},
    };
    int rc = parse_opts("sample", argc, argv, o, sizeof o / sizeof *o, "--ckpt FILE [options]");
    if (rc) return rc == 1 ? 0 : 2;
    if (!ckpt) { fprintf(stderr, "crownshy sample: --ckpt is required\n"); return 2; }
    if (n < 1 || n > 4096 || steps < 1 || seed < 0 || !(d > 0)) { fprintf(stderr, "crownshy sample: bad --n, --euler, --seed or --spacing\n"); return 2; }
    model *m;
    double scale;
    cs_status st = train_load_model(ckpt, &m, (int)n, &scale);
    if (st) return fail("sample", st);
    patch_set *ps;
    /* held-out toy stands: seeds far from any training seed */
    if ((st = toy_data(&ps, (n + 63) / 64, d, 900000 + (unsigned long)seed, scale))) { model_free(m); return fail("sample", st); }
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
    return st ? fail("sample", st) : 0;
}

static int cmd_bench_model(int argc, char **argv)
{
    long repeats = 5, steps = 20, batch = 64;
    const cli_opt o[] = {
        {"repeats", 'l', &repeats, "timed repeats, the median is reported (default 5)"},
        {"steps", 'l', &steps, "training steps per repeat (default 20)"},
        {"batch", 'l', &batch, "patches per step (default 64)"},
    };
    int rc = parse_opts("bench-model", argc, argv, o, sizeof o / sizeof *o,
                        "[options]   (reference configuration of SPEC §10; set OPENBLAS_NUM_THREADS=1)");
    if (rc) return rc == 1 ? 0 : 2;
    if (repeats < 1 || repeats > 15 || steps < 1 || batch < 1) { fprintf(stderr, "crownshy bench-model: repeats 1..15, steps and batch >= 1\n"); return 2; }
    model_cfg cfg = model_cfg_reference(PATCH_NCOND);
    train_bench_result r;
    cs_status st = train_bench(&cfg, (int)batch, (int)steps, (int)repeats, &r);
    if (st) return fail("bench-model", st);
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
    /* revision 2 (SPEC §10): the pair-aware model at the same configuration,
     * in the same run; its rate against the same run's gemm_fma rate (the
     * fused product the model runs on) and sgemm rate */
    train_bench_result rp;
    cfg.pair = 1;
    st = train_bench(&cfg, (int)batch, (int)steps, (int)repeats, &rp);
    if (st) return fail("bench-model", st);
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

/* Common --help handling: every command answers --help with exit 0. */
static int want_help(int argc, char **argv, const char *text)
{
    for (int i = 1; i < argc; i++)
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) { fputs(text, stdout); return 1; }
    return 0;
}

static int die(cs_status st)
{
    fprintf(stderr, "crownshy: %s\n", cs_errmsg()[0] ? cs_errmsg() : cs_status_name(st));
    return cs_exit_code(st);
}

static int cmd_verify(int argc, char **argv)
{
    if (want_help(argc, argv,
                  "usage: crownshy verify [--no-figures]\n"
                  "Audit pins and frozen hashes, recompute every claim of audit/claims.tsv from frozen/,\n"
                  "compare with paper/numbers.tex, judge every gate, redraw every figure, and print\n"
                  "'N passed, N failed'. Exit 1 if anything failed; pending claims are listed, not passed.\n"))
        return 0;
    verify_opts o = {0};
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--no-figures")) o.no_figures = 1;
        else { fprintf(stderr, "crownshy verify: unknown option '%s'\n", argv[i]); return 2; }
    }
    cs_status st = verify_run(&o);
    if (st && st != CS_EFAIL) return die(st);
    return cs_exit_code(st);
}

static int cmd_numbers(int argc, char **argv)
{
    if (want_help(argc, argv,
                  "usage: crownshy numbers [--check]\n"
                  "Regenerate paper/numbers.tex from frozen/ (atomic). With --check, only compare.\n"))
        return 0;
    int check = argc > 1 && !strcmp(argv[1], "--check");
    if (argc > 1 && !check) { fprintf(stderr, "crownshy numbers: unknown option '%s'\n", argv[1]); return 2; }
    claims c;
    cs_status st = claims_load(AUDIT_CLAIMS, &c);
    if (st) return die(st);
    claim_result *res;
    if ((st = verify_eval_all(&c, &res))) { claims_free(&c); return die(st); }
    if (check) {
        checklist cl = {0};
        audit_numbers(&c, res, &cl);
        int bad = 0;
        for (size_t i = 0; i < cl.n; i++) {
            printf("%s %s\n", verdict_name(cl.items[i].v), cl.items[i].msg);
            bad |= cl.items[i].v == VERDICT_FAIL;
        }
        checklist_free(&cl);
        free(res);
        claims_free(&c);
        return bad ? 1 : 0;
    }
    st = claims_write_numbers(AUDIT_NUMBERS, &c, res);
    if (!st) st = claims_write_comparison("paper/comparison.tex", &c, res);
    size_t pend = 0;
    for (size_t i = 0; i < c.n; i++) pend += res[i].status != VERDICT_PASS;
    if (!st) printf("wrote %s: %zu claims (%zu pending)\n", AUDIT_NUMBERS, c.n, pend);
    free(res);
    claims_free(&c);
    return st ? die(st) : 0;
}

static int cmd_audit(int argc, char **argv)
{
    if (want_help(argc, argv,
                  "usage: crownshy audit\n"
                  "Check pins (estimator hash, teacher version and hash, gate hashes), frozen-file hashes,\n"
                  "frozen provenance vs pins, the claim registry, numbers.tex and the paper text.\n"))
        return 0;
    claims c;
    cs_status st = claims_load(AUDIT_CLAIMS, &c);
    if (st) return die(st);
    claim_result *res;
    if ((st = verify_eval_all(&c, &res))) { claims_free(&c); return die(st); }
    checklist cl = {0};
    audit_run(&c, res, &cl);
    size_t count[3] = {0};
    checklist_print(&cl, count);
    printf("%zu passed, %zu failed\n", count[VERDICT_PASS] + count[VERDICT_PENDING], count[VERDICT_FAIL]);
    checklist_free(&cl);
    free(res);
    claims_free(&c);
    return count[VERDICT_FAIL] ? 1 : 0;
}

static int cmd_trace(int argc, char **argv)
{
    if (want_help(argc, argv, "usage: crownshy trace MACRO\nPrint a claim's value, frozen file, function, gate and test.\n")) return 0;
    if (argc != 2) { fprintf(stderr, "usage: crownshy trace MACRO\n"); return 2; }
    cs_status st = verify_trace(argv[1]);
    return st ? die(st) : 0;
}

static int cmd_pin(int argc, char **argv)
{
    if (want_help(argc, argv,
                  "usage: crownshy pin\n"
                  "Rewrite audit/pins.tsv from the current estimator, teacher and gates. Deliberate:\n"
                  "afterwards frozen/ must be regenerated (make reproduce freeze) or the audit fails.\n"))
        return 0;
    cs_status st = audit_pin();
    if (st) return die(st);
    printf("wrote %s\n", AUDIT_PINS);
    return 0;
}

static int cmd_hash_frozen(int argc, char **argv)
{
    if (want_help(argc, argv, "usage: crownshy hash-frozen\nRewrite audit/frozen.sha256 from frozen/ (part of make freeze).\n")) return 0;
    cs_status st = audit_hash_frozen();
    if (st) return die(st);
    printf("wrote %s\n", AUDIT_FROZEN_HASHES);
    return 0;
}

static int cmd_gates(int argc, char **argv)
{
    if (want_help(argc, argv,
                  "usage: crownshy gates [FILE.gate ...]\n"
                  "Parse the preregistered gate files (default: every gates/ *.gate) and print each\n"
                  "threshold with its file and line. Exit 3 on a malformed file.\n"))
        return 0;
    char *files[64];
    int n = 0;
    if (argc > 1) {
        for (int i = 1; i < argc && n < 64; i++) files[n++] = strdup(argv[i]);
    } else {
        DIR *d = opendir("gates");
        if (!d) { fprintf(stderr, "crownshy gates: gates/: cannot open\n"); return 3; }
        struct dirent *e;
        while ((e = readdir(d)) && n < 64) {
            size_t l = strlen(e->d_name);
            if (l > 5 && !strcmp(e->d_name + l - 5, ".gate")) {
                char p[600];
                snprintf(p, sizeof p, "gates/%s", e->d_name);
                files[n++] = strdup(p);
            }
        }
        closedir(d);
    }
    int rc = 0;
    for (int i = 0; i < n; i++) {
        gate *g;
        if (gate_load(files[i], &g)) { fprintf(stderr, "crownshy: %s\n", cs_errmsg()); rc = 3; free(files[i]); continue; }
        printf("%s: ok\n", files[i]);
        gate_free(g);
        free(files[i]);
    }
    return rc;
}

static int cmd_check_tsv(int argc, char **argv)
{
    if (want_help(argc, argv,
                  "usage: crownshy check-tsv FILE.tsv ...\n"
                  "Validate frozen tables: provenance lines, header, field counts, and every column\n"
                  "that is numeric in its first row numeric in every row. Exit 3 naming file, line, field.\n"))
        return 0;
    if (argc < 2) { fprintf(stderr, "usage: crownshy check-tsv FILE.tsv ...\n"); return 2; }
    int rc = 0;
    for (int i = 1; i < argc; i++) {
        tsv *t;
        if (tsv_read(argv[i], &t)) { fprintf(stderr, "crownshy: %s\n", cs_errmsg()); rc = 3; continue; }
        int bad = 0;
        for (size_t c = 0; c < tsv_ncols(t) && !bad && tsv_nrows(t) > 0; c++) {
            double v;
            const char *col = tsv_colname(t, c);
            if (tsv_double_nf(t, 0, col, &v)) continue; /* a text column */
            for (size_t r = 1; r < tsv_nrows(t) && !bad; r++)
                if (tsv_double_nf(t, r, col, &v)) { fprintf(stderr, "crownshy: %s\n", cs_errmsg()); bad = 1; }
        }
        if (bad) rc = 3;
        else printf("%s: ok (%zu rows, %zu columns)\n", argv[i], tsv_nrows(t), tsv_ncols(t));
        tsv_free(t);
    }
    return rc;
}

static int cmd_figures(int argc, char **argv)
{
    if (want_help(argc, argv,
                  "usage: crownshy figures\n"
                  "Redraw every figure (figures/ *.gp, gnuplot) whose frozen data exist; the same step as\n"
                  "in crownshy verify. Exit 1 if a script fails.\n"))
        return 0;
    if (argc > 1) { fprintf(stderr, "crownshy figures: unknown option '%s'\n", argv[1]); return 2; }
    checklist cl = {0};
    verify_figures(&cl);
    size_t count[3] = {0};
    checklist_print(&cl, count);
    checklist_free(&cl);
    return count[VERDICT_FAIL] ? 1 : 0;
}

static const cli_cmd cli_cmds[] = {
    {"figures", cmd_figures, "redraw every figure with gnuplot from frozen data"},
    {"main-run", exp_main_cmd_run, "E3/E4: one (seed, arm) training + evaluation unit"},
    {"main-baselines", exp_main_cmd_baselines, "E3/E4: direction-blind baseline and noise floor"},
    {"main-summary", exp_main_cmd_summary, "E3/E4: gather runs into frozen tables"},
    {"comp-run", exp_comp_cmd_run, "E7: comparison patch (teacher, joint, independent) and dart probe"},
    {"bench-teacher", exp_cmd_bench_teacher, "teacher ms per 144-tree stand at N = 48 and 384"},
    {"run", exp_cmd_run, "run one experiment unit of E1/E2/figure data (crownshy run --help)"},
    {"gates", cmd_gates, "parse and list the preregistered gate files"},
    {"check-tsv", cmd_check_tsv, "validate frozen TSV files"},
    {"verify", cmd_verify, "audit, recompute every claim, judge gates, redraw figures"},
    {"numbers", cmd_numbers, "regenerate paper/numbers.tex from frozen/"},
    {"audit", cmd_audit, "check pins, frozen hashes, provenance, registry and paper"},
    {"trace", cmd_trace, "trace one macro to its value, file, function, gate and test"},
    {"pin", cmd_pin, "re-pin the estimator, teacher and gates (deliberate)"},
    {"hash-frozen", cmd_hash_frozen, "record the hashes of frozen/ (make freeze)"},
    {"field-summary", cmd_field_summary, "summarise a raw field table (FIELD_TABLE) with the canonical estimator"},
    {"field-calibrate", cmd_field_calibrate, "E5: calibrate die-back beta to the field tree-mean median clearance"},
    {"field-beta", cmd_field_beta, "E5: print beta_field from a calibration table"},
    {"field-heldout", cmd_field_heldout, "E5: held-out spread, elongation and uncoupled control at beta_field"},
    {"aniso-lattice", cmd_aniso_lattice, "E6: anisotropy on the controlled lattice at beta_field"},
    {"aniso-hardcore", cmd_aniso_hardcore, "E6: hard-core stem family sweep"},
    {"aniso-jitter", cmd_aniso_jitter, "E6: jitter-amplitude family sweep"},
    {"aniso-jitter-calibrate", cmd_aniso_jitter_calibrate, "E6: calibrate jitter a* to the field anisotropy median"},
    {"aniso-heldout", cmd_aniso_heldout, "E6: held-out stands at a*"},
    {"field-diagnose", cmd_field_diagnose, "E5/E6: diagnostics for the elongation and anisotropy verdicts"},
    {"version", cmd_version, "print the version"},
    {"train", cmd_train, "train the flow-matching generator (toy stands for now)"},
    {"sample", cmd_sample, "generate crowns with a trained checkpoint (100 Euler steps)"},
    {"bench-model", cmd_bench_model, "trainer steps/s, model and sgemm GFLOP/s (SPEC §10)"},
};
#define NCMDS (sizeof cli_cmds / sizeof cli_cmds[0])

static void usage(FILE *f)
{
    fprintf(f, "usage: crownshy <command> [options]   (crownshy <command> --help)\n\ncommands:\n");
    for (size_t i = 0; i < NCMDS; i++) fprintf(f, "  %-16s %s\n", cli_cmds[i].name, cli_cmds[i].help);
    fprintf(f, "\nexit codes: 0 ok, 1 a gate or claim failed, 2 usage error, 3 bad or missing input\n");
}

int main(int argc, char **argv)
{
    cs_gsl_install();
    if (argc < 2) { usage(stderr); return 2; }
    if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") || !strcmp(argv[1], "help")) {
        usage(stdout);
        return 0;
    }
    for (size_t i = 0; i < NCMDS; i++)
        if (!strcmp(argv[1], cli_cmds[i].name)) return cli_cmds[i].fn(argc - 1, argv + 1);
    fprintf(stderr, "crownshy: unknown command '%s'\n", argv[1]);
    usage(stderr);
    return 2;
}
