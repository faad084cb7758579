/* Tests for src/model/gemm.c: every vector path this CPU has is bit-identical to the
 * scalar fma chain (the property that makes training reproducible across
 * machines), the scalar chain agrees with a double-precision product, and
 * masked column tails never write outside N. Shapes cover the 6-row and
 * 16/64-column tile edges, transposed A, and padded leading dimensions. */
#include "testutil.h"
#include "gemm.h"
#include <stdint.h>

typedef struct { int M, N, K, transA, acc; } shape;

static const shape shapes[] = {
    {1, 1, 1, 0, 0},   {7, 5, 3, 0, 1},    {13, 70, 9, 0, 0},  {6, 64, 64, 0, 1},
    {25, 130, 17, 1, 0}, {24, 24, 16, 0, 0}, {24, 16, 24, 1, 1}, {64, 36, 300, 1, 1},
    {11, 200, 5, 0, 1}, {5, 7, 40, 1, 0},   {30, 33, 2, 0, 1},  {192, 64, 96, 1, 0},
};

/* Deterministic values that do not cancel: a fixed LCG mapped to [-1, 1). */
static void fill(float *x, size_t n, uint32_t seed)
{
    for (size_t i = 0; i < n; i++) {
        seed = seed * 1664525u + 1013904223u;
        x[i] = (float)((seed >> 8) * (1.0 / 16777216.0) * 2.0 - 1.0);
    }
}

typedef struct { float *A, *B, *C0; ptrdiff_t ars, aks, ldb, ldc; } operands;

static operands make_ops(const shape *s, uint32_t seed)
{
    operands o;
    o.ldb = s->N + 3;
    o.ldc = s->N + 5;
    if (s->transA) { o.ars = 1; o.aks = s->M + 2; } else { o.ars = s->K + 1; o.aks = 1; }
    size_t na = s->transA ? (size_t)s->K * o.aks : (size_t)s->M * o.ars;
    o.A = malloc(sizeof(float) * na);
    o.B = malloc(sizeof(float) * (size_t)s->K * o.ldb);
    o.C0 = malloc(sizeof(float) * (size_t)s->M * o.ldc);
    assert_non_null(o.A); assert_non_null(o.B); assert_non_null(o.C0);
    fill(o.A, na, seed);
    fill(o.B, (size_t)s->K * o.ldb, seed + 1);
    fill(o.C0, (size_t)s->M * o.ldc, seed + 2);
    return o;
}

static void free_ops(operands *o) { free(o->A); free(o->B); free(o->C0); }

static float *run(gemm_isa isa, const shape *s, const operands *o)
{
    float *C = malloc(sizeof(float) * (size_t)s->M * o->ldc);
    assert_non_null(C);
    memcpy(C, o->C0, sizeof(float) * (size_t)s->M * o->ldc);
    gemm_fma_isa(isa, s->M, s->N, s->K, o->A, o->ars, o->aks, o->B, o->ldb, C, o->ldc, s->acc, NULL, NULL, NULL);
    return C;
}

static void check_paths_identical(gemm_isa isa)
{
    if (!gemm_isa_available(isa)) { print_message("path %d not on this CPU: skipped\n", (int)isa); return; }
    for (size_t t = 0; t < sizeof shapes / sizeof *shapes; t++) {
        const shape *s = &shapes[t];
        operands o = make_ops(s, 17u + (uint32_t)t);
        float *ref = run(GEMM_SCALAR, s, &o), *got = run(isa, s, &o);
        for (size_t i = 0; i < (size_t)s->M * o.ldc; i++)
            if (memcmp(&ref[i], &got[i], sizeof(float)) != 0) {
                print_error("shape %zu (M %d N %d K %d) element %zu: path %d %.17g, scalar %.17g\n",
                            t, s->M, s->N, s->K, i, (int)isa, (double)got[i], (double)ref[i]);
                fail();
            }
        free(ref); free(got); free_ops(&o);
    }
}

static void test_avx512_bit_identical_to_scalar(void **st) { (void)st; check_paths_identical(GEMM_AVX512); }
static void test_avx2_bit_identical_to_scalar(void **st) { (void)st; check_paths_identical(GEMM_AVX2); }
static void test_auto_bit_identical_to_scalar(void **st) { (void)st; check_paths_identical(GEMM_AUTO); }

static void test_scalar_matches_double_product(void **st)
{
    (void)st;
    for (size_t t = 0; t < sizeof shapes / sizeof *shapes; t++) {
        const shape *s = &shapes[t];
        operands o = make_ops(s, 101u + (uint32_t)t);
        float *got = run(GEMM_SCALAR, s, &o);
        for (int i = 0; i < s->M; i++)
            for (int j = 0; j < s->N; j++) {
                double e = s->acc ? o.C0[i * o.ldc + j] : 0, mag = fabs(e);
                for (int k = 0; k < s->K; k++) {
                    double p = (double)o.A[i * o.ars + k * o.aks] * o.B[k * o.ldb + j];
                    e += p;
                    mag += fabs(p);
                }
                ASSERT_NEAR(got[i * o.ldc + j], e, 1e-6 * mag + 1e-30);
            }
        free(got); free_ops(&o);
    }
}

/* A bias row as the start of every chain (C = bias + A B) gives the bits of
 * copying the bias into C's rows and accumulating, on every path; K = 0 and
 * K = 300 (split into k-chunks) included. */
static void test_bias_start_equals_preloaded_rows(void **st)
{
    (void)st;
    const shape sh[] = {{13, 70, 9, 0, 0}, {24, 192, 64, 0, 0}, {64, 36, 300, 1, 0}, {7, 5, 0, 0, 0}};
    for (size_t t = 0; t < sizeof sh / sizeof *sh; t++) {
        const shape *s = &sh[t];
        operands o = make_ops(s, 41u + (uint32_t)t);
        float *bias = malloc(sizeof(float) * s->N), *want = malloc(sizeof(float) * (size_t)s->M * o.ldc);
        float *got = malloc(sizeof(float) * (size_t)s->M * o.ldc);
        assert_non_null(bias); assert_non_null(want); assert_non_null(got);
        fill(bias, s->N, 7u + (uint32_t)t);
        memcpy(want, o.C0, sizeof(float) * (size_t)s->M * o.ldc);
        for (int i = 0; i < s->M; i++) memcpy(want + i * o.ldc, bias, sizeof(float) * s->N);
        gemm_fma_isa(GEMM_SCALAR, s->M, s->N, s->K, o.A, o.ars, o.aks, o.B, o.ldb, want, o.ldc, 1, NULL, NULL, NULL);
        for (int isa = GEMM_SCALAR; isa <= GEMM_AVX512; isa++) {
            memcpy(got, o.C0, sizeof(float) * (size_t)s->M * o.ldc);
            gemm_fma_isa((gemm_isa)isa, s->M, s->N, s->K, o.A, o.ars, o.aks, o.B, o.ldb, got, o.ldc, 0, bias, NULL,
                         NULL);
            for (size_t i = 0; i < (size_t)s->M * o.ldc; i++)
                if (memcmp(&want[i], &got[i], sizeof(float)) != 0) {
                    print_error("shape %zu path %d element %zu: %.17g, want %.17g\n", t, isa, i,
                                (double)got[i], (double)want[i]);
                    fail();
                }
        }
        free(bias); free(want); free(got); free_ops(&o);
    }
}

/* The padding columns N..ldc-1 keep their values on every path. */
static void test_padding_untouched(void **st)
{
    (void)st;
    const shape s = {13, 70, 9, 0, 0};
    operands o = make_ops(&s, 5u);
    for (int isa = GEMM_SCALAR; isa <= GEMM_AVX512; isa++) {
        float *got = run((gemm_isa)isa, &s, &o);
        for (int i = 0; i < s.M; i++)
            for (int j = s.N; j < o.ldc; j++) ASSERT_EXACT(got[i * o.ldc + j], o.C0[i * o.ldc + j]);
        free(got);
    }
    free_ops(&o);
}

static void test_k_zero_clears_or_keeps(void **st)
{
    (void)st;
    float C[6] = {1, 2, 3, 4, 5, 6};
    gemm_fma(2, 3, 0, NULL, 0, 0, NULL, 3, C, 3, 1);
    ASSERT_EXACT(C[5], 6);
    gemm_fma(2, 3, 0, NULL, 0, 0, NULL, 3, C, 3, 0);
    ASSERT_EXACT(C[0], 0);
    ASSERT_EXACT(C[5], 0);
}

static void test_transpose(void **st)
{
    (void)st;
    float w[6] = {1, 2, 3, 4, 5, 6}, t[6]; /* w is 2 x 3 */
    gemm_transpose(t, w, 2, 3);
    const float want[6] = {1, 4, 2, 5, 3, 6};
    for (int i = 0; i < 6; i++) ASSERT_EXACT(t[i], want[i]);
}

/* Sizes with full 8 x 8 blocks and ragged edges both ways. */
static void test_transpose_blocks_and_edges(void **st)
{
    (void)st;
    const int sz[][2] = {{20, 37}, {64, 256}, {8, 8}, {3, 17}, {192, 64}};
    for (size_t t = 0; t < sizeof sz / sizeof *sz; t++) {
        const int N = sz[t][0], K = sz[t][1];
        float *w = malloc(sizeof(float) * N * K), *got = malloc(sizeof(float) * N * K);
        assert_non_null(w); assert_non_null(got);
        fill(w, (size_t)N * K, 3u + (uint32_t)t);
        gemm_transpose(got, w, N, K);
        for (int n = 0; n < N; n++)
            for (int k = 0; k < K; k++)
                if (memcmp(&got[k * N + n], &w[n * K + k], sizeof(float)) != 0) {
                    print_error("%d x %d: dst[%d][%d] = %.17g, want %.17g\n", N, K, k, n,
                                (double)got[k * N + n], (double)w[n * K + k]);
                    fail();
                }
        free(w); free(got);
    }
}

/* The strided, scaled form (an attention head's keys inside qkv): the same
 * product s * x as one value at a time, blocks and ragged edges. */
static void test_transpose_scaled_strided(void **st)
{
    (void)st;
    const int sz[][4] = {{24, 16, 192, 24}, {13, 11, 20, 17}}; /* N, K, lds, ldd */
    for (size_t t = 0; t < sizeof sz / sizeof *sz; t++) {
        const int N = sz[t][0], K = sz[t][1], lds = sz[t][2], ldd = sz[t][3];
        const float s = 0.3f;
        float *src = malloc(sizeof(float) * N * lds), *got = calloc((size_t)K * ldd, sizeof(float));
        assert_non_null(src); assert_non_null(got);
        fill(src, (size_t)N * lds, 11u + (uint32_t)t);
        gemm_transpose_scaled(got, ldd, src, lds, N, K, s);
        for (int n = 0; n < N; n++)
            for (int k = 0; k < K; k++) {
                const float want = s * src[n * lds + k];
                if (memcmp(&got[k * ldd + n], &want, sizeof want) != 0) {
                    print_error("%d x %d: dst[%d][%d] = %.17g, want %.17g\n", N, K, k, n,
                                (double)got[k * ldd + n], (double)want);
                    fail();
                }
            }
        free(src); free(got);
    }
}

/* The epilogue sees each strip once, in order, with its rows already final. */
typedef struct { float *copy; const float *C; ptrdiff_t ldc; int N, next, calls, bad; } epi_rec;
static void record(void *p, int i0, int rows)
{
    epi_rec *e = p;
    if (i0 != e->next || rows < 1 || rows > GEMM_STRIP) e->bad++;
    e->next = i0 + rows;
    e->calls++;
    for (int i = i0; i < i0 + rows; i++)
        memcpy(e->copy + i * e->ldc, e->C + i * e->ldc, sizeof(float) * e->N);
}

static void test_epilogue_sees_final_strips_in_order(void **st)
{
    (void)st;
    const shape s = {25, 130, 17, 1, 1}; /* 2 strips of GEMM_STRIP = 12 and one of 1 */
    operands o = make_ops(&s, 9u);
    for (int isa = GEMM_SCALAR; isa <= GEMM_AVX512; isa++) {
        float *C = malloc(sizeof(float) * s.M * o.ldc), *copy = calloc((size_t)s.M * o.ldc, sizeof(float));
        assert_non_null(C); assert_non_null(copy);
        memcpy(C, o.C0, sizeof(float) * s.M * o.ldc);
        epi_rec e = {copy, C, o.ldc, s.N, 0, 0, 0};
        gemm_fma_isa((gemm_isa)isa, s.M, s.N, s.K, o.A, o.ars, o.aks, o.B, o.ldb, C, o.ldc, 1, NULL, record, &e);
        ASSERT_EXACT(e.bad, 0);
        ASSERT_EXACT(e.calls, (s.M + GEMM_STRIP - 1) / GEMM_STRIP);
        ASSERT_EXACT(e.next, s.M);
        for (int i = 0; i < s.M; i++)
            for (int j = 0; j < s.N; j++) ASSERT_EXACT(copy[i * o.ldc + j], C[i * o.ldc + j]);
        free(C); free(copy);
    }
    free_ops(&o);
}

/* gemm_fma_heads equals H separate scalar products, bit for bit. */
static void check_heads(int H, int M, int n, int K, int transA, uint32_t seed)
{
    const ptrdiff_t ahs = (ptrdiff_t)M * K + 3, ars = transA ? 1 : K, aks = transA ? M : 1;
    const ptrdiff_t ldb = (ptrdiff_t)H * n + 2, ldc = (ptrdiff_t)H * n + 1;
    float *A = malloc(sizeof(float) * (size_t)(H * ahs)), *B = malloc(sizeof(float) * (size_t)(K * ldb));
    float *C1 = calloc((size_t)(M * ldc), sizeof(float)), *C2 = calloc((size_t)(M * ldc), sizeof(float));
    assert_non_null(A); assert_non_null(B); assert_non_null(C1); assert_non_null(C2);
    fill(A, (size_t)(H * ahs), seed);
    fill(B, (size_t)(K * ldb), seed + 1);
    gemm_fma_heads(H, M, n, K, A, ahs, ars, aks, B, ldb, C1, ldc);
    for (int h = 0; h < H; h++)
        gemm_fma_isa(GEMM_SCALAR, M, n, K, A + h * ahs, ars, aks, B + h * n, ldb, C2 + h * n, ldc, 0, NULL, NULL, NULL);
    for (int i = 0; i < M * ldc; i++)
        if (memcmp(&C1[i], &C2[i], sizeof(float)) != 0) {
            print_error("heads H %d M %d n %d K %d element %d: %.17g, per-head scalar %.17g\n",
                        H, M, n, K, i, (double)C1[i], (double)C2[i]);
            fail();
        }
    free(A); free(B); free(C1); free(C2);
}

static void test_heads_reference_attention_shapes(void **st)
{
    (void)st;
    check_heads(4, 24, 16, 24, 0, 61u); /* P V */
    check_heads(4, 24, 16, 24, 1, 62u); /* P^T dO */
}

static void test_heads_odd_shapes_and_fallback(void **st)
{
    (void)st;
    check_heads(3, 5, 16, 7, 0, 63u);
    check_heads(1, 13, 16, 2, 1, 64u);
    check_heads(2, 9, 8, 11, 0, 65u); /* n != 16: per-head path */
    check_heads(5, 7, 16, 3, 0, 66u); /* H > 4: per-head path */
}

static void test_isa_name_is_a_path(void **st)
{
    (void)st;
    const char *n = gemm_isa_name();
    assert_true(!strcmp(n, "avx512") || !strcmp(n, "avx2") || !strcmp(n, "scalar"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_avx512_bit_identical_to_scalar),
        cmocka_unit_test(test_avx2_bit_identical_to_scalar),
        cmocka_unit_test(test_auto_bit_identical_to_scalar),
        cmocka_unit_test(test_scalar_matches_double_product),
        cmocka_unit_test(test_padding_untouched),
        cmocka_unit_test(test_bias_start_equals_preloaded_rows),
        cmocka_unit_test(test_k_zero_clears_or_keeps),
        cmocka_unit_test(test_transpose),
        cmocka_unit_test(test_transpose_blocks_and_edges),
        cmocka_unit_test(test_transpose_scaled_strided),
        cmocka_unit_test(test_epilogue_sees_final_strips_in_order),
        cmocka_unit_test(test_heads_reference_attention_shapes),
        cmocka_unit_test(test_heads_odd_shapes_and_fallback),
        cmocka_unit_test(test_isa_name_is_a_path),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
