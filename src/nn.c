/* nn: layer kernels (see nn.h). The matrix products go to gemm_fma (src/gemm.h:
 * bit-identical on every ISA); cblas_sgemm remains only as the benchmark's
 * yardstick (nn_product_gflops). Every other loop is written on 8-wide GCC/Clang vector types, because -O2 without fast-math
 * will not vectorise float reductions by itself (reassociation is forbidden).
 * The hot kernels are compiled twice (target_clones: AVX2 and baseline x86-64,
 * picked at load time); both clones execute the same lane-wise IEEE operations
 * in the same order, so their results are bit-identical - no -march=native,
 * no FMA contraction (-ffp-contract=off), no fast-math. Reductions use a fixed
 * lane order. Paper §4.2; SPEC §8, §10. */
#include "nn.h"
#include "gemm.h"
#include <cblas.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* The vector helpers are always inlined, so no vector crosses a call boundary. */
#pragma GCC diagnostic ignored "-Wpsabi"

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(NN_NO_CLONES)
#define HOT __attribute__((target_clones("avx2", "default")))
#else
#define HOT
#endif
#define INL static inline __attribute__((always_inline))
/* AVX-512 forms of the GELU and of attention at the reference head shape,
 * taken at run time where the CPU has AVX-512F (absent from the baseline copy
 * that test_nn_clones compares them with). */
#if defined(__x86_64__) && defined(__GNUC__) && !defined(NN_NO_CLONES)
#define NN_AVX512 1
#endif

typedef float vf __attribute__((vector_size(32)));
typedef int vi __attribute__((vector_size(32)));
enum { VL = 8 };

INL vf ld(const float *p) { vf v; memcpy(&v, p, sizeof v); return v; }
INL void st(float *p, vf v) { memcpy(p, &v, sizeof v); }
/* A vector constructor {a, a, ...} is lowered to insert chains in the AVX2
 * clone by GCC 12, while a scalar operand of a vector operation becomes one
 * broadcast; so splat is written as 0 + a (exact except that -0 becomes +0,
 * identically in both clones), and hot loops write `scalar * vector`. */
INL vf splat(float a) { vf z = {0}; return z + a; }
/* Horizontal sum by butterfly, result in every lane:
 * ((v0+v4)+(v2+v6)) + ((v1+v5)+(v3+v7)). One fixed order everywhere. */
#if defined(__clang__)
#define SWAP4(v) __builtin_shufflevector((v), (v), 4, 5, 6, 7, 0, 1, 2, 3)
#define SWAP2(v) __builtin_shufflevector((v), (v), 2, 3, 0, 1, 6, 7, 4, 5)
#define SWAP1(v) __builtin_shufflevector((v), (v), 1, 0, 3, 2, 5, 4, 7, 6)
#else
#define SWAP4(v) __builtin_shuffle((v), (vi){4, 5, 6, 7, 0, 1, 2, 3})
#define SWAP2(v) __builtin_shuffle((v), (vi){2, 3, 0, 1, 6, 7, 4, 5})
#define SWAP1(v) __builtin_shuffle((v), (vi){1, 0, 3, 2, 5, 4, 7, 6})
#endif
INL vf hsumv(vf v)
{
    v = v + SWAP4(v);
    v = v + SWAP2(v);
    return v + SWAP1(v);
}
INL float hsum(vf v) { return hsumv(v)[0]; }

/* y[0..n) += a * x[0..n) */
INL void axpy(float *restrict y, float a, const float *restrict x, int n)
{
    int i = 0;
    for (; i + VL <= n; i += VL) st(y + i, ld(y + i) + a * ld(x + i));
    for (; i < n; i++) y[i] += a * x[i];
}

/* sum of x[0..n), fixed order: 8 lanes, then the tail. */
INL float vsum(const float *x, int n)
{
    vf acc = splat(0.f);
    int i = 0;
    for (; i + VL <= n; i += VL) acc += ld(x + i);
    float s = hsum(acc);
    for (; i < n; i++) s += x[i];
    return s;
}

INL vf vmax(vf a, vf b) { vi m = a > b; return (vf)(((vi)a & m) | ((vi)b & ~m)); }
/* Horizontal max by butterfly, result in every lane (max is exact). */
INL vf hmaxv(vf v)
{
    v = vmax(v, SWAP4(v));
    v = vmax(v, SWAP2(v));
    return vmax(v, SWAP1(v));
}

/* max of x[0..n), n >= 1 (max is exact, so the order does not matter). */
INL float vmaxv(const float *x, int n)
{
    float mx = x[0];
    int i = 0;
    if (n >= VL) {
        vf m = ld(x);
        for (i = VL; i + VL <= n; i += VL) m = vmax(m, ld(x + i));
        mx = hmaxv(m)[0];
    }
    for (; i < n; i++) mx = x[i] > mx ? x[i] : mx;
    return mx;
}

/* sum of a[i]*b[i], fixed order: 8 lanes, then the tail. */
INL float vdot(const float *a, const float *b, int n)
{
    vf acc = splat(0.f);
    int i = 0;
    for (; i + VL <= n; i += VL) acc += ld(a + i) * ld(b + i);
    float s = hsum(acc);
    for (; i < n; i++) s += a[i] * b[i];
    return s;
}

/* ---- exp ------------------------------------------------------------------ */
/* exp(x) = 2^n * p(r), x = n ln2 + r, |r| <= ln2/2, p = Taylor to degree 7. */
#define DEF_VEXP(NAME, VF, VI, SPLAT) \
INL VF NAME(VF x) \
{ \
    const VF lo = SPLAT(-87.0f), hi = SPLAT(88.0f); \
    VI mlo = x < lo, mhi = x > hi; \
    x = (VF)(((VI)x & ~mlo) | ((VI)lo & mlo)); \
    x = (VF)(((VI)x & ~mhi) | ((VI)hi & mhi)); \
    const VF shifter = SPLAT(12582912.0f); /* 1.5*2^23: add-subtract rounds to nearest */ \
    VF kn = (x * SPLAT(1.44269504088896341f) + shifter) - shifter; \
    VF r = x - kn * SPLAT(0.693145751953125f);      /* ln2 high part (kn*hi exact) */ \
    r = r - kn * SPLAT(1.428606765330187e-06f);     /* ln2 low part */ \
    VF p = SPLAT(1.f / 5040.f); \
    p = p * r + SPLAT(1.f / 720.f); \
    p = p * r + SPLAT(1.f / 120.f); \
    p = p * r + SPLAT(1.f / 24.f); \
    p = p * r + SPLAT(1.f / 6.f); \
    p = p * r + SPLAT(0.5f); \
    p = p * r + SPLAT(1.f); \
    p = p * r + SPLAT(1.f); \
    VI n = __builtin_convertvector(kn, VI); \
    VI bits = (n + 127) << 23; \
    return p * (VF)bits; \
}
DEF_VEXP(vexp, vf, vi, splat)

/* Scalar tails go through the same lane arithmetic, so a value does not depend
 * on whether it sat in a full vector or in the tail. */
INL float sexp(float x) { return vexp(splat(x))[0]; }

HOT void nn_expf(float *y, const float *x, size_t n)
{
    size_t i = 0;
    for (; i + VL <= n; i += VL) st(y + i, vexp(ld(x + i)));
    for (; i < n; i++) y[i] = sexp(x[i]);
}

/* ---- linear ----------------------------------------------------------------- */
/* All three products go to gemm_fma (one fma chain per output element, the
 * same bits on every ISA). The forward needs w as a row-major [K x N] B
 * operand, so it is transposed into the caller's scratch first: K*N floats,
 * cheap next to the M*K*N product at the model's M = B*T rows. */
/* out = in w^T (+ b), then epi on each finished strip (may be NULL). Every
 * forward linear layer, fused or not, goes through here. */
static void linear_forward_epi(float *out, const float *in, const float *w, const float *b,
                               int M, int K, int N, float *wt, gemm_epilogue epi, void *ctx)
{
    if (w) gemm_transpose(wt, w, N, K);
    gemm_fma_bias_epi(M, N, K, in, K, 1, wt, N, out, N, b, epi, ctx);
}

void nn_linear_forward(float *out, const float *in, const float *w, const float *b,
                       int M, int K, int N, float *wt)
{
    linear_forward_epi(out, in, w, b, M, K, N, wt, NULL, NULL);
}

HOT static void colsum_add(float *db, const float *dout, int M, int N)
{
    for (int r = 0; r < M; r++) axpy(db, 1.f, dout + (size_t)r * N, N);
}

/* dinp = dout w with epi on its strips (both skipped when dinp == NULL),
 * dw += dout^T in, db += column sums; every backward linear layer. */
static void linear_backward_epi(float *dinp, float *dw, float *db, const float *dout,
                                const float *in, const float *w, int M, int K, int N,
                                gemm_epilogue epi, void *ctx)
{
    if (dinp) gemm_fma_epi(M, K, N, dout, N, 1, w, K, dinp, K, 0, epi, ctx);
    gemm_fma(N, K, M, dout, 1, N, in, K, dw, K, 1);
    if (db) colsum_add(db, dout, M, N);
}

void nn_linear_backward(float *dinp, float *dw, float *db, const float *dout,
                        const float *in, const float *w, int M, int K, int N)
{
    linear_backward_epi(dinp, dw, db, dout, in, w, M, K, N, NULL, NULL);
}

double nn_product_gflops(int M, const int *sizes, int n, int reps, int blas)
{
    int mx = 1;
    for (int i = 0; i < n; i++) mx = sizes[i] > mx ? sizes[i] : mx;
    float *A = malloc(sizeof(float) * M * mx), *W = malloc(sizeof(float) * mx * mx);
    float *Cm = malloc(sizeof(float) * M * mx);
    if (!A || !W || !Cm) { free(A); free(W); free(Cm); return 0; }
    for (size_t i = 0; i < (size_t)M * mx; i++) A[i] = (float)((i % 17) * 0.01 - 0.08);
    for (size_t i = 0; i < (size_t)mx * mx; i++) W[i] = (float)((i % 13) * 0.01 - 0.06);
    double fl = 0;
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    for (int a = 0; a < n; a++)
        for (int b = 0; b < n; b++)
            for (int k = 0; k < reps; k++) {
                if (blas)
                    cblas_sgemm(CblasRowMajor, CblasNoTrans, CblasTrans, M, sizes[a], sizes[b], 1.f,
                                A, sizes[b], W, sizes[b], 0.f, Cm, sizes[a]);
                else /* W read as the transposed operand, as after nn_linear_forward's transpose */
                    gemm_fma(M, sizes[a], sizes[b], A, sizes[b], 1, W, sizes[a], Cm, sizes[a], 0);
                fl += 2.0 * M * sizes[a] * sizes[b];
            }
    clock_gettime(CLOCK_MONOTONIC, &t1);
    free(A); free(W); free(Cm);
    return fl / ((t1.tv_sec - t0.tv_sec) + 1e-9 * (t1.tv_nsec - t0.tv_nsec)) / 1e9;
}

/* ---- layer norm ---------------------------------------------------------------- */
#define LN_EPS 1e-5f

HOT void nn_layernorm_forward(float *out, float *mean, float *rstd, const float *in,
                              const float *g, const float *b, int M, int C)
{
    const float invC = 1.f / (float)C;
    for (int r = 0; r < M; r++) {
        const float *x = in + (size_t)r * C;
        float *y = out + (size_t)r * C;
        float mu = vsum(x, C) * invC;
        vf acc = splat(0.f), vm = splat(mu);
        int c = 0;
        for (; c + VL <= C; c += VL) { vf d = ld(x + c) - vm; acc += d * d; }
        float var = hsum(acc);
        for (; c < C; c++) { float d = x[c] - mu; var += d * d; }
        float rs = 1.f / sqrtf(var * invC + LN_EPS);
        vf vr = splat(rs);
        for (c = 0; c + VL <= C; c += VL)
            st(y + c, (ld(x + c) - vm) * vr * ld(g + c) + ld(b + c));
        for (; c < C; c++) y[c] = (x[c] - mu) * rs * g[c] + b[c];
        mean[r] = mu;
        rstd[r] = rs;
    }
}

HOT void nn_layernorm_backward(float *dinp, float *dg, float *db, const float *dout,
                               const float *in, const float *mean, const float *rstd,
                               const float *g, int M, int C)
{
    const float invC = 1.f / (float)C;
    for (int r = 0; r < M; r++) {
        const float *x = in + (size_t)r * C, *dy = dout + (size_t)r * C;
        float *dx = dinp + (size_t)r * C;
        vf vm = splat(mean[r]), vr = splat(rstd[r]);
        vf s1 = splat(0.f), s2 = splat(0.f);
        int c = 0;
        for (; c + VL <= C; c += VL) {
            vf xh = (ld(x + c) - vm) * vr, d = ld(dy + c);
            vf dxh = d * ld(g + c);
            s1 += dxh;
            s2 += dxh * xh;
            st(dg + c, ld(dg + c) + d * xh);
            st(db + c, ld(db + c) + d);
        }
        float a1 = hsum(s1), a2 = hsum(s2);
        for (; c < C; c++) {
            float xh = (x[c] - mean[r]) * rstd[r], dxh = dy[c] * g[c];
            a1 += dxh;
            a2 += dxh * xh;
            dg[c] += dy[c] * xh;
            db[c] += dy[c];
        }
        a1 *= invC;
        a2 *= invC;
        vf va1 = splat(a1), va2 = splat(a2);
        for (c = 0; c + VL <= C; c += VL) {
            vf xh = (ld(x + c) - vm) * vr;
            vf dxh = ld(dy + c) * ld(g + c);
            st(dx + c, ld(dx + c) + vr * (dxh - va1 - xh * va2));
        }
        for (; c < C; c++) {
            float xh = (x[c] - mean[r]) * rstd[r], dxh = dy[c] * g[c];
            dx[c] += rstd[r] * (dxh - a1 - xh * a2);
        }
    }
}

/* ---- GELU ------------------------------------------------------------------------ */
#define GELU_K 0.7978845608028654f /* sqrt(2/pi) */
#define GELU_A 0.044715f

/* sigmoid(2u) of the tanh-form GELU: gelu(x) = x * gsig(x). */
#define DEF_VGSIG(NAME, VF, VEXP, SPLAT) \
INL VF NAME(VF x) \
{ \
    VF u = SPLAT(GELU_K) * (x + SPLAT(GELU_A) * x * x * x); \
    return SPLAT(1.f) / (SPLAT(1.f) + VEXP(SPLAT(-2.f) * u)); \
}
DEF_VGSIG(vgsig, vf, vexp, splat)

INL vf vgelu_grad(vf x, vf s)
{
    vf du = splat(GELU_K) * (splat(1.f) + splat(3.f * GELU_A) * (x * x));
    return s + x * s * (splat(1.f) - s) * splat(2.f) * du;
}

HOT void nn_gelu_forward(float *out, const float *in, size_t n)
{
    size_t i = 0;
    for (; i + VL <= n; i += VL) { vf x = ld(in + i); st(out + i, x * vgsig(x)); }
    for (; i < n; i++) { vf x = splat(in[i]); out[i] = (x * vgsig(x))[0]; }
}

HOT void nn_gelu_forward_save(float *out, float *sig, const float *in, size_t n)
{
    size_t i = 0;
    for (; i + VL <= n; i += VL) {
        vf x = ld(in + i), s = vgsig(x);
        st(sig + i, s);
        st(out + i, x * s);
    }
    for (; i < n; i++) { vf x = splat(in[i]), s = vgsig(x); sig[i] = s[0]; out[i] = (x * s)[0]; }
}

HOT void nn_gelu_backward(float *dinp, const float *dout, const float *in, size_t n)
{
    size_t i = 0;
    for (; i + VL <= n; i += VL) { vf x = ld(in + i); st(dinp + i, ld(dout + i) * vgelu_grad(x, vgsig(x))); }
    for (; i < n; i++) { vf x = splat(in[i]); dinp[i] = dout[i] * vgelu_grad(x, vgsig(x))[0]; }
}

#ifdef NN_AVX512
static void gelu_backward16(float *dinp, const float *dout, const float *in, const float *sig, size_t n);
#endif

HOT void nn_gelu_backward_saved(float *dinp, const float *dout, const float *in,
                                const float *sig, size_t n)
{
#ifdef NN_AVX512
    if (gemm_isa_available(GEMM_AVX512)) { gelu_backward16(dinp, dout, in, sig, n); return; }
#endif
    size_t i = 0;
    for (; i + VL <= n; i += VL) st(dinp + i, ld(dout + i) * vgelu_grad(ld(in + i), ld(sig + i)));
    for (; i < n; i++) dinp[i] = dout[i] * vgelu_grad(splat(in[i]), splat(sig[i]))[0];
}

/* Columns c..N-1 of one row of the fused bias + GELU, one value at a time
 * through the same lane arithmetic as the vector loops. */
INL void bias_gelu_tail(float *hr, float *sr, float *orow, const float *b, int c, int N)
{
    for (; c < N; c++) {
        float x = hr[c] + b[c];
        vf sg = vgsig(splat(x));
        hr[c] = x; sr[c] = sg[0]; orow[c] = (x * sg)[0];
    }
}

/* The GELU forward is compute-bound (an exp and a division per value) and
 * the largest element-wise cost of a training step; on AVX-512 it runs on
 * 16-lane vectors. Every lane executes the same IEEE operations in the same
 * order as in the 8-lane code (no reductions here), so the values are
 * identical (test_nn_clones compares this path with the baseline build). */
#ifdef NN_AVX512
typedef float vf16 __attribute__((vector_size(64)));
typedef int vi16 __attribute__((vector_size(64)));
INL vf16 ld16(const float *p) { vf16 v; memcpy(&v, p, sizeof v); return v; }
INL void st16(float *p, vf16 v) { memcpy(p, &v, sizeof v); }
INL vf16 splat16(float a) { vf16 z = {0}; return z + a; }
DEF_VEXP(vexp16, vf16, vi16, splat16)
DEF_VGSIG(vgsig16, vf16, vexp16, splat16)

__attribute__((target("avx512f"))) static void bias_gelu16(float *h, float *sig, float *out,
                                                           const float *b, int M, int N)
{
    for (int r = 0; r < M; r++) {
        float *hr = h + (size_t)r * N, *sr = sig + (size_t)r * N, *orow = out + (size_t)r * N;
        int c = 0;
        for (; c + 16 <= N; c += 16) {
            vf16 x = ld16(hr + c) + ld16(b + c), sg = vgsig16(x);
            st16(hr + c, x); st16(sr + c, sg); st16(orow + c, x * sg);
        }
        bias_gelu_tail(hr, sr, orow, b, c, N);
    }
}

/* The GELU backward (from the saved sigmoid) on 16 lanes, lane-wise as the
 * 8-lane loop; the scalar tail is the 8-lane code's. */
INL vf16 vgelu_grad16(vf16 x, vf16 s)
{
    vf16 du = splat16(GELU_K) * (splat16(1.f) + splat16(3.f * GELU_A) * (x * x));
    return s + x * s * (splat16(1.f) - s) * splat16(2.f) * du;
}

__attribute__((target("avx512f"))) static void gelu_backward16(float *dinp, const float *dout,
                                                               const float *in, const float *sig,
                                                               size_t n)
{
    size_t i = 0;
    for (; i + 16 <= n; i += 16) st16(dinp + i, ld16(dout + i) * vgelu_grad16(ld16(in + i), ld16(sig + i)));
    for (; i < n; i++) dinp[i] = dout[i] * vgelu_grad(splat(in[i]), splat(sig[i]))[0];
}

#endif

HOT void nn_bias_gelu_forward_save(float *h, float *sig, float *out, const float *b, int M, int N)
{
#ifdef NN_AVX512
    if (gemm_isa_available(GEMM_AVX512)) { bias_gelu16(h, sig, out, b, M, N); return; }
#endif
    for (int r = 0; r < M; r++) {
        float *hr = h + (size_t)r * N, *sr = sig + (size_t)r * N, *orow = out + (size_t)r * N;
        int c = 0;
        for (; c + VL <= N; c += VL) {
            vf x = ld(hr + c) + ld(b + c), sg = vgsig(x);
            st(hr + c, x); st(sr + c, sg); st(orow + c, x * sg);
        }
        bias_gelu_tail(hr, sr, orow, b, c, N);
    }
}

HOT void nn_bias_residual_forward(float *out, const float *y, const float *b, const float *x, int M, int N)
{
    for (int r = 0; r < M; r++) {
        size_t o = (size_t)r * N;
        int c = 0;
        for (; c + VL <= N; c += VL) st(out + o + c, (ld(y + o + c) + ld(b + c)) + ld(x + o + c));
        for (; c < N; c++) out[o + c] = (y[o + c] + b[c]) + x[o + c];
    }
}

/* ---- fused linear layers ------------------------------------------------------------ */
/* The product's epilogue runs the element-wise pass on each strip of finished
 * rows while they are in L1, instead of a second sweep over M x N floats. The
 * element-wise kernels are the ones above, called on row ranges: they treat
 * rows independently and never depend on a value's position in a vector, so
 * the results are bit-identical to the unfused sequence (tested). */
typedef struct {
    float *h, *sig, *out, *ln, *mean, *rstd;
    const float *b, *x, *g, *beta, *hin, *hsig;
    int N;
} fuse_ctx;

static void epi_bias_gelu(void *p, int i0, int rows)
{
    const fuse_ctx *f = p;
    size_t o = (size_t)i0 * f->N;
    nn_bias_gelu_forward_save(f->h + o, f->sig + o, f->out + o, f->b, rows, f->N);
}

static void epi_bias_residual_ln(void *p, int i0, int rows)
{
    const fuse_ctx *f = p;
    size_t o = (size_t)i0 * f->N;
    nn_bias_residual_forward(f->out + o, f->out + o, f->b, f->x + o, rows, f->N);
    if (f->ln)
        nn_layernorm_forward(f->ln + o, f->mean + i0, f->rstd + i0, f->out + o, f->g, f->beta, rows, f->N);
}

static void epi_gelu_backward(void *p, int i0, int rows)
{
    const fuse_ctx *f = p;
    size_t o = (size_t)i0 * f->N, n = (size_t)rows * f->N;
    nn_gelu_backward_saved(f->h + o, f->h + o, f->hin + o, f->hsig + o, n);
}

void nn_linear_bias_gelu_forward(float *h, float *sig, float *out, const float *in,
                                 const float *w, const float *b, int M, int K, int N, float *wt)
{
    fuse_ctx f = {.h = h, .sig = sig, .out = out, .b = b, .N = N};
    linear_forward_epi(h, in, w, NULL, M, K, N, wt, epi_bias_gelu, &f);
}

void nn_linear_bias_residual_forward(float *out, const float *in, const float *w,
                                     const float *b, const float *x, float *ln, float *mean,
                                     float *rstd, const float *g, const float *beta,
                                     int M, int K, int N, float *wt)
{
    fuse_ctx f = {.out = out, .ln = ln, .mean = mean, .rstd = rstd, .b = b, .x = x,
                  .g = g, .beta = beta, .N = N};
    linear_forward_epi(out, in, w, NULL, M, K, N, wt, epi_bias_residual_ln, &f);
}

void nn_linear_backward_gelu(float *dinp, float *dw, float *db, const float *dout,
                             const float *in, const float *w, const float *h,
                             const float *sig, int M, int K, int N)
{
    fuse_ctx f = {.h = dinp, .hin = h, .hsig = sig, .N = K};
    linear_backward_epi(dinp, dw, db, dout, in, w, M, K, N, epi_gelu_backward, &f);
}

/* ---- residual ---------------------------------------------------------------------- */
HOT void nn_residual_forward(float *out, const float *a, const float *b, size_t n)
{
    size_t i = 0;
    for (; i + VL <= n; i += VL) st(out + i, ld(a + i) + ld(b + i));
    for (; i < n; i++) out[i] = a[i] + b[i];
}

HOT void nn_residual_backward(float *acc, const float *x, size_t n)
{
    size_t i = 0;
    for (; i + VL <= n; i += VL) st(acc + i, ld(acc + i) + ld(x + i));
    for (; i < n; i++) acc[i] += x[i];
}

/* ---- attention -------------------------------------------------------------------- */
/* Per patch and head the work is six small products on T x hd blocks
 * (T = 24, hd = 16 at the reference configuration), read in place from qkv
 * through gemm's strides. The scores (Q K^T) and dP (dO V^T) go head by head
 * through gemm_fma on a transposed copy of the head's keys or values (hd x T,
 * in the scratch; the score scale 1/sqrt(hd) is folded into the keys' copy).
 * The four products with an hd-wide result (P V, P^T dO, dS K, dS^T Q) go
 * through gemm_fma_heads, all heads of a patch per call. Values are those of
 * per-head gemm_fma calls. The softmax and its backward are vector loops. */

size_t nn_attention_scratch_len(int T, int C, int H)
{
    return (size_t)H * T * T + (size_t)(C / H) * T;
}

/* y[0..n) += x (the pair terms of nn_attention_*_biased). */
INL void add_rows(float *restrict y, const float *restrict x, int n)
{
    int i = 0;
    for (; i + VL <= n; i += VL) st(y + i, ld(y + i) + ld(x + i));
    for (; i < n; i++) y[i] += x[i];
}

/* In place softmax of s[0..n). */
INL void softmax_row(float *s, int n)
{
    float mx = vmaxv(s, n);
    int j = 0;
    vf vm = splat(mx);
    for (; j + VL <= n; j += VL) st(s + j, vexp(ld(s + j) - vm));
    for (; j < n; j++) s[j] = sexp(s[j] - mx);
    float inv = 1.f / vsum(s, n);
    for (j = 0; j + VL <= n; j += VL) st(s + j, ld(s + j) * inv);
    for (; j < n; j++) s[j] *= inv;
}

HOT static void softmax_rows(float *P, int T)
{
    for (int i = 0; i < T; i++) softmax_row(P + (size_t)i * T, T);
}

/* dS = P (dP - rowsum(P dP)) scale, in place over dP (both T x T). */
HOT static void softmax_backward_rows(float *ds, const float *P, int T, float scale)
{
    for (int i = 0; i < T; i++) {
        const float *p = P + (size_t)i * T;
        float *d = ds + (size_t)i * T;
        float dot = vdot(p, d, T);
        int j = 0;
        for (; j + VL <= T; j += VL) st(d + j, ld(p + j) * (ld(d + j) - dot) * scale);
        for (; j < T; j++) d[j] = p[j] * (d[j] - dot) * scale;
    }
}

/* ---- attention on AVX-512 at the reference head shape (T = 24, hd = 16) ----------- */
/* The generic kernels above spend most of their time around the products,
 * not in them: a gemm_fma call per head and per 24 x 24 x 16 or 24 x 16 x 24
 * block, each set up for general strides. Here one patch's attention runs in register
 * blocks of 12 rows: a score row is one 16-lane plus one 8-lane vector, an
 * hd-wide output row one 16-lane vector. Every element is still one fma chain
 * over k in ascending order from +0, and the softmax and its backward keep the
 * 8-lane reductions of softmax_row / softmax_backward_rows (the same chunk
 * order and butterfly), so the values are those of the generic kernels
 * (test_nn_clones compares the two builds bit for bit). */
#ifdef NN_AVX512
#include <immintrin.h>
#define A512 __attribute__((target("avx512f,fma"), always_inline)) static inline

/* S[12 x 24] (row stride 24) = A[12 x 16] (row stride ars) Bt[16 x 24]. */
A512 void tt_block(float *S, const float *A, ptrdiff_t ars, const float *Bt)
{
    __m512 z[12];
    __m256 y[12];
    _Pragma("GCC unroll 12") for (int r = 0; r < 12; r++) { z[r] = _mm512_setzero_ps(); y[r] = _mm256_setzero_ps(); }
    for (int d = 0; d < 16; d++) {
        __m512 b0 = _mm512_loadu_ps(Bt + d * 24);
        __m256 b1 = _mm256_loadu_ps(Bt + d * 24 + 16);
        _Pragma("GCC unroll 12") for (int r = 0; r < 12; r++) {
            __m512 x = _mm512_set1_ps(A[r * ars + d]);
            z[r] = _mm512_fmadd_ps(x, b0, z[r]);
            y[r] = _mm256_fmadd_ps(_mm512_castps512_ps256(x), b1, y[r]);
        }
    }
    _Pragma("GCC unroll 12") for (int r = 0; r < 12; r++) {
        _mm512_storeu_ps(S + r * 24, z[r]);
        _mm256_storeu_ps(S + r * 24 + 16, y[r]);
    }
}

/* Cm[12 x 16] (row stride ldc) = sum over k < 24 of A(r, k) B[k][0..15],
 * A(r, k) = A[r * ars + k * aks]; ars and aks are literals at every call. */
A512 void hw_block(float *Cm, ptrdiff_t ldc, const float *A, const ptrdiff_t ars, const ptrdiff_t aks,
                   const float *B, ptrdiff_t ldb)
{
    __m512 c[12];
    _Pragma("GCC unroll 12") for (int r = 0; r < 12; r++) c[r] = _mm512_setzero_ps();
    for (int k = 0; k < 24; k++) {
        __m512 b = _mm512_loadu_ps(B + k * ldb);
        _Pragma("GCC unroll 12") for (int r = 0; r < 12; r++)
            c[r] = _mm512_fmadd_ps(_mm512_set1_ps(A[r * ars + k * aks]), b, c[r]);
    }
    _Pragma("GCC unroll 12") for (int r = 0; r < 12; r++) _mm512_storeu_ps(Cm + r * ldc, c[r]);
}

/* softmax_row on 12 rows of 24 (chunks j 0-7, 8-15, 16-23), in three passes
 * over the rows (maxima; exponentials and sums; scaling) so that the rows'
 * long dependency chains overlap instead of following one another. */
A512 void softmax24x12(float *s)
{
    float mx[12], inv[12];
    for (int r = 0; r < 12; r++) mx[r] = vmaxv(s + r * 24, 24);
    for (int r = 0; r < 12; r++) {
        float *row = s + r * 24;
        st16(row, vexp16(ld16(row) - splat16(mx[r])));
        st(row + 16, vexp(ld(row + 16) - splat(mx[r])));
        inv[r] = vsum(row, 24);
    }
    for (int r = 0; r < 12; r++) inv[r] = 1.f / inv[r];
    for (int r = 0; r < 12; r++) {
        float *row = s + r * 24;
        st16(row, ld16(row) * inv[r]);
        st(row + 16, ld(row + 16) * inv[r]);
    }
}

/* softmax_backward_rows on one row: d = p (d - p.d) scale. */
A512 void softmax_backward24(float *d, const float *p, float scale)
{
    const float dot = vdot(p, d, 24);
    st16(d, ld16(p) * (ld16(d) - dot) * scale);
    st(d + 16, ld(p + 16) * (ld(d + 16) - dot) * scale);
}

/* One patch (24 tokens), all heads: the values of nn_attention_forward. */
__attribute__((target("avx512f,fma"))) static void attention_forward24(float *out, float *prob,
                                                                       const float *qkv, int C, int H,
                                                                       float *kt, const float *sb)
{
    const int C3 = 3 * C;
    const float scale = 1.f / sqrtf(16.f);
    for (int h = 0; h < H; h++) {
        float *P = prob + (size_t)h * 576;
        gemm_transpose_scaled(kt, 24, qkv + C + h * 16, C3, 24, 16, scale);
        for (int i0 = 0; i0 < 24; i0 += 12) {
            tt_block(P + i0 * 24, qkv + (size_t)i0 * C3 + h * 16, C3, kt);
            if (sb) add_rows(P + i0 * 24, sb + (size_t)h * 576 + i0 * 24, 12 * 24);
            softmax24x12(P + i0 * 24);
            hw_block(out + (size_t)i0 * C + h * 16, C, P + i0 * 24, 24, 1, qkv + 2 * C + h * 16, C3);
        }
    }
}

/* One patch, all heads: the values of nn_attention_backward. */
__attribute__((target("avx512f,fma"))) static void attention_backward24(float *g, const float *dO,
                                                                        const float *qkv,
                                                                        const float *prob, int C,
                                                                        int H, float *ds, float *vt,
                                                                        const float *dpx)
{
    const int C3 = 3 * C;
    const float scale = 1.f / sqrtf(16.f);
    for (int h = 0; h < H; h++) {
        const float *P = prob + (size_t)h * 576, *q = qkv + h * 16, *k = qkv + C + h * 16;
        float *dsh = ds + (size_t)h * 576;
        gemm_transpose_scaled(vt, 24, qkv + 2 * C + h * 16, C3, 24, 16, 1.f);
        for (int i0 = 0; i0 < 24; i0 += 12) {
            tt_block(dsh + i0 * 24, dO + (size_t)i0 * C + h * 16, C, vt);
            if (dpx) add_rows(dsh + i0 * 24, dpx + (size_t)h * 576 + i0 * 24, 12 * 24);
            for (int r = i0; r < i0 + 12; r++) softmax_backward24(dsh + r * 24, P + r * 24, scale);
        }
        for (int i0 = 0; i0 < 24; i0 += 12) {
            const size_t o = (size_t)i0 * C3 + h * 16;
            hw_block(g + 2 * C + o, C3, P + i0, 1, 24, dO + h * 16, C);  /* dV = P^T dO */
            hw_block(g + o, C3, dsh + i0 * 24, 24, 1, k, C3);             /* dQ = dS K */
            hw_block(g + C + o, C3, dsh + i0, 1, 24, q, C3);              /* dK = dS^T Q */
        }
    }
}
#endif

void nn_attention_forward(float *out, float *prob, const float *qkv,
                          int B, int T, int C, int H, nn_attn_mode mode, float *scratch)
{
    nn_attention_forward_biased(out, prob, qkv, NULL, B, T, C, H, mode, scratch);
}

void nn_attention_forward_biased(float *out, float *prob, const float *qkv, const float *sbias,
                                 int B, int T, int C, int H, nn_attn_mode mode, float *scratch)
{
    const int hd = C / H, C3 = 3 * C;
    if (mode == NN_ATTN_SELF) {
        /* Softmax over one admissible key is exactly 1: the output is v itself. */
        for (int r = 0; r < B * T; r++)
            memcpy(out + (size_t)r * C, qkv + (size_t)r * C3 + 2 * C, sizeof(float) * C);
        return;
    }
#ifdef NN_AVX512
    if (T == 24 && hd == 16 && gemm_isa_available(GEMM_AVX512)) {
        for (int b = 0; b < B; b++)
            attention_forward24(out + (size_t)b * T * C, prob + (size_t)b * H * T * T,
                                qkv + (size_t)b * T * C3, C, H, scratch,
                                sbias ? sbias + (size_t)b * H * T * T : NULL);
        return;
    }
#endif
    const float scale = 1.f / sqrtf((float)hd);
    float *kt = scratch; /* [hd x T] scale K^T of one head */
    for (int b = 0; b < B; b++) {
        const float *base = qkv + (size_t)b * T * C3;
        for (int h = 0; h < H; h++) {
            float *P = prob + ((size_t)b * H + h) * T * T;
            /* P = Q (scale K^T), softmax by rows, out = P V */
            gemm_transpose_scaled(kt, T, base + C + h * hd, C3, T, hd, scale);
            gemm_fma(T, T, hd, base + h * hd, C3, 1, kt, T, P, T, 0);
            if (sbias) add_rows(P, sbias + ((size_t)b * H + h) * T * T, T * T);
            softmax_rows(P, T);
        }
        /* out_h = P_h V_h for all heads in one pass */
        gemm_fma_heads(H, T, hd, T, prob + (size_t)b * H * T * T, (ptrdiff_t)T * T, T, 1,
                       base + 2 * C, C3, out + (size_t)b * T * C, C);
    }
}

void nn_attention_backward(float *dqkv, const float *dout, const float *qkv,
                           const float *prob, int B, int T, int C, int H,
                           nn_attn_mode mode, float *scratch)
{
    nn_attention_backward_biased(dqkv, dout, qkv, prob, NULL, B, T, C, H, mode, scratch);
}

void nn_attention_backward_biased(float *dqkv, const float *dout, const float *qkv,
                                  const float *prob, const float *dpadd, int B, int T, int C,
                                  int H, nn_attn_mode mode, float *scratch)
{
    const int hd = C / H, C3 = 3 * C;
    if (mode == NN_ATTN_SELF) {
        for (int r = 0; r < B * T; r++) {
            float *g = dqkv + (size_t)r * C3;
            memset(g, 0, sizeof(float) * 2 * C); /* q and k receive no gradient */
            memcpy(g + 2 * C, dout + (size_t)r * C, sizeof(float) * C);
        }
        return;
    }
    /* [H x T x T] dP then dS of every head; [hd x T] V^T of one head */
    float *ds = scratch, *vt = scratch + (size_t)H * T * T;
#ifdef NN_AVX512
    if (T == 24 && hd == 16 && gemm_isa_available(GEMM_AVX512)) {
        for (int b = 0; b < B; b++)
            attention_backward24(dqkv + (size_t)b * T * C3, dout + (size_t)b * T * C,
                                 qkv + (size_t)b * T * C3, prob + (size_t)b * H * T * T, C, H, ds, vt,
                                 dpadd ? dpadd + (size_t)b * H * T * T : NULL);
        return;
    }
#endif
    const float scale = 1.f / sqrtf((float)hd);
    for (int b = 0; b < B; b++) {
        const float *base = qkv + (size_t)b * T * C3;
        const float *dO = dout + (size_t)b * T * C;
        float *g = dqkv + (size_t)b * T * C3;
        for (int h = 0; h < H; h++) {
            const float *P = prob + ((size_t)b * H + h) * T * T;
            const float *v = base + 2 * C + h * hd;
            /* dP = dO V^T, then the softmax backward turns it into dS */
            float *dsh = ds + (size_t)h * T * T;
            gemm_transpose_scaled(vt, T, v, C3, T, hd, 1.f);
            gemm_fma(T, T, hd, dO + h * hd, C, 1, vt, T, dsh, T, 0);
            if (dpadd) add_rows(dsh, dpadd + ((size_t)b * H + h) * T * T, T * T);
            softmax_backward_rows(dsh, P, T, scale);
        }
        /* dV = P^T dO, dQ = dS K, dK = dS^T Q, all heads per pass */
        const float *Pb = prob + (size_t)b * H * T * T;
        const ptrdiff_t hs = (ptrdiff_t)T * T;
        gemm_fma_heads(H, T, hd, T, Pb, hs, 1, T, dO, C, g + 2 * C, C3);
        gemm_fma_heads(H, T, hd, T, ds, hs, T, 1, base + C, C3, g, C3);
        gemm_fma_heads(H, T, hd, T, ds, hs, 1, T, base, C3, g + C, C3);
    }
}

/* ---- attention fused into its neighbouring products ------------------------------- */
/* A patch's attention runs as soon as the product has finished the patch's T
 * rows, while they are still in L1/L2 (at the model's batch the whole qkv does
 * not fit L2). The per-patch calls are the kernels above with B = 1, so the
 * values are those of the unfused sequence (tested). */
typedef struct {
    float *out, *prob;
    const float *qkv, *dout, *cprob;
    int T, C, H, next;
    nn_attn_mode mode;
    float *scratch;
} attn_ctx;

static void epi_attention_forward(void *p, int i0, int rows)
{
    attn_ctx *a = p;
    const size_t T = a->T, C = a->C, H = a->H;
    for (int done = (i0 + rows) / a->T; a->next < done; a->next++) {
        size_t b = a->next;
        nn_attention_forward(a->out + b * T * C, a->prob ? a->prob + b * H * T * T : NULL,
                             a->qkv + b * T * 3 * C, 1, a->T, a->C, a->H, a->mode, a->scratch);
    }
}

static void epi_attention_backward(void *p, int i0, int rows)
{
    attn_ctx *a = p;
    const size_t T = a->T, C = a->C, H = a->H;
    for (int done = (i0 + rows) / a->T; a->next < done; a->next++) {
        size_t b = a->next;
        nn_attention_backward(a->out + b * T * 3 * C, a->dout + b * T * C, a->qkv + b * T * 3 * C,
                              a->cprob ? a->cprob + b * H * T * T : NULL, 1, a->T, a->C, a->H,
                              a->mode, a->scratch);
    }
}

void nn_linear_attention_forward(float *qkv, float *out, float *prob, const float *in,
                                 const float *w, const float *b, int B, int T, int C, int H,
                                 nn_attn_mode mode, float *wt, float *scratch)
{
    const int M = B * T, N = 3 * C;
    attn_ctx a = {.out = out, .prob = prob, .qkv = qkv, .T = T, .C = C, .H = H, .mode = mode,
                  .scratch = scratch};
    linear_forward_epi(qkv, in, w, b, M, C, N, wt, epi_attention_forward, &a);
}

void nn_linear_backward_attention(float *dqkv, float *datt, float *dw, float *db,
                                  const float *dout, const float *att, const float *w,
                                  const float *qkv, const float *prob, int B, int T, int C,
                                  int H, nn_attn_mode mode, float *scratch)
{
    const int M = B * T;
    attn_ctx a = {.out = dqkv, .qkv = qkv, .dout = datt, .cprob = prob, .T = T, .C = C, .H = H,
                  .mode = mode, .scratch = scratch};
    linear_backward_epi(datt, dw, db, dout, att, w, M, C, C, epi_attention_backward, &a);
}
