/* The hot kernels of src/model/nn.c and nn_attn.c are built as AVX2 and
 * baseline x86-64 clones picked at load time, with AVX-512 forms of the GELU
 * and of attention at the reference head shape taken on the AVX-512 gemm
 * path. This test compiles a second, baseline-only copy of both
 * (NN_NO_CLONES, symbols renamed) and checks that it gives bit-identical
 * results to the library's kernels on every gemm path this CPU has, on the
 * reference shapes, so a run does not depend on the machine's vector
 * extensions. */
#include "testutil.h"
#define NN_NO_CLONES
#define nn_expf base_expf
#define nn_linear_forward base_linear_forward
#define nn_linear_backward base_linear_backward
#define nn_layernorm_forward base_layernorm_forward
#define nn_layernorm_backward base_layernorm_backward
#define nn_gelu_forward base_gelu_forward
#define nn_gelu_forward_save base_gelu_forward_save
#define nn_gelu_backward base_gelu_backward
#define nn_gelu_backward_saved base_gelu_backward_saved
#define nn_residual_forward base_residual_forward
#define nn_bias_gelu_forward_save base_bias_gelu_forward_save
#define nn_bias_residual_forward base_bias_residual_forward
#define nn_residual_backward base_residual_backward
#define nn_attention_forward base_attention_forward
#define nn_attention_backward base_attention_backward
#define nn_attention_scratch_len base_attention_scratch_len
#define nn_attention_forward_biased base_attention_forward_biased
#define nn_attention_backward_biased base_attention_backward_biased
#define nn_linear_bias_gelu_forward base_linear_bias_gelu_forward
#define nn_linear_bias_residual_forward base_linear_bias_residual_forward
#define nn_linear_backward_gelu base_linear_backward_gelu
#define nn_linear_attention_forward base_linear_attention_forward
#define nn_linear_backward_attention base_linear_backward_attention
#define nn_linear_backward_qkv base_linear_backward_qkv
#define nn_linear_forward_epi base_linear_forward_epi
#define nn_linear_backward_epi base_linear_backward_epi
#include "nn.c"
#include "nn_attn.c"
#undef nn_expf
#undef nn_layernorm_forward
#undef nn_layernorm_backward
#undef nn_gelu_forward_save
#undef nn_gelu_backward_saved
#undef nn_attention_forward
#undef nn_attention_backward
#undef nn_attention_scratch_len
#undef nn_attention_forward_biased
#undef nn_attention_backward_biased
#undef nn_bias_gelu_forward_save
/* the library's (dispatched) kernels; nn.h was consumed by the renamed copy */
void nn_expf(float *y, const float *x, size_t n);
void nn_layernorm_forward(float *out, float *mean, float *rstd, const float *in,
                          const float *g, const float *b, int M, int C);
void nn_layernorm_backward(float *dinp, float *dg, float *db, const float *dout,
                           const float *in, const float *mean, const float *rstd,
                           const float *g, int M, int C);
void nn_gelu_forward_save(float *out, float *sig, const float *in, size_t n);
void nn_gelu_backward_saved(float *dinp, const float *dout, const float *in,
                            const float *sig, size_t n);
void nn_attention_forward(float *out, float *prob, const float *qkv,
                          int B, int T, int C, int H, nn_attn_mode mode, float *scratch);
void nn_attention_backward(float *dqkv, const float *dout, const float *qkv,
                           const float *prob, int B, int T, int C, int H,
                           nn_attn_mode mode, float *scratch);
size_t nn_attention_scratch_len(int T, int C, int H);
void nn_attention_forward_biased(float *out, float *prob, const float *qkv, const float *sbias,
                                 int B, int T, int C, int H, nn_attn_mode mode, float *scratch);
void nn_attention_backward_biased(float *dqkv, const float *dout, const float *qkv,
                                  const float *prob, const float *dpadd, int B, int T, int C,
                                  int H, nn_attn_mode mode, float *scratch);
void nn_bias_gelu_forward_save(float *h, float *sig, float *out, const float *b, int M, int N);

static void tu_fill(float *x, size_t n, float a, unsigned *state)
{
    for (size_t i = 0; i < n; i++) {
        unsigned s = *state;
        s ^= s << 13; s ^= s >> 17; s ^= s << 5;
        *state = s;
        x[i] = a * (2.0f * (float)(s >> 8) / 16777216.0f - 1.0f);
    }
}

static void same(const float *a, const float *b, size_t n, const char *what)
{
    if (memcmp(a, b, n * sizeof(float)) != 0) {
        size_t i = 0;
        while (a[i] == b[i]) i++;
        print_error("%s: clone results differ at %zu: %.9g vs %.9g\n", what, i, a[i], b[i]);
        fail();
    }
}

/* The library's kernels on one gemm path (gemm_set_isa also chooses the layer
 * kernels' AVX-512 or AVX2 forms, gemm.h) against the baseline copy. */
static void check_path(gemm_isa isa)
{
    if (!gemm_isa_available(isa)) { print_message("path %d not on this CPU: skipped\n", (int)isa); return; }
    gemm_isa before = gemm_set_isa(isa);
    enum { B = 4, T = 24, C = 64, H = 4, F = 256, N = B * T };
    unsigned st = 17;
    float *qkv = malloc(sizeof(float) * N * 3 * C), *dout = malloc(sizeof(float) * N * C);
    float *o1 = malloc(sizeof(float) * N * 3 * C), *o2 = malloc(sizeof(float) * N * 3 * C);
    float *p1 = malloc(sizeof(float) * B * H * T * T), *p2 = malloc(sizeof(float) * B * H * T * T);
    float *scr = malloc(sizeof(float) * nn_attention_scratch_len(T, C, H));
    float *h = malloc(sizeof(float) * N * F), *g1 = malloc(sizeof(float) * N * F), *g2 = malloc(sizeof(float) * N * F);
    float *s1 = malloc(sizeof(float) * N * F), *s2 = malloc(sizeof(float) * N * F);
    float gam[C], bet[C], mu[N], rs[N], dg1[C] = {0}, db1[C] = {0}, dg2[C] = {0}, db2[C] = {0};
    tu_fill(qkv, (size_t)N * 3 * C, 2, &st); tu_fill(dout, (size_t)N * C, 1, &st);
    tu_fill(h, (size_t)N * F, 4, &st); tu_fill(gam, C, 1, &st); tu_fill(bet, C, 1, &st);

    nn_attention_forward(o1, p1, qkv, B, T, C, H, NN_ATTN_JOINT, scr);
    base_attention_forward(o2, p2, qkv, B, T, C, H, NN_ATTN_JOINT, scr);
    same(o1, o2, (size_t)N * C, "attention forward");
    same(p1, p2, (size_t)B * H * T * T, "attention probabilities");
    nn_attention_backward(o1, dout, qkv, p1, B, T, C, H, NN_ATTN_JOINT, scr);
    base_attention_backward(o2, dout, qkv, p1, B, T, C, H, NN_ATTN_JOINT, scr);
    same(o1, o2, (size_t)N * 3 * C, "attention backward");

    /* the pair-aware forms (src/model/pairattn.h): score bias and dP term, and the
     * dS left in the scratch by a one-patch backward */
    {
        float *sb = malloc(sizeof(float) * B * H * T * T), *dpx = malloc(sizeof(float) * B * H * T * T);
        float *scr2 = malloc(sizeof(float) * nn_attention_scratch_len(T, C, H));
        tu_fill(sb, (size_t)B * H * T * T, 1.5f, &st); tu_fill(dpx, (size_t)B * H * T * T, 1.f, &st);
        nn_attention_forward_biased(o1, p1, qkv, sb, B, T, C, H, NN_ATTN_JOINT, scr);
        base_attention_forward_biased(o2, p2, qkv, sb, B, T, C, H, NN_ATTN_JOINT, scr2);
        same(o1, o2, (size_t)N * C, "biased attention forward");
        same(p1, p2, (size_t)B * H * T * T, "biased attention probabilities");
        for (int b = 0; b < B; b++) {
            const size_t r = (size_t)b * T, ph = (size_t)b * H * T * T;
            nn_attention_backward_biased(o1 + r * 3 * C, dout + r * C, qkv + r * 3 * C, p1 + ph, dpx + ph,
                                         1, T, C, H, NN_ATTN_JOINT, scr);
            base_attention_backward_biased(o2 + r * 3 * C, dout + r * C, qkv + r * 3 * C, p1 + ph, dpx + ph,
                                           1, T, C, H, NN_ATTN_JOINT, scr2);
            same(scr, scr2, (size_t)H * T * T, "biased attention dS in the scratch");
        }
        same(o1, o2, (size_t)N * 3 * C, "biased attention backward");
        free(sb); free(dpx); free(scr2);
    }

    nn_gelu_forward_save(g1, s1, h, (size_t)N * F);
    base_gelu_forward_save(g2, s2, h, (size_t)N * F);
    same(g1, g2, (size_t)N * F, "gelu forward");
    nn_gelu_backward_saved(g1, h, h, s1, (size_t)N * F);
    base_gelu_backward_saved(g2, h, h, s1, (size_t)N * F);
    same(g1, g2, (size_t)N * F, "gelu backward");

    nn_layernorm_forward(o1, mu, rs, qkv, gam, bet, N, C);
    base_layernorm_forward(o2, mu, rs, qkv, gam, bet, N, C);
    same(o1, o2, (size_t)N * C, "layernorm forward");
    memset(o1, 0, sizeof(float) * N * C); memset(o2, 0, sizeof(float) * N * C);
    nn_layernorm_backward(o1, dg1, db1, dout, qkv, mu, rs, gam, N, C);
    base_layernorm_backward(o2, dg2, db2, dout, qkv, mu, rs, gam, N, C);
    same(o1, o2, (size_t)N * C, "layernorm backward");
    same(dg1, dg2, C, "layernorm dg");

    /* bias + GELU: the library takes its 16-lane AVX-512 form where the CPU has
     * it; the baseline copy is 8-lane SSE. 21 columns leave a scalar tail. */
    for (int NC = 21; NC <= 64; NC += 43) {
        enum { R = 40, NMAX = 64 };
        float bias[NMAX], ha[R * NMAX], hb[R * NMAX], sa[R * NMAX], sb[R * NMAX], oa[R * NMAX], ob[R * NMAX];
        tu_fill(bias, NC, 1, &st); tu_fill(ha, (size_t)R * NC, 5, &st);
        memcpy(hb, ha, sizeof(float) * R * NC);
        nn_bias_gelu_forward_save(ha, sa, oa, bias, R, NC);
        base_bias_gelu_forward_save(hb, sb, ob, bias, R, NC);
        same(ha, hb, (size_t)R * NC, "bias+gelu pre-activation");
        same(sa, sb, (size_t)R * NC, "bias+gelu sigmoid");
        same(oa, ob, (size_t)R * NC, "bias+gelu output");
    }
    nn_expf(o1, h, (size_t)N * 3);
    base_expf(o2, h, (size_t)N * 3);
    same(o1, o2, (size_t)N * 3, "exp");
    free(qkv); free(dout); free(o1); free(o2); free(p1); free(p2); free(scr);
    free(h); free(g1); free(g2); free(s1); free(s2);
    gemm_set_isa(before);
}

/* Attention at the reference head shape (T = 24, hd = 16), which the AVX-512
 * and AVX2 paths run in register blocks of their own, against the generic
 * kernels of the baseline copy: six patches, unbiased and biased, with scores
 * large enough that the exponential's clamp is reached and with exact zeros
 * (signed zeros and the clamp are where a reordered or contracted operation
 * would show first). */
static void check_attention24(gemm_isa isa)
{
    if (!gemm_isa_available(isa)) { print_message("path %d not on this CPU: skipped\n", (int)isa); return; }
    gemm_isa before = gemm_set_isa(isa);
    enum { B = 6, T = 24, C = 64, H = 4, N = B * T };
    unsigned st = 29;
    const size_t nq = (size_t)N * 3 * C, no = (size_t)N * C, np = (size_t)B * H * T * T;
    float *qkv = malloc(sizeof(float) * nq), *dout = malloc(sizeof(float) * no);
    float *o1 = malloc(sizeof(float) * nq), *o2 = malloc(sizeof(float) * nq);
    float *p1 = malloc(sizeof(float) * np), *p2 = malloc(sizeof(float) * np);
    float *sb = malloc(sizeof(float) * np), *dpx = malloc(sizeof(float) * np);
    float *scr1 = malloc(sizeof(float) * nn_attention_scratch_len(T, C, H));
    float *scr2 = malloc(sizeof(float) * nn_attention_scratch_len(T, C, H));
    tu_fill(qkv, nq, 3, &st); tu_fill(dout, no, 1, &st); tu_fill(sb, np, 2, &st); tu_fill(dpx, np, 1, &st);
    for (size_t i = 0; i < nq; i += 7) qkv[i] = 0.f;
    for (size_t i = 3; i < nq; i += 11) qkv[i] = -0.f;
    for (size_t i = 0; i < (size_t)T * 3 * C; i += 5) qkv[i] *= 40.f; /* patch 0: clamped scores */
    for (size_t i = 0; i < no; i += 9) dout[i] = 0.f;
    for (int biased = 0; biased < 2; biased++) {
        nn_attention_forward_biased(o1, p1, qkv, biased ? sb : NULL, B, T, C, H, NN_ATTN_JOINT, scr1);
        base_attention_forward_biased(o2, p2, qkv, biased ? sb : NULL, B, T, C, H, NN_ATTN_JOINT, scr2);
        same(o1, o2, no, "reference-shape attention forward");
        same(p1, p2, np, "reference-shape attention probabilities");
        for (int b = 0; b < B; b++) {
            const size_t r = (size_t)b * T, ph = (size_t)b * H * T * T;
            nn_attention_backward_biased(o1 + r * 3 * C, dout + r * C, qkv + r * 3 * C, p1 + ph,
                                         biased ? dpx + ph : NULL, 1, T, C, H, NN_ATTN_JOINT, scr1);
            base_attention_backward_biased(o2 + r * 3 * C, dout + r * C, qkv + r * 3 * C, p1 + ph,
                                           biased ? dpx + ph : NULL, 1, T, C, H, NN_ATTN_JOINT, scr2);
            same(scr1, scr2, (size_t)H * T * T, "reference-shape attention dS");
        }
        same(o1, o2, nq, "reference-shape attention backward");
    }
    free(qkv); free(dout); free(o1); free(o2); free(p1); free(p2); free(sb); free(dpx); free(scr1); free(scr2);
    gemm_set_isa(before);
}

/* The layer norm on every path against the baseline copy: rows in fours and
 * one at a time (11 rows), widths whose element-wise passes take 16 lanes on
 * the AVX-512 path (64, 48) and one that does not (40); means, reciprocal
 * deviations, outputs and all three gradients. */
static void check_layernorm(gemm_isa isa)
{
    if (!gemm_isa_available(isa)) { print_message("path %d not on this CPU: skipped\n", (int)isa); return; }
    gemm_isa before = gemm_set_isa(isa);
    enum { M = 11, CMAX = 64 };
    const int widths[3] = {64, 48, 40};
    unsigned st = 31;
    for (int w = 0; w < 3; w++) {
        const int C = widths[w];
        float x[M * CMAX], dy[M * CMAX], g[CMAX], b[CMAX], y1[M * CMAX], y2[M * CMAX];
        float dx1[M * CMAX], dx2[M * CMAX], mu1[M], mu2[M], rs1[M], rs2[M];
        float dg1[CMAX], dg2[CMAX], db1[CMAX], db2[CMAX];
        tu_fill(x, (size_t)M * C, 3, &st); tu_fill(dy, (size_t)M * C, 1, &st);
        tu_fill(g, C, 1, &st); tu_fill(b, C, 1, &st); tu_fill(dx1, (size_t)M * C, 1, &st);
        memcpy(dx2, dx1, sizeof(float) * M * C);
        tu_fill(dg1, C, 1, &st); memcpy(dg2, dg1, sizeof(float) * C);
        tu_fill(db1, C, 1, &st); memcpy(db2, db1, sizeof(float) * C);
        nn_layernorm_forward(y1, mu1, rs1, x, g, b, M, C);
        base_layernorm_forward(y2, mu2, rs2, x, g, b, M, C);
        same(mu1, mu2, M, "layernorm mean");
        same(rs1, rs2, M, "layernorm 1/sd");
        same(y1, y2, (size_t)M * C, "layernorm forward (rows in fours and alone)");
        nn_layernorm_backward(dx1, dg1, db1, dy, x, mu1, rs1, g, M, C);
        base_layernorm_backward(dx2, dg2, db2, dy, x, mu2, rs2, g, M, C);
        same(dx1, dx2, (size_t)M * C, "layernorm input gradient");
        same(dg1, dg2, C, "layernorm dg");
        same(db1, db2, C, "layernorm db");
    }
    gemm_set_isa(before);
}

/* The GELU's sigmoid(2u) of one value as DEF_VGSIG / DEF_VEXP compute it
 * (nn.c, nn_vec.h), written naively: float operations one at a time, the
 * clamps as comparisons and 2^n from its exponent bits. The naive reference
 * of the intrinsic bias + GELU kernels. */
static float ref_gsig(float x)
{
    float u = 0.7978845608028654f * (x + 0.044715f * x * x * x);
    float y = -2.f * u;
    if (y < -87.0f) y = -87.0f;
    if (y > 88.0f) y = 88.0f;
    float kn = (y * 1.44269504088896341f + 12582912.0f) - 12582912.0f;
    float r = y - kn * 0.693145751953125f;
    r = r - kn * 1.428606765330187e-06f;
    float p = 1.f / 5040.f;
    p = p * r + 1.f / 720.f;
    p = p * r + 1.f / 120.f;
    p = p * r + 1.f / 24.f;
    p = p * r + 1.f / 6.f;
    p = p * r + 0.5f;
    p = p * r + 1.f;
    p = p * r + 1.f;
    unsigned bits = (unsigned)((int)kn + 127) << 23;
    float two;
    memcpy(&two, &bits, sizeof two);
    return 1.f / (1.f + p * two);
}

static int same_bits(float a, float b) { return memcmp(&a, &b, sizeof a) == 0 || (isnan(a) && isnan(b)); }

/* bias + GELU at the model's MLP width and beyond (N = 256 + 21: the
 * kernels' blocks of 8 x 16 and 16 x 8 lanes, single vectors and the scalar
 * tail) on one path, against the baseline copy and the one-value reference,
 * on values that reach both clamps of the exponential, infinities, signed
 * zeros, subnormals and a NaN; then the forward-only form (sig NULL, as the
 * sampler calls it) gives the same outputs and leaves h alone. */
static void check_bias_gelu_wide(gemm_isa isa)
{
    if (!gemm_isa_available(isa)) { print_message("path %d not on this CPU: skipped\n", (int)isa); return; }
    gemm_isa before = gemm_set_isa(isa);
    enum { R = 7, NC = 277, NE = R * NC };
    unsigned st = 41;
    float *ha = malloc(sizeof(float) * NE), *hb = malloc(sizeof(float) * NE), *h0 = malloc(sizeof(float) * NE);
    float *sa = malloc(sizeof(float) * NE), *sb = malloc(sizeof(float) * NE);
    float *oa = malloc(sizeof(float) * NE), *ob = malloc(sizeof(float) * NE), *of = malloc(sizeof(float) * NE);
    float bias[NC];
    tu_fill(bias, NC, 1, &st);
    tu_fill(h0, NE, 12, &st); /* |x| up to 13: both clamps are reached */
    const float special[] = {0.f, -0.f, INFINITY, -INFINITY, NAN, 1e-40f, -1e-40f, 1e-30f, -1e30f, 1e30f,
                             -9.5f, 9.5f, -200.f, 200.f, 3e38f, -3e38f};
    for (size_t k = 0; k < sizeof special / sizeof *special; k++) { /* bias 0 there: x is the special value */
        h0[37 * k + 5] = special[k];
        bias[(37 * k + 5) % NC] = 0.f;
    }
    for (int c = 0; c < NC; c += 13) h0[4 * NC + c] = -bias[c]; /* x = +0 exactly */
    memcpy(ha, h0, sizeof(float) * NE);
    memcpy(hb, h0, sizeof(float) * NE);
    nn_bias_gelu_forward_save(ha, sa, oa, bias, R, NC);
    base_bias_gelu_forward_save(hb, sb, ob, bias, R, NC);
    same(ha, hb, NE, "wide bias+gelu pre-activation");
    for (int i = 0; i < NE; i++) {
        const float x = h0[i] + bias[i % NC], sg = ref_gsig(x);
        if (!same_bits(sa[i], sg) || !same_bits(sb[i], sg) || !same_bits(oa[i], x * sg)) {
            print_error("path %d, value %d (x = %.9g): sigmoid %.9g / %.9g, naive %.9g; out %.9g, naive %.9g\n",
                        (int)isa, i, x, sa[i], sb[i], sg, oa[i], x * sg);
            fail();
        }
    }
    memcpy(ha, h0, sizeof(float) * NE);
    nn_bias_gelu_forward_save(ha, NULL, of, bias, R, NC);
    for (int i = 0; i < NE; i++)
        if (!same_bits(of[i], oa[i])) { print_error("forward-only bias+gelu differs at %d\n", i); fail(); }
    assert_memory_equal(ha, h0, sizeof(float) * NE);
    free(ha); free(hb); free(h0); free(sa); free(sb); free(oa); free(ob); free(of);
    gemm_set_isa(before);
}

static void test_bias_gelu_wide_avx512(void **s) { (void)s; check_bias_gelu_wide(GEMM_AVX512); }
static void test_bias_gelu_wide_avx2(void **s) { (void)s; check_bias_gelu_wide(GEMM_AVX2); }
static void test_bias_gelu_wide_scalar(void **s) { (void)s; check_bias_gelu_wide(GEMM_SCALAR); }

static void test_layernorm_avx512(void **s) { (void)s; check_layernorm(GEMM_AVX512); }
static void test_layernorm_avx2(void **s) { (void)s; check_layernorm(GEMM_AVX2); }

static void test_reference_shape_attention_avx512(void **s) { (void)s; check_attention24(GEMM_AVX512); }
static void test_reference_shape_attention_avx2(void **s) { (void)s; check_attention24(GEMM_AVX2); }

static void test_avx512_kernels_agree_with_baseline(void **s) { (void)s; check_path(GEMM_AVX512); }
static void test_avx2_kernels_agree_with_baseline(void **s) { (void)s; check_path(GEMM_AVX2); }
static void test_scalar_path_kernels_agree_with_baseline(void **s) { (void)s; check_path(GEMM_SCALAR); }

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_avx512_kernels_agree_with_baseline),
        cmocka_unit_test(test_avx2_kernels_agree_with_baseline),
        cmocka_unit_test(test_scalar_path_kernels_agree_with_baseline),
        cmocka_unit_test(test_reference_shape_attention_avx512),
        cmocka_unit_test(test_layernorm_avx512),
        cmocka_unit_test(test_layernorm_avx2),
        cmocka_unit_test(test_reference_shape_attention_avx2),
        cmocka_unit_test(test_bias_gelu_wide_avx512),
        cmocka_unit_test(test_bias_gelu_wide_avx2),
        cmocka_unit_test(test_bias_gelu_wide_scalar),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
