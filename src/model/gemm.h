/* gemm: the one matrix product of the model (design.md §8, §10; paper §4.2).
 *
 *   C[i][j] = (accumulate ? C[i][j] : 0) + sum_k A(i, k) * B[k][j],
 *   A(i, k) = A[i * ars + k * aks]   (so A or A^T, any leading dimension),
 *   B row-major with leading dimension ldb, C row-major with ldc.
 *
 * Why not cblas_sgemm: OpenBLAS picks its kernel per CPU at load time, so the
 * same training run gives different bits on different machines, and at the
 * model's shapes (K or N of 16..256) its operand packing and C scaling took
 * about 15% of a training step's profile on the reference machine. Here every C element is ONE chain of fused
 * multiply-adds over k in ascending order, whatever the ISA: the AVX-512, AVX2+FMA and scalar (fmaf) paths give
 * bit-identical results (tested), so a training run does not depend on the CPU's vector extensions. The vector paths
 * keep a 6-row x (up to) 64-column tile of C in registers and stream B rows. Limits: float only; no threads; A, B and C
 * must not overlap. */
#ifndef GEMM_H
#define GEMM_H
#include <stddef.h>

/* Called once per finished strip of C rows [i0, i0 + rows), strips in
 * ascending order, all of them GEMM_STRIP rows except the last; every path
 * uses the same strips, so an epilogue's results do not depend on the ISA.
 * 12 rows: the layer norm epilogue takes its rows in fours (nn.c). */
typedef void (*gemm_epilogue)(void *ctx, int i0, int rows);
enum { GEMM_STRIP = 12 };

typedef enum { GEMM_AUTO = 0, GEMM_SCALAR = 1, GEMM_AVX2 = 2, GEMM_AVX512 = 3 } gemm_isa;

void gemm_fma(int M, int N, int K, const float *A, ptrdiff_t ars, ptrdiff_t aks,
              const float *B, ptrdiff_t ldb, float *C, ptrdiff_t ldc, int accumulate);
/* gemm_fma, then epi(ctx, ...) on each strip of finished rows (fusing an
 * element-wise pass into the product while its rows are in cache). */
void gemm_fma_epi(int M, int N, int K, const float *A, ptrdiff_t ars, ptrdiff_t aks,
                  const float *B, ptrdiff_t ldb, float *C, ptrdiff_t ldc, int accumulate,
                  gemm_epilogue epi, void *ctx);
/* C = bias + A B: each chain starts from bias[j] instead of +0 (the bits of
 * copying bias into every row of C and accumulating, without the copy). */
void gemm_fma_bias_epi(int M, int N, int K, const float *A, ptrdiff_t ars, ptrdiff_t aks,
                       const float *B, ptrdiff_t ldb, float *C, ptrdiff_t ldc, const float *bias,
                       gemm_epilogue epi, void *ctx);
/* H products side by side, sharing the rows of B and C (the heads of
 * multi-head attention): for h < H,
 *   C[i][h*n + j] = sum_k A[h*ahs + i*ars + k*aks] * B[k][h*n + j],
 * overwriting C; each element one fma chain over k ascending, so the values
 * equal H separate gemm_fma calls on any path. (The training runs' shape,
 * T = 24 and hd = 16 on AVX-512, has its own kernel in nn.c.) */
void gemm_fma_heads(int H, int M, int n, int K, const float *A, ptrdiff_t ahs, ptrdiff_t ars,
                    ptrdiff_t aks, const float *B, ptrdiff_t ldb, float *C, ptrdiff_t ldc);
/* The same with a chosen path; an unavailable path falls back to the best
 * available one below it (tests compare paths bit for bit). bias (may be
 * NULL) is used when accumulate is 0. */
void gemm_fma_isa(gemm_isa isa, int M, int N, int K, const float *A, ptrdiff_t ars,
                  ptrdiff_t aks, const float *B, ptrdiff_t ldb, float *C, ptrdiff_t ldc,
                  int accumulate, const float *bias, gemm_epilogue epi, void *ctx);
/* Make gemm_fma use `isa` (or the best available below it) from now on, and
 * the layer kernels follow it (gemm_get_isa); returns the path used before.
 * For tests that run a whole model on each path, and for benchmarks
 * (`crownshy bench-model --path`); results do not depend on it. */
gemm_isa gemm_set_isa(gemm_isa isa);
/* 1 when this CPU can run the path. */
int gemm_isa_available(gemm_isa isa);
/* The path in use (gemm_set_isa, or the best this CPU has). The layer kernels
 * of nn.c take their AVX-512 forms only when it is GEMM_AVX512, so a whole
 * model can be run, tested and timed on each path. */
gemm_isa gemm_get_isa(void);
/* The core's fused multiply-add peak at the path's vector width (AVX-512:
 * 512-bit, AVX2: 256-bit, scalar: fmaf) in GFLOP/s: 12-16 independent chains of
 * `iters` fmas per lane, no loads or stores, timed in the calling thread's CPU
 * time (the yardstick of `make bench`,
 * design.md §10). An unavailable path falls back as gemm_fma_isa does. */
double gemm_peak_gflops(gemm_isa isa, long iters);
/* The path gemm_fma takes: "avx512", "avx2" or "scalar". */
const char *gemm_isa_name(void);
/* dst[K x N] = src[N x K]^T (weights stored [out x in] to a B operand). */
void gemm_transpose(float *dst, const float *src, int N, int K);
/* dst[k * ldd + n] = s * src[n * lds + k] for n < N, k < K (strided rows,
 * e.g. one attention head's keys inside qkv). */
void gemm_transpose_scaled(float *dst, ptrdiff_t ldd, const float *src, ptrdiff_t lds, int N, int K,
                           float s);

#endif
