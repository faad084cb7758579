/* step_split: where a training step of the generator spends its time, against
 * the core's FMA peak (design.md §10.1; the third part of `make bench`).
 *
 * Linked with -Wl,--wrap for the four gemm entry points the layers call
 * (gemm_fma, gemm_fma_epi, gemm_fma_bias_epi, gemm_fma_heads), so the library
 * is the one every unit runs, unchanged: each call is timed (its epilogue,
 * the fused element-wise pass, timed apart and left out) and recorded with
 * its operands. After the timed steps the recorded products of the last step
 * are run again with the same operands and in the same order:
 *   in step       the products as they ran inside the steps;
 *   back to back  the step's products one after the other, nothing between;
 *   hot           each product alone, after three runs of the same call;
 *   the rest      step time minus the products in step: attention, GELU,
 *                 layer norms, the pair terms, the noise, AdamW, ...
 * and the bound: a step whose products ran at their hot rate and whose rest
 * took what it took, as a fraction of the peak, beside the step time that
 * the training goal (SPEED_GOAL_TRAIN of the peak, speed.h; judged by
 * bench-model) allows. A replay overwrites C (gradients included), so every
 * round trains a model of its own from the same seeds.
 *
 * A step is timed in the thread's CPU time (CLOCK_THREAD_CPUTIME_ID, read
 * twice per step), which time spent in other processes does not enter, and
 * beside it in wall time from the time-stamp counter. A step whose wall time
 * exceeds its CPU time by 5 % (and 0.2 ms) was preempted: it is discarded
 * with its products, and the count is printed. The products inside a step
 * are timed on the time-stamp counter (steady on the CPUs this runs on): the
 * thread clock costs a system call per reading in a VM, which the ~2,300
 * readings of a step would add to the step; in a kept step wall and CPU time
 * agree, and the products' wall time is scaled by the step's CPU/wall ratio,
 * so the rest (step less products) is taken in one clock. The replays run
 * after the steps: back to back the fastest of three passes, hot the
 * fastest of three timed runs of each call (a preempted run is never the
 * fastest). Not run by `make check` or CI: a measurement, like the rest of
 * `make bench`.
 *
 * usage: step_split [--rounds N] [--steps N] [--path all|avx512|avx2|scalar] */
#include "gemm.h"
#include "model.h"
#include "patch.h"
#include "speed.h"
#include "stats.h"
#include "train.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#if defined(__x86_64__)
#include <x86intrin.h>
#endif

enum { MAX_CALLS = 4096, MAX_ROUNDS = 15, BATCH = 64 };

typedef struct {
    int kind; /* 0 gemm_fma(_epi), 1 gemm_fma_bias_epi, 2 gemm_fma_heads */
    int M, N, K, acc, H, n;
    const float *A, *B, *bias;
    ptrdiff_t ars, aks, ahs, ldb, ldc;
    float *C;
    double s; /* seconds in the product, epilogue left out */
} call_rec;

static call_rec calls[MAX_CALLS];
static int ncalls, recording, overflow;
static double tick_s, epi_s;

static double now_s(void)
{
#if defined(__x86_64__)
    return (double)__rdtsc() * tick_s;
#else
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
#endif
}

/* This thread's CPU time (two readings per step: the preemption test). */
static double thread_cpu_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

/* Seconds per counter tick, against the monotonic clock over 0.2 s. */
static void clock_calibrate(void)
{
#if defined(__x86_64__)
    struct timespec a, b;
    clock_gettime(CLOCK_MONOTONIC, &a);
    unsigned long long t0 = __rdtsc();
    double el;
    do {
        clock_gettime(CLOCK_MONOTONIC, &b);
        el = (double)(b.tv_sec - a.tv_sec) + 1e-9 * (double)(b.tv_nsec - a.tv_nsec);
    } while (el < 0.2);
    tick_s = el / (double)(__rdtsc() - t0);
#endif
}

void __real_gemm_fma(int, int, int, const float *, ptrdiff_t, ptrdiff_t, const float *, ptrdiff_t, float *,
                     ptrdiff_t, int);
void __real_gemm_fma_epi(int, int, int, const float *, ptrdiff_t, ptrdiff_t, const float *, ptrdiff_t, float *,
                         ptrdiff_t, int, gemm_epilogue, void *);
void __real_gemm_fma_bias_epi(int, int, int, const float *, ptrdiff_t, ptrdiff_t, const float *, ptrdiff_t,
                              float *, ptrdiff_t, const float *, gemm_epilogue, void *);
void __real_gemm_fma_heads(int, int, int, int, const float *, ptrdiff_t, ptrdiff_t, ptrdiff_t, const float *,
                           ptrdiff_t, float *, ptrdiff_t);
typedef struct { gemm_epilogue epi; void *ctx; } epi_ctx;

static void epi_timed(void *ctx, int i0, int rows)
{
    const epi_ctx *e = ctx;
    double t0 = now_s();
    e->epi(e->ctx, i0, rows);
    epi_s += now_s() - t0;
}

static void record(call_rec r)
{
    if (!recording) return;
    if (ncalls < MAX_CALLS) calls[ncalls++] = r;
    else overflow = 1;
}

void __wrap_gemm_fma(int M, int N, int K, const float *A, ptrdiff_t ars, ptrdiff_t aks, const float *B,
                     ptrdiff_t ldb, float *C, ptrdiff_t ldc, int acc)
{
    double t0 = now_s();
    __real_gemm_fma(M, N, K, A, ars, aks, B, ldb, C, ldc, acc);
    record((call_rec){0, M, N, K, acc, 0, 0, A, B, NULL, ars, aks, 0, ldb, ldc, C, now_s() - t0});
}

void __wrap_gemm_fma_epi(int M, int N, int K, const float *A, ptrdiff_t ars, ptrdiff_t aks, const float *B,
                         ptrdiff_t ldb, float *C, ptrdiff_t ldc, int acc, gemm_epilogue epi, void *ctx)
{
    epi_ctx e = {epi, ctx};
    epi_s = 0;
    double t0 = now_s();
    __real_gemm_fma_epi(M, N, K, A, ars, aks, B, ldb, C, ldc, acc, epi ? epi_timed : NULL, epi ? &e : NULL);
    record((call_rec){0, M, N, K, acc, 0, 0, A, B, NULL, ars, aks, 0, ldb, ldc, C, now_s() - t0 - epi_s});
}

void __wrap_gemm_fma_bias_epi(int M, int N, int K, const float *A, ptrdiff_t ars, ptrdiff_t aks,
                              const float *B, ptrdiff_t ldb, float *C, ptrdiff_t ldc, const float *bias,
                              gemm_epilogue epi, void *ctx)
{
    epi_ctx e = {epi, ctx};
    epi_s = 0;
    double t0 = now_s();
    __real_gemm_fma_bias_epi(M, N, K, A, ars, aks, B, ldb, C, ldc, bias, epi ? epi_timed : NULL, epi ? &e : NULL);
    record((call_rec){1, M, N, K, 0, 0, 0, A, B, bias, ars, aks, 0, ldb, ldc, C, now_s() - t0 - epi_s});
}

void __wrap_gemm_fma_heads(int H, int M, int n, int K, const float *A, ptrdiff_t ahs, ptrdiff_t ars,
                           ptrdiff_t aks, const float *B, ptrdiff_t ldb, float *C, ptrdiff_t ldc)
{
    double t0 = now_s();
    __real_gemm_fma_heads(H, M, n, K, A, ahs, ars, aks, B, ldb, C, ldc);
    record((call_rec){2, M, H * n, K, 0, H, n, A, B, NULL, ars, aks, ahs, ldb, ldc, C, now_s() - t0});
}

static void replay(const call_rec *r)
{
    switch (r->kind) {
    case 2:
        __real_gemm_fma_heads(r->H, r->M, r->n, r->K, r->A, r->ahs, r->ars, r->aks, r->B, r->ldb, r->C, r->ldc);
        break;
    case 1:
        __real_gemm_fma_bias_epi(r->M, r->N, r->K, r->A, r->ars, r->aks, r->B, r->ldb, r->C, r->ldc, r->bias, NULL,
                                 NULL);
        break;
    default: __real_gemm_fma(r->M, r->N, r->K, r->A, r->ars, r->aks, r->B, r->ldb, r->C, r->ldc, r->acc);
    }
}

enum { S_STEP, S_IN, S_SEQ, S_HOT, S_REST, S_BOUND, S_FRAC, S_NS };
static const char *const s_name[S_NS] = {"step_ms", "products_in_step_ms", "products_back_to_back_ms",
                                         "products_hot_ms", "rest_ms", "bound_of_peak", "step_of_peak"};

/* One round: a fresh model, `steps` timed steps, then the last step's
 * products replayed. v[S_STEP..S_REST] (ms) for the round; returns 0, 1 on
 * failure, or 2 when every step tried was preempted (no figure). */
static int round_run(const model_cfg *cfg, patch_set *ps, int steps, double v[S_NS], double *gflop_products,
                     int *preempted, int *timed)
{
    train_opts o = train_opts_default();
    o.batch = BATCH;
    o.steps = 100000;
    train *t = NULL;
    if (train_alloc(&t, cfg, ps, &o)) return 1;
    for (int s = 0; s < 3; s++) /* warm the caches and the allocations */
        if (train_step(t, NULL)) { train_free(t); return 1; }
    double step = 0, in = 0;
    int kept = 0, tried = 0;
    /* a step the kernel preempted (its wall time beyond its thread CPU time)
     * is discarded, products and all: up to eight tries per kept step */
    while (kept < steps && tried < 8 * steps) {
        tried++;
        (*timed)++;
        ncalls = 0;
        recording = 1;
        double c0 = thread_cpu_s(), t0 = now_s();
        cs_status st = train_step(t, NULL);
        double wall = now_s() - t0, cpu = thread_cpu_s() - c0;
        recording = 0;
        if (st || overflow) { train_free(t); return 1; }
        if (wall > 1.05 * cpu + 2e-4) { (*preempted)++; continue; }
        step += cpu;
        kept++;
        double prod = 0;
        for (int i = 0; i < ncalls; i++) prod += calls[i].s;
        in += wall > cpu ? prod * cpu / wall : prod;
    }
    if (!kept) { train_free(t); return 2; }
    steps = kept;
    double fl = 0, seq = 1e30, hot = 0;
    for (int i = 0; i < ncalls; i++) fl += 2.0 * calls[i].M * calls[i].N * calls[i].K;
    for (int q = 0; q < 3; q++) {
        double t0 = now_s();
        for (int i = 0; i < ncalls; i++) replay(&calls[i]);
        double d = now_s() - t0;
        if (d < seq) seq = d;
    }
    for (int i = 0; i < ncalls; i++) {
        for (int w = 0; w < 3; w++) replay(&calls[i]);
        double best = 1e30;
        for (int q = 0; q < 3; q++) {
            double t0 = now_s();
            replay(&calls[i]);
            double d = now_s() - t0;
            if (d < best) best = d;
        }
        hot += best;
    }
    train_free(t);
    v[S_STEP] = 1e3 * step / steps;
    v[S_IN] = 1e3 * in / steps;
    v[S_SEQ] = 1e3 * seq;
    v[S_HOT] = 1e3 * hot;
    v[S_REST] = v[S_STEP] - v[S_IN];
    *gflop_products = fl / 1e9;
    return 0;
}

/* median [min, max] of n >= 1 values (stats.h) */
static double median_of(const double *x, int n, double *lo, double *hi)
{
    double m = 0;
    stats_median(x, (size_t)n, &m); /* fails only on n = 0 or out of memory */
    *lo = stats_min(x, (size_t)n);
    *hi = stats_max(x, (size_t)n);
    return m;
}

static int split_path(gemm_isa isa, patch_set *ps, int rounds, int steps)
{
    gemm_set_isa(isa);
    printf("path\t%s\n", gemm_isa_name());
    static const char *const model_name[2] = {"pair", "plain"};
    for (int mk = 0; mk < 2; mk++) {
        model_cfg cfg = model_cfg_reference(PATCH_NCOND);
        cfg.pair = mk == 0;
        double v[S_NS][MAX_ROUNDS], pk[MAX_ROUNDS], gp = 0;
        int preempted = 0, timed = 0;
        const double model_fl = model_train_flops(&cfg, BATCH) / 1e9;
        int nr = 0;
        for (int q0 = 0; q0 < rounds; q0++) {
            double p0 = gemm_peak_gflops(isa, 1L << 21), r[S_NS];
            int rc = round_run(&cfg, ps, steps, r, &gp, &preempted, &timed);
            if (rc == 2) continue; /* a round the machine's load left without a figure */
            if (rc) {
                fprintf(stderr, "step_split: a training step failed%s\n",
                        overflow ? " (more gemm calls than recorded)" : "");
                return 1;
            }
            const int q = nr++;
            double p1 = gemm_peak_gflops(isa, 1L << 21);
            pk[q] = 0.5 * (p0 + p1);
            for (int s = S_STEP; s <= S_REST; s++) v[s][q] = r[s];
            /* fractions against the mean of the peaks before and after the round */
            v[S_BOUND][q] = model_fl / ((r[S_HOT] + r[S_REST]) * 1e-3) / pk[q];
            v[S_FRAC][q] = model_fl / (r[S_STEP] * 1e-3) / pk[q];
        }
        printf("%s_steps_discarded\t%d\tof %d timed (preempted: wall time beyond the thread's CPU time by 5 %%)\n",
               model_name[mk], preempted, timed);
        if (!nr) {
            printf("%s: every step of every round was preempted: no split on this path (run on a quieter machine)\n",
                   model_name[mk]);
            continue;
        }
        double lo, hi, pmed = median_of(pk, nr, &lo, &hi);
        printf("%s_gflop_per_step\t%.3f\t(products %.3f)\n", model_name[mk], model_fl, gp);
        if (nr < rounds) printf("%s_rounds\t%d of %d (the others: every step preempted)\n", model_name[mk], nr, rounds);
        printf("%s_fma_peak_gflops\t%.1f\t[%.1f, %.1f]\n", model_name[mk], pmed, lo, hi);
        double med[S_NS];
        for (int s = 0; s < S_NS; s++) {
            med[s] = median_of(v[s], nr, &lo, &hi);
            printf("%s_%s\t%.3f\t[%.3f, %.3f]", model_name[mk], s_name[s], med[s], lo, hi);
            if (s >= S_IN && s <= S_HOT) printf("\t%.3f of peak", gp / (med[s] * 1e-3) / pmed);
            printf("\n");
        }
        const double allowed = model_fl / (SPEED_GOAL_TRAIN * pmed) * 1e3;
        printf("%s_step_ms_at_goal\t%.3f\t(%.2f of the peak); with the products at their hot rate the rest may take "
               "%.3f ms, "
               "it takes %.3f\n",
               model_name[mk], allowed, SPEED_GOAL_TRAIN, allowed - med[S_HOT], med[S_REST]);
    }
    return 0;
}

int main(int argc, char **argv)
{
    int rounds = 5, steps = 8;
    const char *path = "all";
    for (int k = 1; k < argc; k++) {
        if (!strcmp(argv[k], "--rounds") && k + 1 < argc) rounds = atoi(argv[++k]);
        else if (!strcmp(argv[k], "--steps") && k + 1 < argc) steps = atoi(argv[++k]);
        else if (!strcmp(argv[k], "--path") && k + 1 < argc) path = argv[++k];
        else {
            fprintf(stderr, "usage: step_split [--rounds 1..%d] [--steps N] [--path all|avx512|avx2|scalar]\n",
                    MAX_ROUNDS);
            return 2;
        }
    }
    if (rounds < 1 || rounds > MAX_ROUNDS || steps < 1) {
        fprintf(stderr, "step_split: --rounds must be 1..%d and --steps >= 1\n", MAX_ROUNDS);
        return 2;
    }
    gemm_isa list[3];
    int n = 0;
    if (!strcmp(path, "all")) {
        for (gemm_isa i = GEMM_AVX512; i >= GEMM_AVX2; i = (gemm_isa)(i - 1))
            if (gemm_isa_available(i)) list[n++] = i;
        if (!n) list[n++] = GEMM_SCALAR;
    } else {
        gemm_isa i = !strcmp(path, "avx512") ? GEMM_AVX512 : !strcmp(path, "avx2") ? GEMM_AVX2
                   : !strcmp(path, "scalar") ? GEMM_SCALAR : GEMM_AUTO;
        if (i == GEMM_AUTO || !gemm_isa_available(i)) {
            fprintf(stderr, "step_split: --path %s: not a path this CPU has\n", path);
            return 2;
        }
        list[n++] = i;
    }
    clock_calibrate();
    patch_set *ps = NULL;
    if (patch_set_alloc(&ps, 2 * BATCH) || patch_set_add_toy(ps, 2, 4.5, 7) ||
        patch_set_standardise(ps, patch_set_rms(ps))) {
        fprintf(stderr, "step_split: could not make the toy patches\n");
        patch_set_free(ps);
        return 4;
    }
    printf("step split: %d rounds of %d training steps, batch %d x 24 tokens, joint arm; median [min, max]; "
           "fractions of the FMA peak measured before and after each round\n", rounds, steps, BATCH);
    int rc = 0;
    for (int k = 0; k < n && !rc; k++) rc = split_path(list[k], ps, rounds, steps);
    patch_set_free(ps);
    return rc;
}
