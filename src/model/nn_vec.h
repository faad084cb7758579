/* nn_vec: the vector helpers the layer kernels share (nn.c, nn_attn.c):
 * 8-lane GCC vector types, fixed-order reductions, the polynomial exp, and
 * (where the compiler can build AVX-512 code) their 16-lane forms. Internal
 * to the model stage: every helper is static inline and always inlined, so
 * the kernels of both files execute the same lane-wise IEEE operations in
 * the same order. Also declares the two linear-layer cores both files use. */
#ifndef NN_VEC_H
#define NN_VEC_H
#include "gemm.h"
#include <stddef.h>
#include <string.h>

/* The vector helpers are always inlined, so no vector crosses a call boundary. */
#pragma GCC diagnostic ignored "-Wpsabi"

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(NN_NO_CLONES)
#define HOT __attribute__((target_clones("avx2", "default")))
#else
#define HOT
#endif
#define INL static inline __attribute__((always_inline))
/* AVX-512 forms of the GELU and of attention at the reference head shape,
 * taken at run time on the AVX-512 gemm path, and an AVX2 form of that
 * attention taken on the AVX2 path (gemm_get_isa; both absent from the
 * baseline copy that test_nn_clones compares them with). */
#if defined(__x86_64__) && defined(__GNUC__) && !defined(NN_NO_CLONES)
#define NN_AVX512 1
#define NN_AVX2 1
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
 * ((x0+x4)+(x2+x6)) + ((x1+x5)+(x3+x7)) over lanes x0..x7. One fixed order everywhere. */
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

/* db[0..n) += rows r < M of x (row stride ldx), row after row: each db[c]
 * is one chain of additions over r in order. Blocks of 8 vectors of columns
 * keep their chains in registers over all rows (the same additions as
 * adding row after row into db). */
INL void colsum_block(float *restrict db, const float *restrict x, ptrdiff_t ldx, int M, int n)
{
    int c = 0;
    for (; c + 8 * VL <= n; c += 8 * VL) {
        vf a[8];
        _Pragma("GCC unroll 8") for (int q = 0; q < 8; q++) a[q] = ld(db + c + q * VL);
        for (int r = 0; r < M; r++) {
            const float *xr = x + (size_t)r * ldx + c;
            _Pragma("GCC unroll 8") for (int q = 0; q < 8; q++) a[q] += ld(xr + q * VL);
        }
        _Pragma("GCC unroll 8") for (int q = 0; q < 8; q++) st(db + c + q * VL, a[q]);
    }
    for (; c + VL <= n; c += VL) {
        vf a = ld(db + c);
        for (int r = 0; r < M; r++) a += ld(x + (size_t)r * ldx + c);
        st(db + c, a);
    }
    for (; c < n; c++) {
        float a = db[c];
        for (int r = 0; r < M; r++) a += x[(size_t)r * ldx + c];
        db[c] = a;
    }
}

#ifdef NN_AVX512
typedef float vf16 __attribute__((vector_size(64)));
typedef int vi16 __attribute__((vector_size(64)));
INL vf16 ld16(const float *p) { vf16 v; memcpy(&v, p, sizeof v); return v; }
INL void st16(float *p, vf16 v) { memcpy(p, &v, sizeof v); }
INL vf16 splat16(float a) { vf16 z = {0}; return z + a; }
DEF_VEXP(vexp16, vf16, vi16, splat16)
#endif


/* ---- the softmax of rows of 24 on intrinsics (nn_attn.c) ------------------ */
/* The operations of vmaxv and vexp / vexp16 in their order, lane by lane,
 * with three steps as single instructions of the same results: vmax(a, b)
 * = a > b ? a : b is x86 max(a, b); the exponential's clamps x < lo ? lo : x
 * and x > hi ? hi : x are max(lo, x) and min(hi, x) (operands in that
 * order: a NaN passes through as before); and on AVX-512 p * 2^kn, 2^kn
 * built from exponent bits, is scalef(p, kn) (kn is an integer in
 * [-126, 127] after the clamps: the same normal power of two, the same
 * rounded product). Several vectors go through each step before the next,
 * so that their long dependency chains overlap (test_nn_clones compares
 * the attention with the baseline build, clamped scores included). */
#if defined(NN_AVX512) || defined(NN_AVX2)
#include <immintrin.h>
#define EXP_CONSTS(SET1) \
    const __typeof__(SET1(0.f)) e_lo = SET1(-87.0f), e_hi = SET1(88.0f), e_l2e = SET1(1.44269504088896341f), \
        e_sh = SET1(12582912.0f), e_hi2 = SET1(0.693145751953125f), e_lo2 = SET1(1.428606765330187e-06f)
/* v[k] = exp(v[k]) for k < NV, statement by statement; kn[k] and r[k] scratch.
 * POW2(p, kn) is p * 2^kn. */
#define EXP_STAGES(V, NV, MUL, ADD, SUB, SET1, MAX, MIN, POW2)                                                         \
    do {                                                                                                               \
        __typeof__(V[0]) kn_[NV], r_[NV];                                                                              \
        _Pragma("GCC unroll 12") for (int k = 0; k < NV; k++) V[k] = MIN(e_hi, MAX(e_lo, V[k]));                       \
        _Pragma("GCC unroll 12") for (int k = 0; k < NV; k++) kn_[k] = SUB(ADD(MUL(V[k], e_l2e), e_sh), e_sh);         \
        _Pragma("GCC unroll 12") for (int k = 0; k < NV; k++) r_[k] = SUB(V[k], MUL(kn_[k], e_hi2));                   \
        _Pragma("GCC unroll 12") for (int k = 0; k < NV; k++) r_[k] = SUB(r_[k], MUL(kn_[k], e_lo2));                  \
        _Pragma("GCC unroll 12") for (int k = 0; k < NV; k++) V[k] =                                                   \
            ADD(MUL(SET1(1.f / 5040.f), r_[k]), SET1(1.f / 720.f));                                                    \
        _Pragma("GCC unroll 12") for (int k = 0; k < NV; k++) V[k] = ADD(MUL(V[k], r_[k]), SET1(1.f / 120.f));         \
        _Pragma("GCC unroll 12") for (int k = 0; k < NV; k++) V[k] = ADD(MUL(V[k], r_[k]), SET1(1.f / 24.f));          \
        _Pragma("GCC unroll 12") for (int k = 0; k < NV; k++) V[k] = ADD(MUL(V[k], r_[k]), SET1(1.f / 6.f));           \
        _Pragma("GCC unroll 12") for (int k = 0; k < NV; k++) V[k] = ADD(MUL(V[k], r_[k]), SET1(0.5f));                \
        _Pragma("GCC unroll 12") for (int k = 0; k < NV; k++) V[k] = ADD(MUL(V[k], r_[k]), SET1(1.f));                 \
        _Pragma("GCC unroll 12") for (int k = 0; k < NV; k++) V[k] = ADD(MUL(V[k], r_[k]), SET1(1.f));                 \
        _Pragma("GCC unroll 12") for (int k = 0; k < NV; k++) V[k] = POW2(V[k], kn_[k]);                               \
    } while (0)

/* vmaxv(x, 24): max over the three 8-lane chunks, then the butterfly */
__attribute__((target("avx2"), always_inline)) static inline float max24_avx(const float *x)
{
    __m256 m = _mm256_max_ps(_mm256_loadu_ps(x), _mm256_loadu_ps(x + 8));
    m = _mm256_max_ps(m, _mm256_loadu_ps(x + 16));
    m = _mm256_max_ps(m, _mm256_permute2f128_ps(m, m, 1)); /* SWAP4 */
    m = _mm256_max_ps(m, _mm256_permute_ps(m, 0x4E));      /* SWAP2 */
    m = _mm256_max_ps(m, _mm256_permute_ps(m, 0xB1));      /* SWAP1 */
    return _mm256_cvtss_f32(m);
}

__attribute__((target("avx2"), always_inline)) static inline __m256 pow2_avx2(__m256 p, __m256 kn)
{
    const __m256i n = _mm256_slli_epi32(_mm256_add_epi32(_mm256_cvttps_epi32(kn), _mm256_set1_epi32(127)), 23);
    return _mm256_mul_ps(p, _mm256_castsi256_ps(n));
}

/* s[i][j] = exp(s[i][j] - mx[i]) for 2 rows of 24 at row i (6 vectors; the
 * subtrahend splat(mx) as vexp's caller forms it: 0 + mx) */
__attribute__((target("avx2"), always_inline)) static inline void exp_rows2_avx2(float *s, const float *mx, int i)
{
    EXP_CONSTS(_mm256_set1_ps);
    __m256 v[6];
    _Pragma("GCC unroll 6") for (int k = 0; k < 6; k++)
        v[k] = _mm256_sub_ps(_mm256_loadu_ps(s + (i + k / 3) * 24 + 8 * (k % 3)), _mm256_set1_ps(0.f + mx[i + k / 3]));
    EXP_STAGES(v, 6, _mm256_mul_ps, _mm256_add_ps, _mm256_sub_ps, _mm256_set1_ps, _mm256_max_ps, _mm256_min_ps,
               pow2_avx2);
    _Pragma("GCC unroll 6") for (int k = 0; k < 6; k++) _mm256_storeu_ps(s + (i + k / 3) * 24 + 8 * (k % 3), v[k]);
}
#endif
#ifdef NN_AVX512
/* 4 rows of 24 at row i on 6 16-lane vectors: each row's lanes 0-15, and the
 * lanes 16-23 of two rows side by side in one vector (lane-wise operations:
 * where a value sits does not change it) */
__attribute__((target("avx512f"), always_inline)) static inline void exp_rows4_avx512(float *s, const float *mx, int i)
{
    EXP_CONSTS(_mm512_set1_ps);
    __m512 v[6];
    _Pragma("GCC unroll 2") for (int u = 0; u < 2; u++) {
        float *a = s + (i + 2 * u) * 24, *b = a + 24;
        const float ma = 0.f + mx[i + 2 * u], mb = 0.f + mx[i + 2 * u + 1];
        v[3 * u] = _mm512_sub_ps(_mm512_loadu_ps(a), _mm512_set1_ps(ma));
        v[3 * u + 1] = _mm512_sub_ps(_mm512_loadu_ps(b), _mm512_set1_ps(mb));
        const __m256 ta = _mm256_sub_ps(_mm256_loadu_ps(a + 16), _mm256_set1_ps(ma));
        const __m256 tb = _mm256_sub_ps(_mm256_loadu_ps(b + 16), _mm256_set1_ps(mb));
        v[3 * u + 2] =
            _mm512_castpd_ps(_mm512_insertf64x4(_mm512_castpd256_pd512(_mm256_castps_pd(ta)), _mm256_castps_pd(tb), 1));
    }
    EXP_STAGES(v, 6, _mm512_mul_ps, _mm512_add_ps, _mm512_sub_ps, _mm512_set1_ps, _mm512_max_ps, _mm512_min_ps,
               _mm512_scalef_ps);
    _Pragma("GCC unroll 2") for (int u = 0; u < 2; u++) {
        float *a = s + (i + 2 * u) * 24, *b = a + 24;
        _mm512_storeu_ps(a, v[3 * u]);
        _mm512_storeu_ps(b, v[3 * u + 1]);
        _mm256_storeu_ps(a + 16, _mm512_castps512_ps256(v[3 * u + 2]));
        _mm256_storeu_ps(b + 16, _mm256_castpd_ps(_mm512_extractf64x4_pd(_mm512_castps_pd(v[3 * u + 2]), 1)));
    }
}
#endif

#endif
