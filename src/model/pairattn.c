/* pairattn: pair-aware attention (see pairattn.h; design.md §8.1).
 * Per patch and layer the pair terms are a handful of small gemm_fma
 * products around nn.c's attention kernels, which take the score bias and
 * the extra dP term through nn_attention_*_biased (their AVX-512 kernel at
 * the reference shape included). Every product is one fma chain per element
 * (gemm.h) and the remaining loops are scalar, so the values do not depend
 * on the ISA (tested against all gemm paths and nn.c's baseline clone). */
#include "pairattn.h"
#include "gemm.h"
#include <math.h>
#include <string.h>

enum { Q = PAIRATTN_Q };

/* The features of pair (i, j) into o[0..Q), in double, rounded to float. */
static void pair_features(float *o, const float *tok, int stride, int i, int j)
{
    const double xi = tok[(size_t)i * stride], yi = tok[(size_t)i * stride + 1];
    const double ri = tok[(size_t)i * stride + 2];
    const double dx = (double)tok[(size_t)j * stride] - xi;
    const double dy = (double)tok[(size_t)j * stride + 1] - yi;
    const double dist = sqrt(dx * dx + dy * dy);
    const double c = dist > 0 ? dx / dist : 0.0, s = dist > 0 ? dy / dist : 0.0;
    o[0] = (float)dx;
    o[1] = (float)dy;
    o[2] = (float)dist;
    o[3] = (float)(dist - ri - (double)tok[(size_t)j * stride + 2]);
    o[4] = (float)c;
    o[5] = (float)s;
    o[6] = (float)(c * c - s * s);
    o[7] = (float)(2 * c * s);
}

void pairattn_features(float *f, const float *tok, int stride, int T)
{
    for (int i = 0; i < T; i++)
        for (int j = 0; j < T; j++) pair_features(f + ((size_t)i * T + j) * Q, tok, stride, i, j);
}

/* ---- the geometry on 4 pairs at a time ---------------------------------------------- */
/* pairattn_geometry runs once per patch and training step (and once per
 * patch of a sampling call): a square root and two divisions per pair in
 * double. Here 4 pairs (i, j..j+3) go through the same double operations in
 * the same order on 4 lanes (each lane the scalar code of pairattn_features),
 * the z-scores in float on 4 lanes, and a 4 x 4 transpose gives the
 * pair-major rows; test_pairattn compares every gemm path with naive loops. */
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define GEOM_VEC 1
#include <immintrin.h>
__attribute__((target("avx2"))) static void geometry_row4(float *phi, float *phit, const double *xs,
                                                         const double *ys, const double *rs, int T, int i, int j,
                                                         const float *mu, const float *isd)
{
    const size_t TT = (size_t)T * T, e = (size_t)i * T + j;
    const __m256d zero = _mm256_setzero_pd(), two = _mm256_set1_pd(2.0);
    const __m256d dx = _mm256_sub_pd(_mm256_loadu_pd(xs + j), _mm256_set1_pd(xs[i]));
    const __m256d dy = _mm256_sub_pd(_mm256_loadu_pd(ys + j), _mm256_set1_pd(ys[i]));
    const __m256d dist = _mm256_sqrt_pd(_mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy)));
    const __m256d pos = _mm256_cmp_pd(dist, zero, _CMP_GT_OQ);
    const __m256d c = _mm256_and_pd(pos, _mm256_div_pd(dx, dist)), sn = _mm256_and_pd(pos, _mm256_div_pd(dy, dist));
    const __m256d f[Q] = {dx, dy, dist,
                          _mm256_sub_pd(_mm256_sub_pd(dist, _mm256_set1_pd(rs[i])), _mm256_loadu_pd(rs + j)),
                          c, sn, _mm256_sub_pd(_mm256_mul_pd(c, c), _mm256_mul_pd(sn, sn)),
                          _mm256_mul_pd(_mm256_mul_pd(two, c), sn)};
    __m128 z[Q];
    for (int q = 0; q < Q; q++) {
        z[q] = _mm_mul_ps(_mm_sub_ps(_mm256_cvtpd_ps(f[q]), _mm_set1_ps(mu[q])), _mm_set1_ps(isd[q]));
        _mm_storeu_ps(phit + q * TT + e, z[q]);
    }
    _MM_TRANSPOSE4_PS(z[0], z[1], z[2], z[3]);
    _MM_TRANSPOSE4_PS(z[4], z[5], z[6], z[7]);
    for (int u = 0; u < 4; u++) {
        _mm_storeu_ps(phi + (e + u) * Q, z[u]);
        _mm_storeu_ps(phi + (e + u) * Q + 4, z[4 + u]);
    }
}
#endif

/* The features of pairs (i, j) for j in [j0, T), then their z-scores. */
static void geometry_tail(float *phi, float *phit, const float *tok, int stride, int T, int i, int j0,
                          const float *mu, const float *isd)
{
    const size_t TT = (size_t)T * T;
    for (int j = j0; j < T; j++) {
        const size_t e = (size_t)i * T + j;
        pair_features(phi + e * Q, tok, stride, i, j);
        for (int q = 0; q < Q; q++) {
            float z = (phi[e * Q + q] - mu[q]) * isd[q];
            phi[e * Q + q] = z;
            phit[(size_t)q * TT + e] = z;
        }
    }
}

void pairattn_geometry(float *phi, float *phit, const float *tok, int stride, int T,
                       const float *mu, const float *isd)
{
    int j4 = 0;
#ifdef GEOM_VEC
    enum { TMAX = 64 };
    if (T <= TMAX && gemm_get_isa() >= GEMM_AVX2) {
        double xs[TMAX], ys[TMAX], rs[TMAX];
        for (int j = 0; j < T; j++) {
            xs[j] = tok[(size_t)j * stride];
            ys[j] = tok[(size_t)j * stride + 1];
            rs[j] = tok[(size_t)j * stride + 2];
        }
        j4 = T - T % 4;
        for (int i = 0; i < T; i++)
            for (int j = 0; j < j4; j += 4) geometry_row4(phi, phit, xs, ys, rs, T, i, j, mu, isd);
    }
#endif
    for (int i = 0; i < T; i++) geometry_tail(phi, phit, tok, stride, T, i, j4, mu, isd);
}

size_t pairattn_scratch_len(int T, int C, int H)
{
    return nn_attention_scratch_len(T, C, H) + (size_t)H * T * T + (size_t)H * T * Q;
}

/* ---- the two batched pair products on 8 lanes -------------------------------------- */
/* Phi (a mix over j per row i) and dP's pair term (a product per row i) are
 * T products of H rows each; one gemm_fma call per row keeps only H chains in
 * flight and waits on the fma latency. Here 3 rows x 4 heads of chains (12
 * ymm accumulators; one 8-lane vector is the Q = 8 features, or 8 keys j)
 * run together, each still one fma chain in the gemm_fma order from +0, so
 * the values are those of the per-row calls (test_pairattn compares every
 * gemm path, whose scalar path takes the calls). AVX2 lanes on the AVX-512
 * path too: at Q = 8 the 16-lane form would need two rows per register. */
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#define PAIR_VEC 1
#define A256 __attribute__((target("avx2,fma"), always_inline)) static inline

/* Phi[h][i][0..8) = sum_j prob[h][i][j] phi[i][j][0..8), rows i..i+2, heads h0..h0+3 */
A256 void mix3x4(float *Phi, const float *prob, const float *phi, int T, int i, int h0)
{
    const size_t TT = (size_t)T * T;
    __m256 c[3][4];
    _Pragma("GCC unroll 3") for (int u = 0; u < 3; u++)
        _Pragma("GCC unroll 4") for (int v = 0; v < 4; v++) c[u][v] = _mm256_setzero_ps();
    for (int j = 0; j < T; j++) {
        _Pragma("GCC unroll 3") for (int u = 0; u < 3; u++) {
            const __m256 b = _mm256_loadu_ps(phi + ((size_t)(i + u) * T + j) * Q);
            _Pragma("GCC unroll 4") for (int v = 0; v < 4; v++) c[u][v] =
                _mm256_fmadd_ps(_mm256_broadcast_ss(prob + (h0 + v) * TT + (size_t)(i + u) * T + j), b, c[u][v]);
        }
    }
    _Pragma("GCC unroll 3") for (int u = 0; u < 3; u++)
        _Pragma("GCC unroll 4") for (int v = 0; v < 4; v++)
            _mm256_storeu_ps(Phi + ((size_t)(h0 + v) * T + i + u) * Q, c[u][v]);
}

/* dpx[h][i][j..j+8) = sum_q dPhi[h][i][q] phit[q][i*T + j..], row i, heads h0..h0+3, j < 24 */
A256 void dpair1x4(float *dpx, const float *dPhi, const float *phit, int T, int i, int h0)
{
    const size_t TT = (size_t)T * T;
    __m256 c[4][3];
    _Pragma("GCC unroll 4") for (int v = 0; v < 4; v++)
        _Pragma("GCC unroll 3") for (int w = 0; w < 3; w++) c[v][w] = _mm256_setzero_ps();
    for (int q = 0; q < Q; q++) {
        const float *b = phit + (size_t)q * TT + (size_t)i * T;
        const __m256 b0 = _mm256_loadu_ps(b), b1 = _mm256_loadu_ps(b + 8), b2 = _mm256_loadu_ps(b + 16);
        _Pragma("GCC unroll 4") for (int v = 0; v < 4; v++) {
            const __m256 a = _mm256_broadcast_ss(dPhi + ((size_t)(h0 + v) * T + i) * Q + q);
            c[v][0] = _mm256_fmadd_ps(a, b0, c[v][0]);
            c[v][1] = _mm256_fmadd_ps(a, b1, c[v][1]);
            c[v][2] = _mm256_fmadd_ps(a, b2, c[v][2]);
        }
    }
    _Pragma("GCC unroll 4") for (int v = 0; v < 4; v++)
        _Pragma("GCC unroll 3") for (int w = 0; w < 3; w++)
            _mm256_storeu_ps(dpx + (h0 + v) * TT + (size_t)i * T + 8 * w, c[v][w]);
}

/* out[i][j..j+32) += sum_q Phi[h_v][i][q] wvt[q][j + 8v..], rows i..i+2 (the
 * value term of every head at once; vector v of the block is in head h_v) */
A256 void value3x4(float *out, const float *Phi, const float *wvt, int T, int C, int hd, int i, int j)
{
    __m256 c[3][4], b[4];
    _Pragma("GCC unroll 3") for (int u = 0; u < 3; u++) _Pragma("GCC unroll 4") for (int v = 0; v < 4; v++) c[u][v] =
        _mm256_loadu_ps(out + (size_t)(i + u) * C + j + 8 * v);
    for (int q = 0; q < Q; q++) {
        _Pragma("GCC unroll 4") for (int v = 0; v < 4; v++) b[v] = _mm256_loadu_ps(wvt + (size_t)q * C + j + 8 * v);
        _Pragma("GCC unroll 3") for (int u = 0; u < 3; u++)
            _Pragma("GCC unroll 4") for (int v = 0; v < 4; v++) {
                const int h = (j + 8 * v) / hd;
                c[u][v] = _mm256_fmadd_ps(_mm256_broadcast_ss(Phi + ((size_t)h * T + i + u) * Q + q), b[v], c[u][v]);
            }
    }
    _Pragma("GCC unroll 3") for (int u = 0; u < 3; u++) _Pragma("GCC unroll 4") for (int v = 0; v < 4; v++)
        _mm256_storeu_ps(out + (size_t)(i + u) * C + j + 8 * v, c[u][v]);
}

/* dPhi[h][i][0..8) = sum_d dO[i][h hd + d] wv[h hd + d][0..8), rows i..i+2, heads h0..h0+3 */
A256 void dphi3x4(float *dPhi, const float *dO, const float *wv, int T, int C, int hd, int i, int h0)
{
    __m256 c[3][4], b[4];
    _Pragma("GCC unroll 3") for (int u = 0; u < 3; u++)
        _Pragma("GCC unroll 4") for (int v = 0; v < 4; v++) c[u][v] = _mm256_setzero_ps();
    for (int d = 0; d < hd; d++) {
        _Pragma("GCC unroll 4") for (int v = 0; v < 4; v++) b[v] =
            _mm256_loadu_ps(wv + ((size_t)(h0 + v) * hd + d) * Q);
        _Pragma("GCC unroll 3") for (int u = 0; u < 3; u++) _Pragma("GCC unroll 4") for (int v = 0; v < 4; v++)
            c[u][v] = _mm256_fmadd_ps(_mm256_broadcast_ss(dO + (size_t)(i + u) * C + (h0 + v) * hd + d), b[v], c[u][v]);
    }
    _Pragma("GCC unroll 3") for (int u = 0; u < 3; u++) _Pragma("GCC unroll 4") for (int v = 0; v < 4; v++)
        _mm256_storeu_ps(dPhi + ((size_t)(h0 + v) * T + i + u) * Q, c[u][v]);
}

/* dwv[h hd + d][0..8) += sum_i dO[i][h hd + d] Phi[h][i][0..8), d..d+1, heads h0..h0+3 */
A256 void dwv2x4(float *dwv, const float *dO, const float *Phi, int T, int C, int hd, int d, int h0)
{
    __m256 c[2][4], b[4];
    _Pragma("GCC unroll 2") for (int u = 0; u < 2; u++) _Pragma("GCC unroll 4") for (int v = 0; v < 4; v++) c[u][v] =
        _mm256_loadu_ps(dwv + ((size_t)(h0 + v) * hd + d + u) * Q);
    for (int i = 0; i < T; i++) {
        _Pragma("GCC unroll 4") for (int v = 0; v < 4; v++) b[v] =
            _mm256_loadu_ps(Phi + ((size_t)(h0 + v) * T + i) * Q);
        _Pragma("GCC unroll 2") for (int u = 0; u < 2; u++) _Pragma("GCC unroll 4") for (int v = 0; v < 4; v++)
            c[u][v] = _mm256_fmadd_ps(_mm256_broadcast_ss(dO + (size_t)i * C + (h0 + v) * hd + d + u), b[v], c[u][v]);
    }
    _Pragma("GCC unroll 2") for (int u = 0; u < 2; u++) _Pragma("GCC unroll 4") for (int v = 0; v < 4; v++)
        _mm256_storeu_ps(dwv + ((size_t)(h0 + v) * hd + d + u) * Q, c[u][v]);
}

/* x[0..n) = s * x[0..n) (a product per value, as the scalar loop) */
__attribute__((target("avx2"))) static void scale_avx2(float *x, size_t n, float s)
{
    const __m256 vs = _mm256_set1_ps(s);
    size_t e = 0;
    for (; e + 8 <= n; e += 8) _mm256_storeu_ps(x + e, _mm256_mul_ps(vs, _mm256_loadu_ps(x + e)));
    for (; e < n; e++) x[e] = s * x[e];
}

__attribute__((target("avx2,fma"))) static void value_avx2(float *out, const float *Phi, const float *wvt, int T, int C,
                                                           int H)
{
    for (int i = 0; i < T; i += 3)
        for (int j = 0; j < C; j += 32) value3x4(out, Phi, wvt, T, C, C / H, i, j);
}

__attribute__((target("avx2,fma"))) static void dvalue_avx2(float *dPhi, float *dwv, const float *dO, const float *Phi,
                                                            const float *wv, int T, int C, int H)
{
    const int hd = C / H;
    for (int h0 = 0; h0 < H; h0 += 4) {
        for (int i = 0; i < T; i += 3) dphi3x4(dPhi, dO, wv, T, C, hd, i, h0);
        for (int d = 0; d < hd; d += 2) dwv2x4(dwv, dO, Phi, T, C, hd, d, h0);
    }
}

__attribute__((target("avx2,fma"))) static void mix_avx2(float *Phi, const float *prob, const float *phi, int T, int H)
{
    for (int h0 = 0; h0 < H; h0 += 4)
        for (int i = 0; i < T; i += 3) mix3x4(Phi, prob, phi, T, i, h0);
}

__attribute__((target("avx2,fma"))) static void dpair_avx2(float *dpx, const float *dPhi, const float *phit, int T,
                                                           int H)
{
    for (int h0 = 0; h0 < H; h0 += 4)
        for (int i = 0; i < T; i++) dpair1x4(dpx, dPhi, phit, T, i, h0);
}
#endif

/* Phi[h][i][q] = sum_j a_hij phi_ijq (one gemm_fma call per row i, all heads). */
static void pair_mix(float *Phi, const float *prob, const float *phi, int T, int H)
{
    const size_t TT = (size_t)T * T;
#ifdef PAIR_VEC
    if (T % 3 == 0 && H % 4 == 0 && gemm_get_isa() >= GEMM_AVX2) { mix_avx2(Phi, prob, phi, T, H); return; }
#endif
    for (int i = 0; i < T; i++)
        gemm_fma(H, Q, T, prob + (size_t)i * T, TT, 1, phi + (size_t)i * T * Q, Q, Phi + (size_t)i * Q,
                 (ptrdiff_t)T * Q, 0);
}

/* dpx[h][i][j] = dPhi_hi . phi_ij (one gemm_fma call per row i, all heads). */
static void pair_dp(float *dpx, const float *dPhi, const float *phit, int T, int H)
{
    const size_t TT = (size_t)T * T;
#ifdef PAIR_VEC
    if (T == 24 && H % 4 == 0 && gemm_get_isa() >= GEMM_AVX2) { dpair_avx2(dpx, dPhi, phit, T, H); return; }
#endif
    for (int i = 0; i < T; i++)
        gemm_fma(H, T, Q, dPhi + (size_t)i * Q, (ptrdiff_t)T * Q, 1, phit + (size_t)i * T, TT,
                 dpx + (size_t)i * T, TT, 0);
}

/* The value term out_h += Phi_h Wv_h^T of every head (one gemm_fma call per
 * head, or 3 rows x 32 columns of chains at a time: the same chains). */
static void pair_value(float *out, const float *Phi, const float *wvt, int T, int C, int H)
{
    const int hd = C / H;
#ifdef PAIR_VEC
    if (T % 3 == 0 && C % 32 == 0 && hd % 8 == 0 && gemm_get_isa() >= GEMM_AVX2) {
        value_avx2(out, Phi, wvt, T, C, H);
        return;
    }
#endif
    for (int h = 0; h < H; h++)
        gemm_fma(T, hd, Q, Phi + (size_t)h * T * Q, Q, 1, wvt + h * hd, C, out + h * hd, C, 1);
}

/* dPhi_h = dO_h Wv_h; dWv_h += dO_h^T Phi_h, every head (per-head gemm_fma
 * calls, or 12 and 8 chains at a time: the same chains). */
static void pair_dvalue(float *dPhi, float *dwv, const float *dO, const float *Phi, const float *wv,
                        int T, int C, int H)
{
    const int hd = C / H;
#ifdef PAIR_VEC
    if (T % 3 == 0 && H % 4 == 0 && hd % 2 == 0 && gemm_get_isa() >= GEMM_AVX2) {
        dvalue_avx2(dPhi, dwv, dO, Phi, wv, T, C, H);
        return;
    }
#endif
    for (int h = 0; h < H; h++) {
        gemm_fma(T, Q, hd, dO + h * hd, C, 1, wv + (size_t)h * hd * Q, Q, dPhi + (size_t)h * T * Q, Q, 0);
        gemm_fma(hd, Q, T, dO + h * hd, 1, C, Phi + (size_t)h * T * Q, Q, dwv + (size_t)h * hd * Q, Q, 1);
    }
}

/* One patch: out[T x C], prob[H x T x T], Phi[H x T x Q] from qkv[T x 3C]. */
static void patch_forward(float *out, float *prob, float *Phi, const float *qkv, const float *phi,
                          const float *phit, const float *wb, const float *wvt, int T, int C, int H,
                          nn_attn_mode mode, float *scratch)
{
    const int hd = C / H, TT = T * T;
    float *sb = scratch + nn_attention_scratch_len(T, C, H); /* [H x T x T] scale * beta */
    if (mode == NN_ATTN_JOINT) {
        const float scale = 1.f / sqrtf((float)hd);
        gemm_fma(H, TT, Q, wb, Q, 1, phit, TT, sb, TT, 0); /* beta[h][ij] = wb_h . phi_ij */
#ifdef PAIR_VEC
        if (gemm_get_isa() >= GEMM_AVX2) scale_avx2(sb, (size_t)H * TT, scale);
        else
#endif
            for (size_t e = 0; e < (size_t)H * TT; e++) sb[e] = scale * sb[e];
        nn_attention_forward_biased(out, prob, qkv, sb, 1, T, C, H, mode, scratch);
        pair_mix(Phi, prob, phi, T, H); /* Phi[h][i][q] = sum_j a_hij phi_ijq */
    } else {
        nn_attention_forward(out, NULL, qkv, 1, T, C, H, mode, scratch);
        for (int h = 0; h < H; h++)
            for (int i = 0; i < T; i++)
                memcpy(Phi + ((size_t)h * T + i) * Q, phi + ((size_t)i * T + i) * Q, sizeof(float) * Q);
    }
    pair_value(out, Phi, wvt, T, C, H); /* out_h += Phi_h Wv_h^T */
}

/* One patch: dqkv[T x 3C] from dO[T x C]; dwb, dwv accumulate. */
static void patch_backward(float *dqkv, float *dwb, float *dwv, const float *dO, const float *qkv,
                           const float *prob, const float *Phi, const float *phi, const float *phit,
                           const float *wv, int T, int C, int H, nn_attn_mode mode, float *scratch)
{
    const int TT = T * T;
    float *dpx = scratch + nn_attention_scratch_len(T, C, H); /* [H x T x T] */
    float *dPhi = dpx + (size_t)H * TT;                       /* [H x T x Q] */
    pair_dvalue(dPhi, dwv, dO, Phi, wv, T, C, H); /* dPhi_h = dO_h Wv_h; dWv_h += dO_h^T Phi_h */
    if (mode == NN_ATTN_JOINT) {
        pair_dp(dpx, dPhi, phit, T, H); /* dP[h][i][j] gains dPhi_hi . phi_ij */
        nn_attention_backward_biased(dqkv, dO, qkv, prob, dpx, 1, T, C, H, mode, scratch);
        /* scratch holds dS = d/d(q.k), which is d/d(beta): dwb += dS phi */
        gemm_fma(H, Q, TT, scratch, TT, 1, phi, Q, dwb, Q, 1);
    } else {
        nn_attention_backward(dqkv, dO, qkv, NULL, 1, T, C, H, mode, scratch);
    }
}

void pairattn_forward(float *out, float *prob, float *Phi, const float *qkv, const float *phi,
                      const float *phit, const float *wb, const float *wv, float *wvt,
                      int B, int T, int C, int H, nn_attn_mode mode, float *scratch)
{
    const size_t TT = (size_t)T * T;
    if (wv) gemm_transpose(wvt, wv, C, Q);
    for (int b = 0; b < B; b++)
        patch_forward(out + (size_t)b * T * C, mode == NN_ATTN_JOINT ? prob + b * H * TT : NULL,
                      Phi + (size_t)b * H * T * Q, qkv + (size_t)b * T * 3 * C, phi + b * TT * Q,
                      phit + b * TT * Q, wb, wvt, T, C, H, mode, scratch);
}

void pairattn_backward(float *dqkv, float *dwb, float *dwv, const float *dout, const float *qkv,
                       const float *prob, const float *Phi, const float *phi, const float *phit,
                       const float *wv, int B, int T, int C, int H, nn_attn_mode mode,
                       float *scratch)
{
    const size_t TT = (size_t)T * T;
    for (int b = 0; b < B; b++)
        patch_backward(dqkv + (size_t)b * T * 3 * C, dwb, dwv, dout + (size_t)b * T * C,
                       qkv + (size_t)b * T * 3 * C, mode == NN_ATTN_JOINT ? prob + b * H * TT : NULL,
                       Phi + (size_t)b * H * T * Q, phi + b * TT * Q, phit + b * TT * Q, wv, T, C, H,
                       mode, scratch);
}

/* ---- fused into the neighbouring products (as nn.c's attention) ------------------- */
typedef struct {
    float *out, *prob, *Phi, *dwb, *dwv;
    const float *qkv, *dout, *cprob, *cPhi, *phi, *phit, *wb, *wv;
    int T, C, H, next;
    nn_attn_mode mode;
    float *scratch;
} pair_ctx;

static void epi_forward(void *p, int i0, int rows)
{
    pair_ctx *a = p;
    const size_t T = a->T, C = a->C, H = a->H, TT = T * T;
    for (int done = (i0 + rows) / a->T; a->next < done; a->next++) {
        size_t b = a->next;
        patch_forward(a->out + b * T * C, a->mode == NN_ATTN_JOINT ? a->prob + b * H * TT : NULL,
                      a->Phi + b * H * T * Q, a->qkv + b * T * 3 * C, a->phi + b * TT * Q,
                      a->phit + b * TT * Q, a->wb, a->wv, a->T, a->C, a->H, a->mode, a->scratch);
    }
}

static void epi_backward(void *p, int i0, int rows)
{
    pair_ctx *a = p;
    const size_t T = a->T, C = a->C, H = a->H, TT = T * T;
    for (int done = (i0 + rows) / a->T; a->next < done; a->next++) {
        size_t b = a->next;
        patch_backward(a->out + b * T * 3 * C, a->dwb, a->dwv, a->dout + b * T * C,
                       a->qkv + b * T * 3 * C, a->mode == NN_ATTN_JOINT ? a->cprob + b * H * TT : NULL,
                       a->cPhi + b * H * T * Q, a->phi + b * TT * Q, a->phit + b * TT * Q, a->wv,
                       a->T, a->C, a->H, a->mode, a->scratch);
    }
}

void pairattn_linear_forward(float *qkv, float *out, float *prob, float *Phi, const float *in,
                             const float *w, const float *b, const float *phi, const float *phit,
                             const float *wb, const float *wvt, int B, int T, int C, int H,
                             nn_attn_mode mode, float *wt, float *scratch)
{
    const int M = B * T, N = 3 * C;
    pair_ctx a = {.out = out, .prob = prob, .Phi = Phi, .qkv = qkv, .phi = phi, .phit = phit,
                  .wb = wb, .wv = wvt, .T = T, .C = C, .H = H, .mode = mode, .scratch = scratch};
    if (w) gemm_transpose(wt, w, N, C);
    if (mode == NN_ATTN_SELF) /* self-only attention reads only v (nn.h) */
        gemm_fma_bias_epi(M, C, C, in, C, 1, wt + 2 * C, N, qkv + 2 * C, N, b ? b + 2 * C : NULL,
                          epi_forward, &a);
    else
        gemm_fma_bias_epi(M, N, C, in, C, 1, wt, N, qkv, N, b, epi_forward, &a);
}

void pairattn_linear_backward(float *dqkv, float *datt, float *dpw, float *dpb, float *dwb,
                              float *dwv, const float *dout, const float *att, const float *pw,
                              const float *qkv, const float *prob, const float *Phi,
                              const float *phi, const float *phit, const float *wv, int B, int T,
                              int C, int H, nn_attn_mode mode, float *scratch)
{
    const int M = B * T;
    pair_ctx a = {.out = dqkv, .dwb = dwb, .dwv = dwv, .qkv = qkv, .dout = datt, .cprob = prob,
                  .cPhi = Phi, .phi = phi, .phit = phit, .wv = wv, .T = T, .C = C, .H = H,
                  .mode = mode, .scratch = scratch};
    /* datt = dout pw with the pair backward on each finished patch, then the
     * projection's own gradients: the calls of nn_linear_backward */
    gemm_fma_epi(M, C, C, dout, C, 1, pw, C, datt, C, 0, epi_backward, &a);
    nn_linear_backward(NULL, dpw, dpb, dout, att, pw, M, C, C);
}
