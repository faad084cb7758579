/* nn_attn: multi-head self-attention of one patch (see nn.h): the generic
 * kernels on gemm_fma, the AVX-512 register-blocked kernels at the reference
 * head shape (T = 24, hd = 16), and attention fused into its neighbouring
 * linear products. Compiled like nn.c (target clones, no FMA contraction, no
 * fast-math), with the same vector helpers (nn_vec.h), so every path gives
 * the same bits (test_nn_clones). Paper §4.2; design.md §8, §10. */
#include "nn.h"
#include "nn_vec.h"
#include "gemm.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

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
#if defined(NN_AVX512) || defined(NN_AVX2)
#include <immintrin.h>
#endif
#ifdef NN_AVX512
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

/* softmax_row on 12 rows of 24 (chunks j 0-7, 8-15, 16-23), in passes over
 * the rows (maxima; exponentials, four rows at a time; sums; scaling) so
 * that the rows' long dependency chains overlap instead of following one
 * another; maxima and exponentials on intrinsics (nn_vec.h). */
A512 void softmax24x12(float *s)
{
    float mx[12], inv[12];
    for (int r = 0; r < 12; r++) mx[r] = max24_avx(s + r * 24);
    for (int r = 0; r < 12; r += 4) exp_rows4_avx512(s, mx, r);
    for (int r = 0; r < 12; r++) inv[r] = vsum(s + r * 24, 24);
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

/* ---- attention on AVX2 at the reference head shape ------------------------------- */
/* The same register blocking on 8-lane vectors, sized for the 16 ymm
 * registers: a score block is 4 rows x 24 (12 accumulators), an hd-wide
 * block 6 rows x 16 (12 accumulators). Every element is one fma chain over
 * k ascending from +0 and the softmax keeps softmax_row's operations, so the
 * values are those of the generic kernels (test_nn_clones). */
#ifdef NN_AVX2
#define A256 __attribute__((target("avx2,fma"), always_inline)) static inline

/* S[4 x 24] (row stride 24) = A[4 x 16] (row stride ars) Bt[16 x 24]. */
A256 void tt_block8(float *S, const float *A, ptrdiff_t ars, const float *Bt)
{
    __m256 c[4][3];
    _Pragma("GCC unroll 4") for (int r = 0; r < 4; r++)
        _Pragma("GCC unroll 3") for (int q = 0; q < 3; q++) c[r][q] = _mm256_setzero_ps();
    for (int d = 0; d < 16; d++) {
        const __m256 b0 = _mm256_loadu_ps(Bt + d * 24), b1 = _mm256_loadu_ps(Bt + d * 24 + 8);
        const __m256 b2 = _mm256_loadu_ps(Bt + d * 24 + 16);
        _Pragma("GCC unroll 4") for (int r = 0; r < 4; r++) {
            const __m256 x = _mm256_broadcast_ss(A + r * ars + d);
            c[r][0] = _mm256_fmadd_ps(x, b0, c[r][0]);
            c[r][1] = _mm256_fmadd_ps(x, b1, c[r][1]);
            c[r][2] = _mm256_fmadd_ps(x, b2, c[r][2]);
        }
    }
    _Pragma("GCC unroll 4") for (int r = 0; r < 4; r++)
        _Pragma("GCC unroll 3") for (int q = 0; q < 3; q++) _mm256_storeu_ps(S + r * 24 + 8 * q, c[r][q]);
}

/* Cm[6 x 16] (row stride ldc) = sum over k < 24 of A(r, k) B[k][0..15],
 * A(r, k) = A[r * ars + k * aks]; ars and aks are literals at every call. */
A256 void hw_block8(float *Cm, ptrdiff_t ldc, const float *A, const ptrdiff_t ars, const ptrdiff_t aks,
                    const float *B, ptrdiff_t ldb)
{
    __m256 c[6][2];
    _Pragma("GCC unroll 6") for (int r = 0; r < 6; r++)
    {
        c[r][0] = _mm256_setzero_ps();
        c[r][1] = _mm256_setzero_ps();
    }
    for (int k = 0; k < 24; k++) {
        const __m256 b0 = _mm256_loadu_ps(B + k * ldb), b1 = _mm256_loadu_ps(B + k * ldb + 8);
        _Pragma("GCC unroll 6") for (int r = 0; r < 6; r++) {
            const __m256 x = _mm256_broadcast_ss(A + r * ars + k * aks);
            c[r][0] = _mm256_fmadd_ps(x, b0, c[r][0]);
            c[r][1] = _mm256_fmadd_ps(x, b1, c[r][1]);
        }
    }
    _Pragma("GCC unroll 6") for (int r = 0; r < 6; r++) {
        _mm256_storeu_ps(Cm + r * ldc, c[r][0]);
        _mm256_storeu_ps(Cm + r * ldc + 8, c[r][1]);
    }
}

/* softmax_row on 12 rows of 24 in passes over the rows as softmax24x12
 * (exponentials two rows at a time). */
A256 void softmax24x12_8(float *s)
{
    float mx[12], inv[12];
    for (int r = 0; r < 12; r++) mx[r] = max24_avx(s + r * 24);
    for (int r = 0; r < 12; r += 2) exp_rows2_avx2(s, mx, r);
    for (int r = 0; r < 12; r++) inv[r] = vsum(s + r * 24, 24);
    for (int r = 0; r < 12; r++) inv[r] = 1.f / inv[r];
    for (int r = 0; r < 12; r++) {
        float *row = s + r * 24;
        st(row, ld(row) * inv[r]);
        st(row + 8, ld(row + 8) * inv[r]);
        st(row + 16, ld(row + 16) * inv[r]);
    }
}

/* softmax_backward_rows on one row of 24: d = p (d - p.d) scale. */
A256 void softmax_backward24_8(float *d, const float *p, float scale)
{
    const float dot = vdot(p, d, 24);
    for (int j = 0; j < 24; j += 8) st(d + j, ld(p + j) * (ld(d + j) - dot) * scale);
}

/* One patch (24 tokens), all heads: the values of nn_attention_forward. */
__attribute__((target("avx2,fma"))) static void attention_forward24_avx2(float *out, float *prob,
                                                                         const float *qkv, int C, int H,
                                                                         float *kt, const float *sb)
{
    const int C3 = 3 * C;
    const float scale = 1.f / sqrtf(16.f);
    for (int h = 0; h < H; h++) {
        float *P = prob + (size_t)h * 576;
        gemm_transpose_scaled(kt, 24, qkv + C + h * 16, C3, 24, 16, scale);
        for (int i0 = 0; i0 < 24; i0 += 12) {
            for (int r = i0; r < i0 + 12; r += 4) tt_block8(P + r * 24, qkv + (size_t)r * C3 + h * 16, C3, kt);
            if (sb) add_rows(P + i0 * 24, sb + (size_t)h * 576 + i0 * 24, 12 * 24);
            softmax24x12_8(P + i0 * 24);
            for (int r = i0; r < i0 + 12; r += 6)
                hw_block8(out + (size_t)r * C + h * 16, C, P + r * 24, 24, 1, qkv + 2 * C + h * 16, C3);
        }
    }
}

/* One patch, all heads: the values of nn_attention_backward. */
__attribute__((target("avx2,fma"))) static void attention_backward24_avx2(float *g, const float *dO,
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
        for (int r = 0; r < 24; r += 4) tt_block8(dsh + r * 24, dO + (size_t)r * C + h * 16, C, vt);
        if (dpx) add_rows(dsh, dpx + (size_t)h * 576, 576);
        for (int r = 0; r < 24; r++) softmax_backward24_8(dsh + r * 24, P + r * 24, scale);
        for (int i0 = 0; i0 < 24; i0 += 6) {
            const size_t o = (size_t)i0 * C3 + h * 16;
            hw_block8(g + 2 * C + o, C3, P + i0, 1, 24, dO + h * 16, C);  /* dV = P^T dO */
            hw_block8(g + o, C3, dsh + i0 * 24, 24, 1, k, C3);             /* dQ = dS K */
            hw_block8(g + C + o, C3, dsh + i0, 1, 24, q, C3);              /* dK = dS^T Q */
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
    if (T == 24 && hd == 16 && gemm_get_isa() == GEMM_AVX512) {
        for (int b = 0; b < B; b++)
            attention_forward24(out + (size_t)b * T * C, prob + (size_t)b * H * T * T,
                                qkv + (size_t)b * T * C3, C, H, scratch,
                                sbias ? sbias + (size_t)b * H * T * T : NULL);
        return;
    }
#endif
#ifdef NN_AVX2
    if (T == 24 && hd == 16 && gemm_get_isa() == GEMM_AVX2) {
        for (int b = 0; b < B; b++)
            attention_forward24_avx2(out + (size_t)b * T * C, prob + (size_t)b * H * T * T,
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
    if (T == 24 && hd == 16 && gemm_get_isa() == GEMM_AVX512) {
        for (int b = 0; b < B; b++)
            attention_backward24(dqkv + (size_t)b * T * C3, dout + (size_t)b * T * C,
                                 qkv + (size_t)b * T * C3, prob + (size_t)b * H * T * T, C, H, ds, vt,
                                 dpadd ? dpadd + (size_t)b * H * T * T : NULL);
        return;
    }
#endif
#ifdef NN_AVX2
    if (T == 24 && hd == 16 && gemm_get_isa() == GEMM_AVX2) {
        for (int b = 0; b < B; b++)
            attention_backward24_avx2(dqkv + (size_t)b * T * C3, dout + (size_t)b * T * C,
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
    if (mode == NN_ATTN_SELF) { /* only the v columns (see nn.h) */
        if (w) gemm_transpose(wt, w, N, C);
        gemm_fma_bias_epi(M, C, C, in, C, 1, wt + 2 * C, N, qkv + 2 * C, N, b ? b + 2 * C : NULL,
                          epi_attention_forward, &a);
        return;
    }
    nn_linear_forward_epi(qkv, in, w, b, M, C, N, wt, epi_attention_forward, &a);
}

void nn_linear_backward_attention(float *dqkv, float *datt, float *dw, float *db,
                                  const float *dout, const float *att, const float *w,
                                  const float *qkv, const float *prob, int B, int T, int C,
                                  int H, nn_attn_mode mode, float *scratch)
{
    const int M = B * T;
    attn_ctx a = {.out = dqkv, .qkv = qkv, .dout = datt, .cprob = prob, .T = T, .C = C, .H = H,
                  .mode = mode, .scratch = scratch};
    nn_linear_backward_epi(datt, dw, db, dout, att, w, M, C, C, epi_attention_backward, &a);
}

/* db[0..n) += rows of x (row stride ldx), row after row: the additions of
 * nn.c's column sums, on a strided block. */
HOT static void colsum_add_strided(float *db, const float *x, ptrdiff_t ldx, int M, int n)
{
    colsum_block(db, x, ldx, M, n);
}

void nn_linear_backward_qkv(float *dinp, float *dw, float *db, const float *dqkv,
                            const float *in, const float *w, int M, int C, nn_attn_mode mode)
{
    if (mode != NN_ATTN_SELF) {
        nn_linear_backward(dinp, dw, db, dqkv, in, w, M, C, 3 * C);
        return;
    }
    const int N = 3 * C;
    const float *dv = dqkv + 2 * C, *wv = w + (size_t)2 * C * C;
    if (dinp) gemm_fma(M, C, C, dv, N, 1, wv, C, dinp, C, 0);
    gemm_fma(C, C, M, dv, 1, N, in, C, dw + (size_t)2 * C * C, C, 1);
    if (db) colsum_add_strided(db + 2 * C, dv, N, M, C);
}
