/* adamw: see adamw.h. Bias corrections are computed once per step in double;
 * the per-parameter loop is float and allocation-free, vectorised on AVX2 and
 * AVX-512 (the gemm path's width, gemm.h) with results identical to the
 * scalar loop (tested). */
#include "adamw.h"
#include "gemm.h"
#include <math.h>

adamw_hp adamw_defaults(void)
{
    adamw_hp h = {0.9, 0.999, 1e-8, 0.01};
    return h;
}

/* The reference loop; the AVX2 form below computes the same expressions
 * lane by lane (separate multiplies and adds, IEEE sqrt and division), so the
 * results are identical. */
static void update_scalar(float *restrict p, const float *restrict g, float *restrict m,
                          float *restrict v, size_t lo, size_t hi, float b1, float b2,
                          float a, float cv, float eps, float keep)
{
    const float c1 = 1.f - b1, c2 = 1.f - b2;
    for (size_t i = lo; i < hi; i++) {
        float gi = g[i];
        float mi = b1 * m[i] + c1 * gi;
        float vi = b2 * v[i] + c2 * (gi * gi);
        m[i] = mi;
        v[i] = vi;
        p[i] = p[i] * keep - a * mi / (sqrtf(vi * cv) + eps);
    }
}

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#define ADAMW_AVX2 1
/* The scalar loop does not vectorise (sqrtf may set errno) and its sqrt and
 * division chain made the update about 2% of a training step. */
__attribute__((target("avx2"))) static size_t update_avx2(float *restrict p, const float *restrict g,
                                                          float *restrict m, float *restrict v,
                                                          size_t lo, size_t hi, float b1, float b2,
                                                          float a, float cv, float eps, float keep)
{
    const __m256 vb1 = _mm256_set1_ps(b1), vb2 = _mm256_set1_ps(b2), vc1 = _mm256_set1_ps(1.f - b1);
    const __m256 vc2 = _mm256_set1_ps(1.f - b2), va = _mm256_set1_ps(a), vcv = _mm256_set1_ps(cv);
    const __m256 veps = _mm256_set1_ps(eps), vkeep = _mm256_set1_ps(keep);
    size_t i = lo;
    for (; i + 8 <= hi; i += 8) {
        __m256 gi = _mm256_loadu_ps(g + i);
        __m256 mi = _mm256_add_ps(_mm256_mul_ps(vb1, _mm256_loadu_ps(m + i)), _mm256_mul_ps(vc1, gi));
        __m256 vi = _mm256_add_ps(_mm256_mul_ps(vb2, _mm256_loadu_ps(v + i)),
                                  _mm256_mul_ps(vc2, _mm256_mul_ps(gi, gi)));
        _mm256_storeu_ps(m + i, mi);
        _mm256_storeu_ps(v + i, vi);
        __m256 den = _mm256_add_ps(_mm256_sqrt_ps(_mm256_mul_ps(vi, vcv)), veps);
        __m256 step = _mm256_div_ps(_mm256_mul_ps(va, mi), den);
        _mm256_storeu_ps(p + i, _mm256_sub_ps(_mm256_mul_ps(_mm256_loadu_ps(p + i), vkeep), step));
    }
    return i;
}

/* The same on 16 lanes, taken on the AVX-512 gemm path: every lane the
 * scalar loop's operations (IEEE multiply, add, sqrt and division round
 * lane by lane, as in the 8-lane form). */
__attribute__((target("avx512f"))) static size_t update_avx512(float *restrict p, const float *restrict g,
                                                              float *restrict m, float *restrict v,
                                                              size_t lo, size_t hi, float b1, float b2,
                                                              float a, float cv, float eps, float keep)
{
    const __m512 vb1 = _mm512_set1_ps(b1), vb2 = _mm512_set1_ps(b2), vc1 = _mm512_set1_ps(1.f - b1);
    const __m512 vc2 = _mm512_set1_ps(1.f - b2), va = _mm512_set1_ps(a), vcv = _mm512_set1_ps(cv);
    const __m512 veps = _mm512_set1_ps(eps), vkeep = _mm512_set1_ps(keep);
    size_t i = lo;
    for (; i + 16 <= hi; i += 16) {
        __m512 gi = _mm512_loadu_ps(g + i);
        __m512 mi = _mm512_add_ps(_mm512_mul_ps(vb1, _mm512_loadu_ps(m + i)), _mm512_mul_ps(vc1, gi));
        __m512 vi = _mm512_add_ps(_mm512_mul_ps(vb2, _mm512_loadu_ps(v + i)),
                                  _mm512_mul_ps(vc2, _mm512_mul_ps(gi, gi)));
        _mm512_storeu_ps(m + i, mi);
        _mm512_storeu_ps(v + i, vi);
        __m512 den = _mm512_add_ps(_mm512_sqrt_ps(_mm512_mul_ps(vi, vcv)), veps);
        __m512 step = _mm512_div_ps(_mm512_mul_ps(va, mi), den);
        _mm512_storeu_ps(p + i, _mm512_sub_ps(_mm512_mul_ps(_mm512_loadu_ps(p + i), vkeep), step));
    }
    return i;
}
#endif

static void update_range(float *restrict p, const float *restrict g, float *restrict m,
                         float *restrict v, size_t lo, size_t hi, float b1, float b2,
                         float a, float cv, float eps, float keep)
{
#ifdef ADAMW_AVX2
    const gemm_isa isa = gemm_get_isa(); /* the path in use, so each path can be tested and timed */
    if (isa == GEMM_AVX512) lo = update_avx512(p, g, m, v, lo, hi, b1, b2, a, cv, eps, keep);
    if (isa >= GEMM_AVX2) lo = update_avx2(p, g, m, v, lo, hi, b1, b2, a, cv, eps, keep);
#endif
    update_scalar(p, g, m, v, lo, hi, b1, b2, a, cv, eps, keep);
}

void adamw_update(float *p, const float *g, float *m, float *v, size_t n, size_t ndecay,
                  long t, double lr, const adamw_hp *hp)
{
    double bc1 = 1.0 - pow(hp->beta1, (double)t), bc2 = 1.0 - pow(hp->beta2, (double)t);
    float a = (float)(lr / bc1), cv = (float)(1.0 / bc2);
    float keep = (float)(1.0 - lr * hp->wd);
    if (ndecay > n) ndecay = n;
    update_range(p, g, m, v, 0, ndecay, (float)hp->beta1, (float)hp->beta2, a, cv, (float)hp->eps, keep);
    update_range(p, g, m, v, ndecay, n, (float)hp->beta1, (float)hp->beta2, a, cv, (float)hp->eps, 1.f);
}
