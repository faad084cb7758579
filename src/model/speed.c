/* speed: the model measurements of `make bench` (see speed.h; design.md §10).
 * Toy data (patch.h) at the reference configuration; the calling thread's CPU
 * time (CLOCK_THREAD_CPUTIME_ID), so other processes on a shared machine do
 * not enter a figure; one BLAS thread. */
#include "speed.h"
#include "gemm.h"
#include "nn.h"
#include "pairattn.h"
#include "patch.h"
#include "train.h"
#include <cblas.h>
#include <gsl/gsl_rng.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

const char *speed_name(speed_what w)
{
    static const char *n[SPEED_NITEMS] = {"own_product", "sgemm", "plain_train", "pair_train",
                                          "pair_indep_train", "plain_sample", "pair_sample",
                                          "pair_indep_sample"};
    return w >= 0 && w < SPEED_NITEMS ? n[w] : "?";
}

double speed_forward_flops(const model_cfg *c, int B)
{
    const double N = (double)B * c->T, C = c->C, F = c->F, T = c->T, hd = (double)c->C / c->H;
    const double NI = c->P + c->nfeat, E = c->ncond + c->ntime, TT = T * T, Q = PAIRATTN_Q;
    double gemm = 2 * N * (NI * C + 3 * C * C * c->L + C * C * c->L + 2 * C * F * c->L + C * c->P)
                + 2.0 * B * (E * C + C * C);
    double attn = c->joint ? 2.0 * B * c->H * TT * hd * 2 * c->L : 0;
    double pair = !c->pair ? 0 : 2.0 * B * c->L * (c->joint ? 2 * c->H * TT * Q + T * C * Q : T * C * Q);
    return gemm + attn + pair;
}

/* ---- the products of one training pass ------------------------------------- */
/* Every linear layer of the model at a pass's MODEL_MICRO * T rows: forward
 * (A row-major times the transposed weights), input gradient (all but the
 * token layer) and weight gradient (A transposed, accumulating), as
 * nn_linear_forward / nn_linear_backward call them. */
typedef struct { int in, out, mult, dinp; } layer;
typedef struct { float *a, *w, *c, *d, *dw; int R, n; layer l[6]; } pass_set;

/* n zeroed floats on a 64-byte boundary */
static float *falloc(size_t n)
{
    const size_t bytes = (sizeof(float) * (n ? n : 1) + 63) / 64 * 64;
    float *p = aligned_alloc(64, bytes);
    if (p) memset(p, 0, bytes);
    return p;
}

static cs_status pass_alloc(pass_set *p, const model_cfg *c)
{
    const int NI = c->P + c->nfeat, C = c->C, F = c->F, L = c->L;
    const layer l[6] = {{NI, C, 1, 0}, {C, 3 * C, L, 1}, {C, C, L, 1}, {C, F, L, 1}, {F, C, L, 1}, {C, c->P, 1, 1}};
    memcpy(p->l, l, sizeof l);
    p->n = 6;
    p->R = MODEL_MICRO * c->T;
    int mx = 1;
    for (int k = 0; k < p->n; k++) mx = l[k].in > mx ? l[k].in : l[k].out > mx ? l[k].out : mx;
    const size_t ra = (size_t)p->R * mx, ww = (size_t)mx * mx;
    /* on cache lines, as the model's arrays (model_alloc) */
    p->a = falloc(ra);
    p->c = falloc(ra);
    p->d = falloc(ra);
    p->w = falloc(ww);
    p->dw = falloc(ww);
    if (!p->a || !p->c || !p->d || !p->w || !p->dw) return cs_err(CS_ENOMEM, "bench: out of memory");
    for (size_t i = 0; i < ra; i++) p->a[i] = (float)((i % 17) * 0.01 - 0.08);
    for (size_t i = 0; i < ww; i++) p->w[i] = (float)((i % 13) * 0.01 - 0.06);
    return CS_OK;
}

static void pass_free(pass_set *p) { free(p->a); free(p->c); free(p->d); free(p->w); free(p->dw); }

static double pass_flops(const pass_set *p)
{
    double f = 0;
    for (int k = 0; k < p->n; k++)
        f += 2.0 * p->R * p->l[k].in * p->l[k].out * p->l[k].mult * (2 + p->l[k].dinp);
    return f;
}

static void pass_run(pass_set *p, int blas)
{
    const int R = p->R;
    for (int k = 0; k < p->n; k++)
        for (int m = 0; m < p->l[k].mult; m++) {
            const int K = p->l[k].in, N = p->l[k].out;
            if (blas) {
                cblas_sgemm(CblasRowMajor, CblasNoTrans, CblasNoTrans, R, N, K, 1.f, p->a, K, p->w, N, 0.f, p->c, N);
                if (p->l[k].dinp)
                    cblas_sgemm(CblasRowMajor, CblasNoTrans, CblasNoTrans, R, K, N, 1.f, p->c, N, p->w, K, 0.f, p->d,
                                K);
                cblas_sgemm(CblasRowMajor, CblasTrans, CblasNoTrans, N, K, R, 1.f, p->c, N, p->a, K, 1.f, p->dw, K);
            } else {
                gemm_fma(R, N, K, p->a, K, 1, p->w, N, p->c, N, 0);
                if (p->l[k].dinp) gemm_fma(R, K, N, p->c, N, 1, p->w, K, p->d, K, 0);
                gemm_fma(N, K, R, p->c, 1, N, p->a, K, p->dw, K, 1);
            }
        }
}

/* ---- the models --------------------------------------------------------------- */
typedef struct {
    patch_set *ps;
    train *t[3]; /* plain joint, pair joint, pair independent */
    model_cfg cfg[3];
    gsl_rng *noise;
    float *x;
    pass_set pass;
    long peak_iters;
} bench_ctx;

/* The measured models train on toy patches (two batches' worth, standardised):
 * a rate depends on the shapes, not on what the patches hold. */
static cs_status toy_patches(patch_set **ps, int B)
{
    cs_status st = patch_set_alloc(ps, 2 * B);
    if (!st) st = patch_set_add_toy(*ps, (2 * B + 63) / 64, 4.5, 7);
    if (!st) st = patch_set_standardise(*ps, patch_set_rms(*ps));
    return st;
}

static cs_status toy_trainer(train **t, const model_cfg *cfg, const patch_set *ps, int B)
{
    train_opts o = train_opts_default();
    o.batch = B;
    o.steps = 100000;
    return train_alloc(t, cfg, ps, &o);
}

static void ctx_free(bench_ctx *b)
{
    for (int k = 0; k < 3; k++) train_free(b->t[k]);
    patch_set_free(b->ps);
    if (b->noise) gsl_rng_free(b->noise);
    free(b->x);
    pass_free(&b->pass);
}

static cs_status ctx_alloc(bench_ctx *b, const model_cfg *ref, int B)
{
    memset(b, 0, sizeof *b);
    cs_status st = toy_patches(&b->ps, B);
    for (int k = 0; k < 3 && !st; k++) {
        b->cfg[k] = *ref;
        b->cfg[k].pair = k > 0;
        b->cfg[k].joint = k < 2;
        st = toy_trainer(&b->t[k], &b->cfg[k], b->ps, B);
        for (int w = 0; !st && w < 2; w++) st = train_step(b->t[k], NULL); /* warm caches */
    }
    if (!st) st = pass_alloc(&b->pass, ref);
    b->noise = gsl_rng_alloc(gsl_rng_mt19937);
    b->x = malloc(sizeof(float) * (size_t)B * ref->T * ref->P);
    if (!st && (!b->noise || !b->x)) st = cs_err(CS_ENOMEM, "bench: out of memory");
    if (st) ctx_free(b);
    return st;
}

/* Peak loop length of about 10 ms on this path. */
static long peak_calibrate(void)
{
    long n = 1 << 16;
    for (;;) {
        double t0 = now_s();
        gemm_peak_gflops(gemm_get_isa(), n);
        if (now_s() - t0 > 0.01 || n > (1L << 34)) return n;
        n *= 2;
    }
}

enum { PASS_REPS = 48 };

/* One measurement: ms per call and model FLOPs per call. */
static cs_status measure(bench_ctx *b, speed_what w, int B, int steps, double *ms, double *flops)
{
    cs_status st = CS_OK;
    const int k = w == SPEED_PLAIN || w == SPEED_PLAIN_SAMPLE ? 0
                : w == SPEED_PAIR || w == SPEED_PAIR_SAMPLE ? 1 : 2;
    /* untimed first: the item's own operands into the caches, as in a run
     * of training or sampling, where the step before is of the same model */
    if (w == SPEED_PRODUCT || w == SPEED_SGEMM) pass_run(&b->pass, w == SPEED_SGEMM);
    else if (w <= SPEED_PAIR_INDEP)
        for (int s = 0; s < SPEED_WARMUP_STEPS && !st; s++) st = train_step(b->t[k], NULL);
    else st = model_sample(b->t[k]->m, b->noise, B, b->ps->feat, b->ps->cond, 1, b->x);
    if (st) return st;
    double t0 = now_s();
    int calls = 1;
    if (w == SPEED_PRODUCT || w == SPEED_SGEMM) {
        calls = PASS_REPS;
        for (int r = 0; r < calls; r++) pass_run(&b->pass, w == SPEED_SGEMM);
        *flops = pass_flops(&b->pass);
    } else if (w <= SPEED_PAIR_INDEP) {
        calls = steps;
        for (int s = 0; s < calls && !st; s++) st = train_step(b->t[k], NULL);
        *flops = model_train_flops(&b->cfg[k], B);
    } else {
        calls = steps;
        st = model_sample(b->t[k]->m, b->noise, B, b->ps->feat, b->ps->cond, calls, b->x);
        *flops = speed_forward_flops(&b->cfg[k], B);
    }
    *ms = (now_s() - t0) * 1e3 / calls;
    return st;
}

static int cmp_dbl(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static speed_stat stat_of(double *v, int n)
{
    qsort(v, n, sizeof *v, cmp_dbl);
    speed_stat s = {n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]), v[0], v[n - 1]};
    return s;
}

cs_status speed_run(const model_cfg *ref, int B, int rounds, int steps, speed_result *r)
{
    memset(r, 0, sizeof *r);
    rounds = rounds < 1 ? 1 : rounds > SPEED_MAX_ROUNDS ? SPEED_MAX_ROUNDS : rounds;
    bench_ctx b;
    cs_status st = ctx_alloc(&b, ref, B);
    if (st) return st;
    const gemm_isa isa = gemm_get_isa();
    const long n = peak_calibrate();
    double pk[SPEED_MAX_ROUNDS], p256[SPEED_MAX_ROUNDS];
    double rate[SPEED_NITEMS][SPEED_MAX_ROUNDS], frac[SPEED_NITEMS][SPEED_MAX_ROUNDS],
        ms[SPEED_NITEMS][SPEED_MAX_ROUNDS];
    for (int q = 0; q < rounds && !st; q++) {
        double p0 = gemm_peak_gflops(isa, n);
        pk[q] = p0;
        p256[q] = gemm_peak_gflops(isa > GEMM_AVX2 ? GEMM_AVX2 : isa, n * (isa > GEMM_AVX2 ? 2 : 1));
        for (int i = 0; i < SPEED_NITEMS && !st; i++) {
            const speed_what w = (speed_what)((i + q) % SPEED_NITEMS); /* rotate the order */
            double t = 0, fl = 0, p1;
            st = measure(&b, w, B, steps < 1 ? 1 : steps, &t, &fl);
            p1 = gemm_peak_gflops(isa, n);
            ms[w][q] = t;
            rate[w][q] = fl / (t * 1e6);
            frac[w][q] = rate[w][q] / (0.5 * (p0 + p1));
            p0 = p1;
        }
    }
    ctx_free(&b);
    if (st) return st;
    r->rounds = rounds;
    r->batch = B;
    r->peak = stat_of(pk, rounds);
    r->peak256 = stat_of(p256, rounds);
    for (int i = 0; i < SPEED_NITEMS; i++) {
        r->item[i].rate = stat_of(rate[i], rounds);
        r->item[i].frac = stat_of(frac[i], rounds);
        r->ms[i] = stat_of(ms[i], rounds);
    }
    return CS_OK;
}

cs_status speed_sample_gflops(model *m, int B, int steps, double *gflops)
{
    const model_cfg *c = &m->cfg;
    const size_t nf = (size_t)B * c->T * c->nfeat, nc = (size_t)B * c->ncond;
    float *feat = malloc(sizeof(float) * (nf + nc + 1)), *x = malloc(sizeof(float) * (size_t)B * c->T * c->P);
    gsl_rng *g = gsl_rng_alloc(gsl_rng_mt19937);
    cs_status st = feat && x && g ? CS_OK : cs_err(CS_ENOMEM, "speed: out of memory");
    if (!st) {
        gsl_rng_set(g, 1);
        for (size_t i = 0; i < nf + nc; i++) feat[i] = (float)(2 * gsl_rng_uniform(g) - 1);
        st = model_sample(m, g, B, feat, feat + nf, 1, x);
    }
    const double t0 = now_s();
    if (!st) st = model_sample(m, g, B, feat, feat + nf, steps, x);
    const double s = (now_s() - t0) / steps;
    if (!st) *gflops = s > 0 ? speed_forward_flops(c, B) / s / 1e9 : 0;
    if (g) gsl_rng_free(g);
    free(feat);
    free(x);
    return st;
}

cs_status speed_model_gflops(const model_cfg *cfg, int B, int steps, double *train_gflops, double *sample_gflops)
{
    patch_set *ps = NULL;
    train *t = NULL;
    cs_status st = toy_patches(&ps, B);
    if (!st) st = toy_trainer(&t, cfg, ps, B);
    if (!st) st = train_step(t, NULL);
    const double t0 = now_s();
    for (int k = 0; k < steps && !st; k++) st = train_step(t, NULL);
    const double s = (now_s() - t0) / steps;
    if (!st) *train_gflops = s > 0 ? model_train_flops(cfg, B) / s / 1e9 : 0;
    if (!st) st = speed_sample_gflops(t->m, B, steps, sample_gflops);
    train_free(t);
    patch_set_free(ps);
    return st;
}
