/* nn: layer kernels (see nn.h). The matrix products go to gemm_fma (src/model/gemm.h:
 * bit-identical on every ISA). Every other loop is written on 8-wide GCC/Clang vector types, because -O2 without
 * fast-math will not vectorise float reductions by itself (reassociation is forbidden). The hot kernels are compiled
 * twice (target_clones: AVX2 and baseline x86-64, picked at load time); both clones execute the same lane-wise IEEE
 * operations in the same order, so their results are bit-identical - no -march=native, no FMA contraction
 * (-ffp-contract=off), no fast-math. Reductions use a fixed lane order. The vector helpers are in nn_vec.h, attention
 * in nn_attn.c. Paper §4.2; design.md §8, §10. */
#include "nn.h"
#include "nn_vec.h"
#include "gemm.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>
#if defined(NN_AVX512) || defined(NN_AVX2)
#include <immintrin.h>
#endif

/* A statement for each of four independent chains (rows, vectors), emitted
 * stage by stage, so the out-of-order core sees four chains side by side. */
#define X4 _Pragma("GCC unroll 4") for (int k = 0; k < 4; k++)

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
void nn_linear_forward_epi(float *out, const float *in, const float *w, const float *b,
                               int M, int K, int N, float *wt, gemm_epilogue epi, void *ctx)
{
    if (w) gemm_transpose(wt, w, N, K);
    gemm_fma_bias_epi(M, N, K, in, K, 1, wt, N, out, N, b, epi, ctx);
}

void nn_linear_forward(float *out, const float *in, const float *w, const float *b,
                       int M, int K, int N, float *wt)
{
    nn_linear_forward_epi(out, in, w, b, M, K, N, wt, NULL, NULL);
}

HOT static void colsum_add(float *db, const float *dout, int M, int N)
{
    colsum_block(db, dout, N, M, N);
}

/* dinp = dout w with epi on its strips (both skipped when dinp == NULL),
 * dw += dout^T in, db += column sums; every backward linear layer. */
void nn_linear_backward_epi(float *dinp, float *dw, float *db, const float *dout,
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
    nn_linear_backward_epi(dinp, dw, db, dout, in, w, M, K, N, NULL, NULL);
}

/* ---- layer norm ---------------------------------------------------------------- */
#define LN_EPS 1e-5f

/* Rows r..r+3 of the layer norm forward (C a multiple of VL), stage by stage
 * across the four rows: each row gets the operations of the one-row loop of
 * nn_layernorm_forward in their order (its sums, butterflies and scalar
 * steps), whose long reduction chains the core could not overlap row after
 * row. */
INL void ln_forward4(float *out, float *mean, float *rstd, const float *in, const float *g,
                     const float *b, int r, int C, float invC)
{
    const float *x[4];
    float *y[4], mu[4], rs[4];
    vf acc[4], vm[4], vr[4];
    X4 { x[k] = in + (size_t)(r + k) * C; y[k] = out + (size_t)(r + k) * C; acc[k] = splat(0.f); }
    for (int c = 0; c < C; c += VL) X4 acc[k] += ld(x[k] + c);
    X4 mu[k] = hsum(acc[k]) * invC;
    X4 { vm[k] = splat(mu[k]); acc[k] = splat(0.f); }
    for (int c = 0; c < C; c += VL) X4 { vf d = ld(x[k] + c) - vm[k]; acc[k] += d * d; }
    X4 rs[k] = 1.f / sqrtf(hsum(acc[k]) * invC + LN_EPS);
    X4 vr[k] = splat(rs[k]);
    for (int c = 0; c < C; c += VL)
        X4 st(y[k] + c, (ld(x[k] + c) - vm[k]) * vr[k] * ld(g + c) + ld(b + c));
    X4 { mean[r + k] = mu[k]; rstd[r + k] = rs[k]; }
}

HOT void nn_layernorm_forward(float *out, float *mean, float *rstd, const float *in,
                              const float *g, const float *b, int M, int C)
{
    const float invC = 1.f / (float)C;
    int r0 = 0;
    if (C % VL == 0)
        for (; r0 + 4 <= M; r0 += 4) ln_forward4(out, mean, rstd, in, g, b, r0, C, invC);
    for (int r = r0; r < M; r++) {
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

/* Rows r..r+3 of the layer norm backward (C a multiple of VL), stage by stage
 * as ln_forward4; dg and db still take row r's terms before row r + 1's. */
INL void ln_backward4(float *dinp, float *dg, float *db, const float *dout, const float *in,
                      const float *mean, const float *rstd, const float *g, int r, int C, float invC)
{
    const float *x[4], *dy[4];
    float *dx[4];
    vf vm[4], vr[4], s1[4], s2[4], va1[4], va2[4];
    X4 {
        x[k] = in + (size_t)(r + k) * C; dy[k] = dout + (size_t)(r + k) * C; dx[k] = dinp + (size_t)(r + k) * C;
        vm[k] = splat(mean[r + k]); vr[k] = splat(rstd[r + k]); s1[k] = splat(0.f); s2[k] = splat(0.f);
    }
    for (int c = 0; c < C; c += VL) {
        vf xh[4], d[4];
        X4 {
            xh[k] = (ld(x[k] + c) - vm[k]) * vr[k]; d[k] = ld(dy[k] + c);
            vf dxh = d[k] * ld(g + c);
            s1[k] += dxh;
            s2[k] += dxh * xh[k];
        }
        vf tg = ld(dg + c), tb = ld(db + c);
        X4 { tg = tg + d[k] * xh[k]; tb = tb + d[k]; }
        st(dg + c, tg); st(db + c, tb);
    }
    X4 {
        float a1 = hsum(s1[k]), a2 = hsum(s2[k]);
        a1 *= invC;
        a2 *= invC;
        va1[k] = splat(a1); va2[k] = splat(a2);
    }
    for (int c = 0; c < C; c += VL)
        X4 {
            vf xh = (ld(x[k] + c) - vm[k]) * vr[k];
            vf dxh = ld(dy[k] + c) * ld(g + c);
            st(dx[k] + c, ld(dx[k] + c) + vr[k] * (dxh - va1[k] - xh * va2[k]));
        }
}

HOT void nn_layernorm_backward(float *dinp, float *dg, float *db, const float *dout,
                               const float *in, const float *mean, const float *rstd,
                               const float *g, int M, int C)
{
    const float invC = 1.f / (float)C;
    int r0 = 0;
    if (C % VL == 0)
        for (; r0 + 4 <= M; r0 += 4) ln_backward4(dinp, dg, db, dout, in, mean, rstd, g, r0, C, invC);
    for (int r = r0; r < M; r++) {
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

/* The sigmoid of four vectors at once, written stage by stage across the four:
 * each vector gets the lane-wise operations of DEF_VGSIG and DEF_VEXP
 * (nn_vec.h) in their order. One vector's chain of about 35 dependent
 * operations is longer than the out-of-order window overlaps, so the bias +
 * GELU pass ran at about half its throughput with one chain at a time. */
#define DEF_VGSIG_X4(NAME, VF, VI, SPLAT) \
INL void NAME(VF *s, const VF *x) \
{ \
    const VF lo = SPLAT(-87.0f), hi = SPLAT(88.0f), shifter = SPLAT(12582912.0f); \
    VF y[4], kn[4], r[4], p[4]; \
    VI ml[4], mh[4], n[4]; \
    X4 y[k] = SPLAT(-2.f) * (SPLAT(GELU_K) * (x[k] + SPLAT(GELU_A) * x[k] * x[k] * x[k])); \
    X4 ml[k] = y[k] < lo; \
    X4 mh[k] = y[k] > hi; \
    X4 y[k] = (VF)(((VI)y[k] & ~ml[k]) | ((VI)lo & ml[k])); \
    X4 y[k] = (VF)(((VI)y[k] & ~mh[k]) | ((VI)hi & mh[k])); \
    X4 kn[k] = (y[k] * SPLAT(1.44269504088896341f) + shifter) - shifter; \
    X4 r[k] = y[k] - kn[k] * SPLAT(0.693145751953125f); \
    X4 r[k] = r[k] - kn[k] * SPLAT(1.428606765330187e-06f); \
    X4 p[k] = SPLAT(1.f / 5040.f) * r[k] + SPLAT(1.f / 720.f); \
    X4 p[k] = p[k] * r[k] + SPLAT(1.f / 120.f); \
    X4 p[k] = p[k] * r[k] + SPLAT(1.f / 24.f); \
    X4 p[k] = p[k] * r[k] + SPLAT(1.f / 6.f); \
    X4 p[k] = p[k] * r[k] + SPLAT(0.5f); \
    X4 p[k] = p[k] * r[k] + SPLAT(1.f); \
    X4 p[k] = p[k] * r[k] + SPLAT(1.f); \
    X4 n[k] = (__builtin_convertvector(kn[k], VI) + 127) << 23; \
    X4 s[k] = SPLAT(1.f) / (SPLAT(1.f) + p[k] * (VF)n[k]); \
}
DEF_VGSIG_X4(vgsig_x4, vf, vi, splat)

/* Columns [c, c + 4 * lanes) of one row of the fused bias + GELU. */
#define BIAS_GELU_X4(VF, LANES, LD, ST, SIGX4) do { \
    VF x_[4], s_[4]; \
    X4 x_[k] = LD(hr + c + LANES * k) + LD(b + c + LANES * k); \
    SIGX4(s_, x_); \
    X4 { ST(hr + c + LANES * k, x_[k]); ST(sr + c + LANES * k, s_[k]); ST(orow + c + LANES * k, x_[k] * s_[k]); } \
} while (0)

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
    if (gemm_get_isa() == GEMM_AVX512) { gelu_backward16(dinp, dout, in, sig, n); return; }
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
        if (sr) { hr[c] = x; sr[c] = sg[0]; }
        orow[c] = (x * sg)[0];
    }
}

/* The GELU forward is compute-bound (an exp and a division per value) and
 * the largest element-wise cost of a training step and of sampling; on the
 * AVX-512 and AVX2 paths it runs on intrinsics, each lane executing the
 * IEEE operations of DEF_VGSIG / DEF_VEXP in their order (no reductions
 * here), so the values are identical (test_nn_clones compares these paths
 * with the baseline build, and with a one-value reference on inputs that
 * reach the clamps, infinities and subnormals). Two of the 8-lane code's
 * steps are single instructions here, with the same results:
 *  - the clamps y < lo ? lo : y and y > hi ? hi : y are max(lo, y) and
 *    min(hi, y) (x86 max(a, b) is a > b ? a : b, min(a, b) a < b ? a : b,
 *    operand order kept: a NaN y passes through either way);
 *  - p * 2^kn built from exponent bits is scalef(p, kn) on AVX-512: kn is
 *    an integer in [-126, 127] after the clamps, so 2^kn is the same normal
 *    float and both round the same exact product.
 * sig == NULL is the forward-only form (sampling): neither x nor the
 * sigmoid is stored, out alone is written. */
/* Vectors per block of the bias + GELU (statement by statement across
 * them): measured best of 2..16 on each path, about a quarter faster than 4
 * (spills and all: the loads and stores have ports to spare). */
enum { GELU_NV512 = 8, GELU_NV256 = 16 };

#ifdef NN_AVX512
/* Columns [c, c + 16 * NV) of one row: x = h + b, out = x * sigmoid(2u),
 * vgsig's operations (clamps and 2^kn as above), statement by statement
 * across the NV vectors so that their long dependency chains (about 30
 * operations and a division each) overlap. */
#define S16 _Pragma("GCC unroll 16") for (int k = 0; k < NV; k++)
__attribute__((target("avx512f"), always_inline)) static inline void bias_gelu16_block(
    float *hr, float *sr, float *orow, const float *b, int c, const int NV)
{
    __m512 x[16], y[16], kn[16], r[16], p[16];
    S16 x[k] = _mm512_add_ps(_mm512_loadu_ps(hr + c + 16 * k), _mm512_loadu_ps(b + c + 16 * k));
    S16 y[k] = _mm512_mul_ps(_mm512_mul_ps(_mm512_set1_ps(GELU_A), x[k]), x[k]);
    S16 y[k] = _mm512_add_ps(x[k], _mm512_mul_ps(y[k], x[k]));
    S16 y[k] = _mm512_mul_ps(_mm512_set1_ps(-2.f), _mm512_mul_ps(_mm512_set1_ps(GELU_K), y[k]));
    S16 y[k] = _mm512_min_ps(_mm512_set1_ps(88.0f), _mm512_max_ps(_mm512_set1_ps(-87.0f), y[k]));
    S16 kn[k] = _mm512_add_ps(_mm512_mul_ps(y[k], _mm512_set1_ps(1.44269504088896341f)), _mm512_set1_ps(12582912.0f));
    S16 kn[k] = _mm512_sub_ps(kn[k], _mm512_set1_ps(12582912.0f));
    S16 r[k] = _mm512_sub_ps(y[k], _mm512_mul_ps(kn[k], _mm512_set1_ps(0.693145751953125f)));
    S16 r[k] = _mm512_sub_ps(r[k], _mm512_mul_ps(kn[k], _mm512_set1_ps(1.428606765330187e-06f)));
    S16 p[k] = _mm512_add_ps(_mm512_mul_ps(_mm512_set1_ps(1.f / 5040.f), r[k]), _mm512_set1_ps(1.f / 720.f));
    S16 p[k] = _mm512_add_ps(_mm512_mul_ps(p[k], r[k]), _mm512_set1_ps(1.f / 120.f));
    S16 p[k] = _mm512_add_ps(_mm512_mul_ps(p[k], r[k]), _mm512_set1_ps(1.f / 24.f));
    S16 p[k] = _mm512_add_ps(_mm512_mul_ps(p[k], r[k]), _mm512_set1_ps(1.f / 6.f));
    S16 p[k] = _mm512_add_ps(_mm512_mul_ps(p[k], r[k]), _mm512_set1_ps(0.5f));
    S16 p[k] = _mm512_add_ps(_mm512_mul_ps(p[k], r[k]), _mm512_set1_ps(1.f));
    S16 p[k] = _mm512_add_ps(_mm512_mul_ps(p[k], r[k]), _mm512_set1_ps(1.f));
    S16 p[k] = _mm512_div_ps(_mm512_set1_ps(1.f), _mm512_add_ps(_mm512_set1_ps(1.f), _mm512_scalef_ps(p[k], kn[k])));
    S16 {
        if (sr) {
            _mm512_storeu_ps(hr + c + 16 * k, x[k]);
            _mm512_storeu_ps(sr + c + 16 * k, p[k]);
        }
        _mm512_storeu_ps(orow + c + 16 * k, _mm512_mul_ps(x[k], p[k]));
    }
}
#undef S16

__attribute__((target("avx512f"))) static void bias_gelu16(float *h, float *sig, float *out,
                                                           const float *b, int M, int N)
{
    for (int r = 0; r < M; r++) {
        float *hr = h + (size_t)r * N, *sr = sig ? sig + (size_t)r * N : NULL, *orow = out + (size_t)r * N;
        int c = 0;
        for (; c + 16 * GELU_NV512 <= N; c += 16 * GELU_NV512) bias_gelu16_block(hr, sr, orow, b, c, GELU_NV512);
        for (; c + 16 <= N; c += 16) bias_gelu16_block(hr, sr, orow, b, c, 1);
        bias_gelu_tail(hr, sr, orow, b, c, N);
    }
}

#endif

#ifdef NN_AVX2
/* Columns [c, c + 8 * NV) of one row: x = h + b, out = x * sigmoid(2u),
 * vgsig's operations (the clamps as above, 2^kn from its exponent bits as DEF_VEXP builds it), statement by statement
 * across the NV vectors so that their long dependency chains (about 30
 * operations and a division each) overlap. */
#define S8 _Pragma("GCC unroll 16") for (int k = 0; k < NV; k++)
__attribute__((target("avx2"), always_inline)) static inline void bias_gelu8_block(
    float *hr, float *sr, float *orow, const float *b, int c, const int NV)
{
    __m256 x[16], y[16], kn[16], r[16], p[16];
    S8 x[k] = _mm256_add_ps(_mm256_loadu_ps(hr + c + 8 * k), _mm256_loadu_ps(b + c + 8 * k));
    S8 y[k] = _mm256_mul_ps(_mm256_mul_ps(_mm256_set1_ps(GELU_A), x[k]), x[k]);
    S8 y[k] = _mm256_add_ps(x[k], _mm256_mul_ps(y[k], x[k]));
    S8 y[k] = _mm256_mul_ps(_mm256_set1_ps(-2.f), _mm256_mul_ps(_mm256_set1_ps(GELU_K), y[k]));
    S8 y[k] = _mm256_min_ps(_mm256_set1_ps(88.0f), _mm256_max_ps(_mm256_set1_ps(-87.0f), y[k]));
    S8 kn[k] = _mm256_add_ps(_mm256_mul_ps(y[k], _mm256_set1_ps(1.44269504088896341f)), _mm256_set1_ps(12582912.0f));
    S8 kn[k] = _mm256_sub_ps(kn[k], _mm256_set1_ps(12582912.0f));
    S8 r[k] = _mm256_sub_ps(y[k], _mm256_mul_ps(kn[k], _mm256_set1_ps(0.693145751953125f)));
    S8 r[k] = _mm256_sub_ps(r[k], _mm256_mul_ps(kn[k], _mm256_set1_ps(1.428606765330187e-06f)));
    S8 p[k] = _mm256_add_ps(_mm256_mul_ps(_mm256_set1_ps(1.f / 5040.f), r[k]), _mm256_set1_ps(1.f / 720.f));
    S8 p[k] = _mm256_add_ps(_mm256_mul_ps(p[k], r[k]), _mm256_set1_ps(1.f / 120.f));
    S8 p[k] = _mm256_add_ps(_mm256_mul_ps(p[k], r[k]), _mm256_set1_ps(1.f / 24.f));
    S8 p[k] = _mm256_add_ps(_mm256_mul_ps(p[k], r[k]), _mm256_set1_ps(1.f / 6.f));
    S8 p[k] = _mm256_add_ps(_mm256_mul_ps(p[k], r[k]), _mm256_set1_ps(0.5f));
    S8 p[k] = _mm256_add_ps(_mm256_mul_ps(p[k], r[k]), _mm256_set1_ps(1.f));
    S8 p[k] = _mm256_add_ps(_mm256_mul_ps(p[k], r[k]), _mm256_set1_ps(1.f));
    S8 p[k] = _mm256_div_ps(
        _mm256_set1_ps(1.f),
        _mm256_add_ps(
            _mm256_set1_ps(1.f),
            _mm256_mul_ps(p[k], _mm256_castsi256_ps(_mm256_slli_epi32(
                                    _mm256_add_epi32(_mm256_cvttps_epi32(kn[k]), _mm256_set1_epi32(127)), 23)))));
    S8 {
        if (sr) {
            _mm256_storeu_ps(hr + c + 8 * k, x[k]);
            _mm256_storeu_ps(sr + c + 8 * k, p[k]);
        }
        _mm256_storeu_ps(orow + c + 8 * k, _mm256_mul_ps(x[k], p[k]));
    }
}
#undef S8

__attribute__((target("avx2"))) static void bias_gelu8(float *h, float *sig, float *out,
                                                       const float *b, int M, int N)
{
    for (int r = 0; r < M; r++) {
        float *hr = h + (size_t)r * N, *sr = sig ? sig + (size_t)r * N : NULL, *orow = out + (size_t)r * N;
        int c = 0;
        for (; c + 8 * GELU_NV256 <= N; c += 8 * GELU_NV256) bias_gelu8_block(hr, sr, orow, b, c, GELU_NV256);
        for (; c + 8 <= N; c += 8) bias_gelu8_block(hr, sr, orow, b, c, 1);
        bias_gelu_tail(hr, sr, orow, b, c, N);
    }
}
#endif

#ifdef NN_AVX512
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
    if (gemm_get_isa() == GEMM_AVX512) { bias_gelu16(h, sig, out, b, M, N); return; }
#endif
#ifdef NN_AVX2
    if (gemm_get_isa() == GEMM_AVX2) { bias_gelu8(h, sig, out, b, M, N); return; }
#endif
    for (int r = 0; r < M; r++) {
        float *hr = h + (size_t)r * N, *sr = sig ? sig + (size_t)r * N : NULL, *orow = out + (size_t)r * N;
        int c = 0;
        for (; sr && c + 4 * VL <= N; c += 4 * VL) BIAS_GELU_X4(vf, VL, ld, st, vgsig_x4);
        for (; c + VL <= N; c += VL) {
            vf x = ld(hr + c) + ld(b + c), sg = vgsig(x);
            if (sr) { st(hr + c, x); st(sr + c, sg); }
            st(orow + c, x * sg);
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
    nn_bias_gelu_forward_save(f->h + o, f->sig ? f->sig + o : NULL, f->out + o, f->b, rows, f->N);
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
    nn_linear_forward_epi(h, in, w, NULL, M, K, N, wt, epi_bias_gelu, &f);
}

void nn_linear_bias_residual_forward(float *out, const float *in, const float *w,
                                     const float *b, const float *x, float *ln, float *mean,
                                     float *rstd, const float *g, const float *beta,
                                     int M, int K, int N, float *wt)
{
    fuse_ctx f = {.out = out, .ln = ln, .mean = mean, .rstd = rstd, .b = b, .x = x,
                  .g = g, .beta = beta, .N = N};
    nn_linear_forward_epi(out, in, w, NULL, M, K, N, wt, epi_bias_residual_ln, &f);
}

void nn_linear_backward_gelu(float *dinp, float *dw, float *db, const float *dout,
                             const float *in, const float *w, const float *h,
                             const float *sig, int M, int K, int N)
{
    fuse_ctx f = {.h = dinp, .hin = h, .hsig = sig, .N = K};
    nn_linear_backward_epi(dinp, dw, db, dout, in, w, M, K, N, epi_gelu_backward, &f);
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
