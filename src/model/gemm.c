/* gemm: fused multiply-add matrix product with ISA-independent results (see
 * gemm.h; design.md §8, §10). The vector paths are the tile template in
 * gemm_tile.inc, instantiated for AVX-512F (16 lanes, tile 6 x 64) and
 * AVX2+FMA (8 lanes, tile 6 x 16: 12 accumulators fit 16 registers). */
#include "gemm.h"
#include <math.h>
#include <string.h>

enum { GEMM_KC = 256 }; /* k-chunk of a long product without epilogue (see run) */
/* Rows of a register tile, and of a super-strip (gemm_tile.inc): one
 * epilogue strip, 2 tiles; 1, 2, 4 and 8 tiles measured alike or slower. */
enum { GEMM_TILE = 6, GEMM_SUPER = GEMM_STRIP };

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define GEMM_X86 1
#include <immintrin.h>
#endif

/* The reference order: one fma chain per element, k ascending. */
static void path_scalar(int M, int N, int K, const float *A, ptrdiff_t ars, ptrdiff_t aks,
                        const float *B, ptrdiff_t ldb, float *C, ptrdiff_t ldc, int acc,
                        const float *bias, gemm_epilogue epi, void *ctx)
{
    for (int i0 = 0; i0 < M; i0 += GEMM_STRIP) {
        int R = M - i0 < GEMM_STRIP ? M - i0 : GEMM_STRIP;
        for (int i = i0; i < i0 + R; i++)
            for (int j = 0; j < N; j++) {
                float c = acc ? C[(ptrdiff_t)i * ldc + j] : bias ? bias[j] : 0.f;
                for (int k = 0; k < K; k++)
                    c = fmaf(A[(ptrdiff_t)i * ars + (ptrdiff_t)k * aks], B[(ptrdiff_t)k * ldb + j], c);
                C[(ptrdiff_t)i * ldc + j] = c;
            }
        if (epi) epi(ctx, i0, R);
    }
}

#ifdef GEMM_X86
/* ---- AVX-512F ---- */
#define GT_ATTR __attribute__((target("avx512f"), unused))
#define GT_NAME(x) x##_avx512
#define GT_VL 16
#define GT_NVMAX 4
#define GT_V __m512
#define GT_MASK __mmask16
#define GT_ZERO() _mm512_setzero_ps()
#define GT_LOAD(p) _mm512_loadu_ps(p)
#define GT_MLOAD(m, p) _mm512_maskz_loadu_ps((m), (p))
#define GT_STORE(p, v) _mm512_storeu_ps((p), (v))
#define GT_MSTORE(m, p, v) _mm512_mask_storeu_ps((p), (m), (v))
#define GT_FMA(a, b, c) _mm512_fmadd_ps((a), (b), (c))
#define GT_SET1(x) _mm512_set1_ps(x)
#define GT_MKMASK(n) ((n) >= 16 ? (__mmask16)0xFFFF : (n) <= 0 ? (__mmask16)0 : (__mmask16)((1u << (n)) - 1u))
#include "gemm_tile.inc"
#undef GT_ATTR
#undef GT_NAME
#undef GT_VL
#undef GT_NVMAX
#undef GT_V
#undef GT_MASK
#undef GT_ZERO
#undef GT_LOAD
#undef GT_MLOAD
#undef GT_STORE
#undef GT_MSTORE
#undef GT_FMA
#undef GT_SET1
#undef GT_MKMASK

/* ---- AVX2 + FMA ---- */
__attribute__((target("avx2"))) static inline __m256i mask8(int n)
{
    return _mm256_cmpgt_epi32(_mm256_set1_epi32(n), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
}
#define GT_ATTR __attribute__((target("avx2,fma"), unused))
#define GT_NAME(x) x##_avx2
#define GT_VL 8
#define GT_NVMAX 2
#define GT_V __m256
#define GT_MASK __m256i
#define GT_ZERO() _mm256_setzero_ps()
#define GT_LOAD(p) _mm256_loadu_ps(p)
#define GT_MLOAD(m, p) _mm256_maskload_ps((p), (m))
#define GT_STORE(p, v) _mm256_storeu_ps((p), (v))
#define GT_MSTORE(m, p, v) _mm256_maskstore_ps((p), (m), (v))
#define GT_FMA(a, b, c) _mm256_fmadd_ps((a), (b), (c))
#define GT_SET1(x) _mm256_set1_ps(x)
#define GT_MKMASK(n) mask8(n)
#include "gemm_tile.inc"
#endif


int gemm_isa_available(gemm_isa isa)
{
#ifdef GEMM_X86
    /* asked once per call of the fused GELU and of every gemm_fma_isa: read
     * the CPU once per process */
    static int avx2 = -1, avx512 = -1;
    if (avx2 < 0) {
        __builtin_cpu_init();
        avx512 = __builtin_cpu_supports("avx512f") ? 1 : 0;
        avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    }
#endif
    switch (isa) {
    case GEMM_AUTO:
    case GEMM_SCALAR: return 1;
#ifdef GEMM_X86
    case GEMM_AVX2: return avx2;
    case GEMM_AVX512: return avx512;
#endif
    default: return 0;
    }
}

static gemm_isa best(gemm_isa want)
{
    if (want == GEMM_AUTO) want = GEMM_AVX512;
    while (want > GEMM_SCALAR && !gemm_isa_available(want)) want = (gemm_isa)(want - 1);
    return want;
}


typedef void (*path_fn)(int, int, int, const float *, ptrdiff_t, ptrdiff_t, const float *,
                        ptrdiff_t, float *, ptrdiff_t, int, const float *, gemm_epilogue, void *);

static path_fn path_of(gemm_isa isa)
{
    switch (best(isa)) {
#ifdef GEMM_X86
    case GEMM_AVX512: return path_avx512;
    case GEMM_AVX2: return path_avx2;
#endif
    default: return path_scalar;
    }
}

static void run(path_fn f, int M, int N, int K, const float *A, ptrdiff_t ars, ptrdiff_t aks,
                const float *B, ptrdiff_t ldb, float *C, ptrdiff_t ldc, int acc,
                const float *bias, gemm_epilogue epi, void *ctx)
{
    if (M <= 0 || N <= 0) return;
    if (acc) bias = NULL;
    if (K <= 0) { /* no products: C is kept, the bias or 0; the epilogue still runs */
        for (int i0 = 0; i0 < M; i0 += GEMM_STRIP) {
            int R = M - i0 < GEMM_STRIP ? M - i0 : GEMM_STRIP;
            for (int i = i0; i < i0 + R && !acc; i++) {
                if (bias) memcpy(C + (ptrdiff_t)i * ldc, bias, sizeof(float) * N);
                else memset(C + (ptrdiff_t)i * ldc, 0, sizeof(float) * N);
            }
            if (epi) epi(ctx, i0, R);
        }
        return;
    }
    if (epi || K <= GEMM_KC) {
        f(M, N, K, A, ars, aks, B, ldb, C, ldc, acc, bias, epi, ctx);
        return;
    }
    /* Long sums (the weight gradients: K = all tokens of the batch) go in
     * chunks of GEMM_KC rows of B, so that a chunk stays in L2 while every
     * strip of C passes over it. C is stored and reloaded between chunks,
     * which is exact: each element is still one fma chain in k order. */
    for (int k0 = 0; k0 < K; k0 += GEMM_KC) {
        int kc = K - k0 < GEMM_KC ? K - k0 : GEMM_KC;
        f(M, N, kc, A + (ptrdiff_t)k0 * aks, ars, aks, B + (ptrdiff_t)k0 * ldb, ldb, C, ldc,
          acc || k0 > 0, k0 > 0 ? NULL : bias, NULL, NULL);
    }
}

void gemm_fma_isa(gemm_isa isa, int M, int N, int K, const float *A, ptrdiff_t ars,
                  ptrdiff_t aks, const float *B, ptrdiff_t ldb, float *C, ptrdiff_t ldc,
                  int accumulate, const float *bias, gemm_epilogue epi, void *ctx)
{
    run(path_of(isa), M, N, K, A, ars, aks, B, ldb, C, ldc, accumulate, bias, epi, ctx);
}

/* The path is resolved once per process (the CPU does not change under it),
 * or set by gemm_set_isa. */
static path_fn auto_path;
static gemm_isa auto_isa = GEMM_AUTO;

gemm_isa gemm_set_isa(gemm_isa isa)
{
    gemm_isa old = auto_isa == GEMM_AUTO ? best(GEMM_AUTO) : auto_isa;
    auto_isa = best(isa);
    auto_path = path_of(auto_isa);
    return old;
}

gemm_isa gemm_get_isa(void) { return auto_isa == GEMM_AUTO ? best(GEMM_AUTO) : auto_isa; }

const char *gemm_isa_name(void)
{
    static const char *names[] = {"auto", "scalar", "avx2", "avx512"};
    return names[auto_isa == GEMM_AUTO ? best(GEMM_AUTO) : auto_isa];
}

void gemm_fma_epi(int M, int N, int K, const float *A, ptrdiff_t ars, ptrdiff_t aks,
                  const float *B, ptrdiff_t ldb, float *C, ptrdiff_t ldc, int accumulate,
                  gemm_epilogue epi, void *ctx)
{
    if (!auto_path) auto_path = path_of(GEMM_AUTO);
    run(auto_path, M, N, K, A, ars, aks, B, ldb, C, ldc, accumulate, NULL, epi, ctx);
}

void gemm_fma_bias_epi(int M, int N, int K, const float *A, ptrdiff_t ars, ptrdiff_t aks,
                       const float *B, ptrdiff_t ldb, float *C, ptrdiff_t ldc, const float *bias,
                       gemm_epilogue epi, void *ctx)
{
    if (!auto_path) auto_path = path_of(GEMM_AUTO);
    run(auto_path, M, N, K, A, ars, aks, B, ldb, C, ldc, 0, bias, epi, ctx);
}

void gemm_fma_heads(int H, int M, int n, int K, const float *A, ptrdiff_t ahs, ptrdiff_t ars,
                    ptrdiff_t aks, const float *B, ptrdiff_t ldb, float *C, ptrdiff_t ldc)
{
    if (!auto_path) auto_path = path_of(GEMM_AUTO);
    for (int h = 0; h < H; h++)
        run(auto_path, M, n, K, A + (ptrdiff_t)h * ahs, ars, aks, B + (ptrdiff_t)h * n, ldb,
            C + (ptrdiff_t)h * n, ldc, 0, NULL, NULL, NULL);
}

void gemm_fma(int M, int N, int K, const float *A, ptrdiff_t ars, ptrdiff_t aks,
              const float *B, ptrdiff_t ldb, float *C, ptrdiff_t ldc, int accumulate)
{
    gemm_fma_epi(M, N, K, A, ars, aks, B, ldb, C, ldc, accumulate, NULL, NULL);
}

/* ---- the FMA peak (gemm_peak_gflops) ---- */
#include <time.h>
static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

/* NC chains a = a * x + y (x just below 1, so nothing overflows or goes
 * subnormal): enough independent chains to cover the fma latency on every
 * fma port, few enough to stay in registers with x and y (16 of the 32 zmm
 * registers, 12 of the 16 ymm ones); the compiler cannot fold them. */
#define PEAK_BODY(V, NC, SET1, FMA, ADD, STORE, LANES)                                \
    V a[NC], x = SET1(0.999f), y = SET1(1e-3f);                                       \
    for (int i = 0; i < NC; i++) a[i] = SET1((float)i);                               \
    double t0 = now_s();                                                             \
    for (long k = 0; k < iters; k++) {                                               \
        _Pragma("GCC unroll 16") for (int i = 0; i < NC; i++) a[i] = FMA(a[i], x, y); \
    }                                                                                \
    double dt = now_s() - t0;                                                        \
    for (int i = 1; i < NC; i++) a[0] = ADD(a[0], a[i]);                             \
    float sink[LANES];                                                               \
    STORE(sink, a[0]);                                                               \
    peak_sink += sink[0];                                                            \
    return dt > 0 ? 2.0 * NC * LANES * (double)iters / dt / 1e9 : 0;

static volatile float peak_sink;
#ifdef GEMM_X86
__attribute__((target("avx512f"))) static double peak_avx512(long iters)
{
    PEAK_BODY(__m512, 16, _mm512_set1_ps, _mm512_fmadd_ps, _mm512_add_ps, _mm512_storeu_ps, 16)
}
__attribute__((target("avx2,fma"))) static double peak_avx2(long iters)
{
    PEAK_BODY(__m256, 12, _mm256_set1_ps, _mm256_fmadd_ps, _mm256_add_ps, _mm256_storeu_ps, 8)
}
#endif
static float add1(float a, float b) { return a + b; }
static void store1(float *p, float v) { *p = v; }
static float set1(float v) { return v; }
static double peak_scalar(long iters) { PEAK_BODY(float, 8, set1, fmaf, add1, store1, 1) }

double gemm_peak_gflops(gemm_isa isa, long iters)
{
    switch (best(isa)) {
#ifdef GEMM_X86
    case GEMM_AVX512: return peak_avx512(iters);
    case GEMM_AVX2: return peak_avx2(iters);
#endif
    default: return peak_scalar(iters);
    }
}

#ifdef GEMM_X86
/* dst[8 x 8] (row stride ldd) = s * src[8 x 8]^T (row stride lds): unpack,
 * shuffle, then swap 128-bit lanes; s * x is the scalar loop's product. */
__attribute__((target("avx2"))) static inline void tr8x8(float *dst, ptrdiff_t ldd, const float *src, ptrdiff_t lds,
                                                         float s)
{
    /* unrolled by hand: as loops over arrays GCC kept r, t and u on the stack */
    const __m256 vs = _mm256_set1_ps(s);
    const __m256 row0 = _mm256_mul_ps(vs, _mm256_loadu_ps(src)), row1 = _mm256_mul_ps(vs, _mm256_loadu_ps(src + lds));
    const __m256 row2 = _mm256_mul_ps(vs, _mm256_loadu_ps(src + 2 * lds)),
                 row3 = _mm256_mul_ps(vs, _mm256_loadu_ps(src + 3 * lds));
    const __m256 row4 = _mm256_mul_ps(vs, _mm256_loadu_ps(src + 4 * lds)),
                 row5 = _mm256_mul_ps(vs, _mm256_loadu_ps(src + 5 * lds));
    const __m256 row6 = _mm256_mul_ps(vs, _mm256_loadu_ps(src + 6 * lds)),
                 row7 = _mm256_mul_ps(vs, _mm256_loadu_ps(src + 7 * lds));
    const __m256 t0 = _mm256_unpacklo_ps(row0, row1), t1 = _mm256_unpackhi_ps(row0, row1);
    const __m256 t2 = _mm256_unpacklo_ps(row2, row3), t3 = _mm256_unpackhi_ps(row2, row3);
    const __m256 t4 = _mm256_unpacklo_ps(row4, row5), t5 = _mm256_unpackhi_ps(row4, row5);
    const __m256 t6 = _mm256_unpacklo_ps(row6, row7), t7 = _mm256_unpackhi_ps(row6, row7);
    const __m256 u0 = _mm256_shuffle_ps(t0, t2, 0x44), u1 = _mm256_shuffle_ps(t0, t2, 0xEE);
    const __m256 u2 = _mm256_shuffle_ps(t1, t3, 0x44), u3 = _mm256_shuffle_ps(t1, t3, 0xEE);
    const __m256 u4 = _mm256_shuffle_ps(t4, t6, 0x44), u5 = _mm256_shuffle_ps(t4, t6, 0xEE);
    const __m256 u6 = _mm256_shuffle_ps(t5, t7, 0x44), u7 = _mm256_shuffle_ps(t5, t7, 0xEE);
    _mm256_storeu_ps(dst, _mm256_permute2f128_ps(u0, u4, 0x20));
    _mm256_storeu_ps(dst + ldd, _mm256_permute2f128_ps(u1, u5, 0x20));
    _mm256_storeu_ps(dst + 2 * ldd, _mm256_permute2f128_ps(u2, u6, 0x20));
    _mm256_storeu_ps(dst + 3 * ldd, _mm256_permute2f128_ps(u3, u7, 0x20));
    _mm256_storeu_ps(dst + 4 * ldd, _mm256_permute2f128_ps(u0, u4, 0x31));
    _mm256_storeu_ps(dst + 5 * ldd, _mm256_permute2f128_ps(u1, u5, 0x31));
    _mm256_storeu_ps(dst + 6 * ldd, _mm256_permute2f128_ps(u2, u6, 0x31));
    _mm256_storeu_ps(dst + 7 * ldd, _mm256_permute2f128_ps(u3, u7, 0x31));
}

/* The 8 x 8 blocks of gemm_transpose_scaled (n0, k0 multiples of 8). */
__attribute__((target("avx2"))) static void tr_blocks(float *dst, ptrdiff_t ldd, const float *src, ptrdiff_t lds,
                                                      int n0, int k0, float s)
{
    for (int n = 0; n < n0; n += 8)
        for (int k = 0; k < k0; k += 8) tr8x8(dst + k * ldd + n, ldd, src + n * lds + k, lds, s);
}
#endif

/* 8 x 8 blocks where the CPU has AVX2, the ragged edges one value at a time;
 * the same products either way. */
void gemm_transpose_scaled(float *dst, ptrdiff_t ldd, const float *src, ptrdiff_t lds, int N, int K,
                           float s)
{
    int n0 = 0, k0 = 0;
#ifdef GEMM_X86
    if (gemm_isa_available(GEMM_AVX2)) {
        n0 = N - N % 8;
        k0 = K - K % 8;
        tr_blocks(dst, ldd, src, lds, n0, k0, s);
    }
#endif
    /* the rest: columns k >= k0 of every row, and rows n >= n0 */
    for (int n = 0; n < N; n++)
        for (int k = n < n0 ? k0 : 0; k < K; k++) dst[k * ldd + n] = s * src[n * lds + k];
}

/* Every forward layer's weights (a copy: 1 * x is x). */
void gemm_transpose(float *dst, const float *src, int N, int K)
{
    gemm_transpose_scaled(dst, N, src, K, N, K, 1.f);
}
