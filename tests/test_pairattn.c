/* Tests for src/model/pairattn.c (pair-aware attention, design.md §8.1): the
 * pair features against trigonometry and by hand, the standardisation, the
 * forward against a naive double reference (tests/pairref.h), every gradient
 * (qkv, score weights wb, value weights wv) against central finite
 * differences of that reference in double precision, for both arms, on a
 * tiny shape and on the reference patch shape (T = 24, hd = 16: nn.c's
 * AVX-512 kernel where the CPU has it); bit-identical results on every gemm
 * path and fused = unfused. Inputs are pseudo-random and of mixed sign, and
 * the score weights are large enough that the bias moves the softmax, so a
 * wrong term cannot hide behind a cancelling one. Mismatches print observed
 * and expected values with %.17g. */
#include "testutil.h"
#pragma GCC diagnostic ignored "-Wunused-function" /* nnref.h's other kernels */
#include "nnref.h"
#include "pairref.h"
#include "pairattn.h"
#include "gemm.h"

#define FD_H 1e-5
#define GRAD_TOL 2e-4
#define FWD_TOL 2e-5
enum { Q = PAIRATTN_Q };

/* max |a - b| relative to max(1, max|b|); on failure the worst entry, %.17g */
#define ASSERT_CLOSE(analytic, numeric, n, tol, what) do { \
    size_t w_; double e_ = tu_maxrel((analytic), (numeric), (n), &w_); \
    if (!(e_ <= (tol))) { \
        print_error("%s: max rel error %.3g at %zu: observed %.17g, expected %.17g\n", \
                    (what), e_, w_, (double)(analytic)[w_], (numeric)[w_]); \
        fail(); } } while (0)

static void same_bits(const float *a, const float *b, size_t n, const char *what)
{
    for (size_t i = 0; i < n; i++)
        if (memcmp(a + i, b + i, sizeof(float)) != 0) {
            print_error("%s: element %zu differs: %.17g vs %.17g\n", what, i, (double)a[i], (double)b[i]);
            fail();
        }
}

/* ---- features ------------------------------------------------------------------ */
static void test_features_by_hand(void **s)
{
    (void)s;
    /* x, y, rbar: stem 1 at distance 1 from stem 0 on a 3-4-5 bearing */
    const float tok[9] = {0.f, 0.f, 0.3f, 0.6f, 0.8f, 0.25f, -1.f, 0.f, 0.4f};
    float f[9 * Q];
    pairattn_features(f, tok, 3, 3);
    const float *f01 = f + 1 * Q;
    const double want01[Q] = {0.6, 0.8, 1.0, 1.0 - 0.3 - 0.25, 0.6, 0.8, 0.36 - 0.64, 2 * 0.6 * 0.8};
    for (int q = 0; q < Q; q++) ASSERT_NEAR(f01[q], want01[q], 2e-7);
    const float *f00 = f;
    for (int q = 0; q < Q; q++) ASSERT_EXACT(f00[q], q == 3 ? (float)(-2 * (double)0.3f) : 0.f);
    /* stem 2 seen from stem 0: due west; cos 2 theta = 1, sin 2 theta = 0 */
    const float *f02 = f + 2 * Q;
    const double want02[Q] = {-1, 0, 1, 1 - (double)0.3f - (double)0.4f, -1, 0, 1, 0};
    for (int q = 0; q < Q; q++) ASSERT_NEAR(f02[q], want02[q], 1e-7);
}

static void test_features_match_trigonometry(void **s)
{
    (void)s;
    enum { T = 24, NF = 5 };
    float tok[T * NF];
    double tokd[T * NF], ref[T * T * Q];
    unsigned st = 3;
    tu_fill(tok, T * NF, 3.f, &st);
    for (int i = 0; i < T; i++) tok[i * NF + 2] = 0.3f + 0.05f * tok[i * NF + 2];
    tu_f2d(tokd, tok, T * NF);
    float f[T * T * Q];
    pairattn_features(f, tok, NF, T);
    ref_pair_features(ref, tokd, NF, T);
    ASSERT_CLOSE(f, ref, (size_t)T * T * Q, 1e-6, "pair features");
}

static void test_geometry_standardises_both_layouts(void **s)
{
    (void)s;
    enum { T = 6, NF = 3 };
    float tok[T * NF], f[T * T * Q], phi[T * T * Q], phit[T * T * Q], mu[Q], isd[Q];
    unsigned st = 9;
    tu_fill(tok, T * NF, 2.f, &st);
    tu_fill(mu, Q, 1.f, &st);
    for (int q = 0; q < Q; q++) isd[q] = 0.5f + 0.25f * q;
    pairattn_features(f, tok, NF, T);
    pairattn_geometry(phi, phit, tok, NF, T, mu, isd);
    for (int e = 0; e < T * T; e++)
        for (int q = 0; q < Q; q++) {
            ASSERT_EXACT(phi[e * Q + q], (f[e * Q + q] - mu[q]) * isd[q]);
            ASSERT_EXACT(phit[q * T * T + e], phi[e * Q + q]);
        }
}

/* The naive geometry: the pair features one pair at a time in double, then
 * each z-score in float, written to both layouts (the order of operations the
 * library's vector kernels must keep). */
static void naive_geometry(float *phi, float *phit, const float *tok, int stride, int T,
                           const float *mu, const float *isd)
{
    const size_t TT = (size_t)T * T;
    for (int i = 0; i < T; i++)
        for (int j = 0; j < T; j++) {
            const double xi = tok[i * stride], yi = tok[i * stride + 1], ri = tok[i * stride + 2];
            const double dx = (double)tok[j * stride] - xi, dy = (double)tok[j * stride + 1] - yi;
            const double dist = sqrt(dx * dx + dy * dy);
            const double c = dist > 0 ? dx / dist : 0.0, sn = dist > 0 ? dy / dist : 0.0;
            const float f[Q] = {(float)dx, (float)dy, (float)dist,
                                (float)(dist - ri - (double)tok[j * stride + 2]), (float)c, (float)sn,
                                (float)(c * c - sn * sn), (float)(2 * c * sn)};
            const size_t e = (size_t)i * T + j;
            for (int q = 0; q < Q; q++) {
                float z = (f[q] - mu[q]) * isd[q];
                phi[e * Q + q] = z;
                phit[q * TT + e] = z;
            }
        }
}

/* pairattn_geometry = the naive loops bit for bit on every gemm path, at the
 * reference patch and at a ragged T, with coincident and aligned stems. */
static void check_geometry_paths(int T)
{
    enum { NF = 12 };
    const size_t n = (size_t)T * T * Q;
    float *tok = malloc(sizeof(float) * T * NF), *phi = malloc(sizeof(float) * n),
          *phit = malloc(sizeof(float) * n), *rphi = malloc(sizeof(float) * n),
          *rphit = malloc(sizeof(float) * n), mu[Q], isd[Q];
    unsigned st = 77 + T;
    tu_fill(tok, (size_t)T * NF, 4.f, &st);
    tu_fill(mu, Q, 1.f, &st);
    for (int q = 0; q < Q; q++) isd[q] = 0.37f + 0.29f * q;
    for (int k = 0; k < NF; k++) tok[3 * NF + k] = tok[1 * NF + k]; /* stems 1 and 3 coincide */
    tok[5 * NF] = tok[2 * NF];                                        /* 2 and 5: same x */
    tok[7 * NF + 1] = tok[2 * NF + 1];                                /* 2 and 7: same y */
    naive_geometry(rphi, rphit, tok, NF, T, mu, isd);
    for (int isa = GEMM_SCALAR; isa <= GEMM_AVX512; isa++) {
        if (!gemm_isa_available((gemm_isa)isa)) continue;
        gemm_isa before = gemm_set_isa((gemm_isa)isa);
        memset(phi, 0xff, sizeof(float) * n);
        memset(phit, 0xff, sizeof(float) * n);
        pairattn_geometry(phi, phit, tok, NF, T, mu, isd);
        gemm_set_isa(before);
        same_bits(phi, rphi, n, "pair geometry (pair-major) against the naive loops");
        same_bits(phit, rphit, n, "pair geometry (feature-major) against the naive loops");
    }
    free(tok); free(phi); free(phit); free(rphi); free(rphit);
}
static void test_geometry_naive_every_path_reference(void **s) { (void)s; check_geometry_paths(24); }
static void test_geometry_naive_every_path_ragged(void **s) { (void)s; check_geometry_paths(11); }

/* ---- layer against the reference ------------------------------------------------ */
typedef struct {
    int B, T, C, H, mode;
    double *qkv, *phi, *wb, *wv, *dout, *out;
} pa_ctx;

static double pa_loss(void *p)
{
    pa_ctx *c = p;
    ref_pair_attention(c->out, c->qkv, c->phi, c->wb, c->wv, c->B, c->T, c->C, c->H, c->mode);
    return tu_dot(c->out, c->dout, (size_t)c->B * c->T * c->C);
}

typedef struct {
    int B, T, C, H;
    size_t nq, no, np;
    float *qkv, *phi, *phit, *wb, *wv, *wvt, *dout, *out, *prob, *Phi, *scr, *dqkv, *dwb, *dwv;
} pa_fix;

static void pa_make(pa_fix *f, int B, int T, int C, int H, unsigned seed)
{
    f->B = B; f->T = T; f->C = C; f->H = H;
    f->nq = (size_t)B * T * 3 * C; f->no = (size_t)B * T * C; f->np = (size_t)B * T * T * Q;
    f->qkv = malloc(sizeof(float) * f->nq); f->dqkv = malloc(sizeof(float) * f->nq);
    f->phi = malloc(sizeof(float) * f->np); f->phit = malloc(sizeof(float) * f->np);
    f->wb = malloc(sizeof(float) * H * Q); f->dwb = calloc((size_t)H * Q, sizeof(float));
    f->wv = malloc(sizeof(float) * C * Q); f->wvt = malloc(sizeof(float) * C * Q);
    f->dwv = calloc((size_t)C * Q, sizeof(float));
    f->dout = malloc(sizeof(float) * f->no); f->out = malloc(sizeof(float) * f->no);
    f->prob = malloc(sizeof(float) * B * H * T * T); f->Phi = malloc(sizeof(float) * B * H * T * Q);
    f->scr = malloc(sizeof(float) * pairattn_scratch_len(T, C, H));
    unsigned st = seed;
    tu_fill(f->qkv, f->nq, 1.5f, &st);
    tu_fill(f->dout, f->no, 1.f, &st);
    tu_fill(f->wb, (size_t)H * Q, 1.5f, &st);
    tu_fill(f->wv, (size_t)C * Q, 1.f, &st);
    /* geometry of random stems, standardised by arbitrary z-scores */
    float *tok = malloc(sizeof(float) * T * 3), mu[Q], isd[Q];
    tu_fill(mu, Q, 0.5f, &st);
    for (int q = 0; q < Q; q++) isd[q] = 0.6f + 0.1f * q;
    for (int b = 0; b < B; b++) {
        tu_fill(tok, (size_t)T * 3, 2.f, &st);
        for (int i = 0; i < T; i++) tok[i * 3 + 2] = 0.35f + 0.05f * tok[i * 3 + 2];
        pairattn_geometry(f->phi + (size_t)b * T * T * Q, f->phit + (size_t)b * T * T * Q, tok, 3, T, mu, isd);
    }
    free(tok);
}

static void pa_free(pa_fix *f)
{
    free(f->qkv); free(f->dqkv); free(f->phi); free(f->phit); free(f->wb); free(f->dwb);
    free(f->wv); free(f->wvt); free(f->dwv); free(f->dout); free(f->out); free(f->prob);
    free(f->Phi); free(f->scr);
}

static void check_layer(int B, int T, int C, int H, nn_attn_mode mode, unsigned seed)
{
    pa_fix f;
    pa_make(&f, B, T, C, H, seed);
    double *qkv = malloc(sizeof(double) * f.nq), *phi = malloc(sizeof(double) * f.np);
    double *wb = malloc(sizeof(double) * H * Q), *wv = malloc(sizeof(double) * C * Q);
    double *dout = malloc(sizeof(double) * f.no), *out = malloc(sizeof(double) * f.no);
    double *g = malloc(sizeof(double) * (f.nq > (size_t)C * Q ? f.nq : (size_t)C * Q));
    tu_f2d(qkv, f.qkv, f.nq); tu_f2d(phi, f.phi, f.np); tu_f2d(wb, f.wb, (size_t)H * Q);
    tu_f2d(wv, f.wv, (size_t)C * Q); tu_f2d(dout, f.dout, f.no);
    pa_ctx c = {B, T, C, H, mode == NN_ATTN_SELF, qkv, phi, wb, wv, dout, out};
    pairattn_forward(f.out, f.prob, f.Phi, f.qkv, f.phi, f.phit, f.wb, f.wv, f.wvt, B, T, C, H, mode, f.scr);
    pa_loss(&c);
    ASSERT_CLOSE(f.out, out, f.no, FWD_TOL, "pair attention forward");
    pairattn_backward(f.dqkv, f.dwb, f.dwv, f.dout, f.qkv, f.prob, f.Phi, f.phi, f.phit, f.wv,
                      B, T, C, H, mode, f.scr);
    tu_fd_grad(g, qkv, f.nq, pa_loss, &c, FD_H);
    ASSERT_CLOSE(f.dqkv, g, f.nq, GRAD_TOL, "pair attention d/dqkv");
    tu_fd_grad(g, wb, (size_t)H * Q, pa_loss, &c, FD_H);
    ASSERT_CLOSE(f.dwb, g, (size_t)H * Q, GRAD_TOL, "pair attention d/dwb");
    tu_fd_grad(g, wv, (size_t)C * Q, pa_loss, &c, FD_H);
    ASSERT_CLOSE(f.dwv, g, (size_t)C * Q, GRAD_TOL, "pair attention d/dwv");
    if (mode == NN_ATTN_SELF) /* a token attending only to itself: the scores do not matter */
        for (int i = 0; i < H * Q; i++) ASSERT_EXACT(f.dwb[i], 0.f);
    else { /* the score term is live: its gradient is not negligible */
        double mx = 0;
        for (int i = 0; i < H * Q; i++) mx = fmax(mx, fabs(f.dwb[i]));
        assert_true(mx > 1e-2);
    }
    pa_free(&f);
    free(qkv); free(phi); free(wb); free(wv); free(dout); free(out); free(g);
}

static void test_layer_joint_tiny(void **s) { (void)s; check_layer(2, 5, 12, 3, NN_ATTN_JOINT, 21); }
static void test_layer_self_tiny(void **s) { (void)s; check_layer(2, 5, 12, 3, NN_ATTN_SELF, 22); }
/* T = 24, hd = 16: nn.c's AVX-512 attention kernel, with the bias and dP terms */
static void test_layer_joint_reference_patch(void **s) { (void)s; check_layer(1, 24, 32, 2, NN_ATTN_JOINT, 23); }
static void test_layer_self_reference_patch(void **s) { (void)s; check_layer(1, 24, 32, 2, NN_ATTN_SELF, 24); }

/* ---- determinism ------------------------------------------------------------------ */
/* forward + backward at the model's shape on gemm path isa into out/dqkv/dwb/dwv */
static void run_path(gemm_isa isa, pa_fix *f, nn_attn_mode mode)
{
    gemm_isa before = gemm_set_isa(isa);
    memset(f->dwb, 0, sizeof(float) * f->H * Q);
    memset(f->dwv, 0, sizeof(float) * f->C * Q);
    pairattn_forward(f->out, f->prob, f->Phi, f->qkv, f->phi, f->phit, f->wb, f->wv, f->wvt,
                     f->B, f->T, f->C, f->H, mode, f->scr);
    pairattn_backward(f->dqkv, f->dwb, f->dwv, f->dout, f->qkv, f->prob, f->Phi, f->phi, f->phit,
                      f->wv, f->B, f->T, f->C, f->H, mode, f->scr);
    gemm_set_isa(before);
}

static void check_paths(nn_attn_mode mode)
{
    pa_fix a, b;
    pa_make(&a, 3, 24, 64, 4, 31);
    pa_make(&b, 3, 24, 64, 4, 31);
    run_path(GEMM_SCALAR, &a, mode);
    for (int isa = GEMM_AVX2; isa <= GEMM_AVX512; isa++) {
        if (!gemm_isa_available((gemm_isa)isa)) {
            print_message("gemm path %d not on this CPU: skipped\n", isa);
            continue;
        }
        run_path((gemm_isa)isa, &b, mode);
        same_bits(b.out, a.out, a.no, "pair forward across gemm paths");
        if (mode == NN_ATTN_JOINT)
            same_bits(b.prob, a.prob, (size_t)3 * 4 * 24 * 24, "pair probabilities across gemm paths");
        same_bits(b.Phi, a.Phi, (size_t)3 * 4 * 24 * Q, "pair mixes across gemm paths");
        same_bits(b.dqkv, a.dqkv, a.nq, "pair d/dqkv across gemm paths");
        same_bits(b.dwb, a.dwb, (size_t)4 * Q, "pair d/dwb across gemm paths");
        same_bits(b.dwv, a.dwv, (size_t)64 * Q, "pair d/dwv across gemm paths");
    }
    pa_free(&a); pa_free(&b);
}
static void test_bit_identical_on_every_gemm_path_joint(void **s) { (void)s; check_paths(NN_ATTN_JOINT); }
static void test_bit_identical_on_every_gemm_path_self(void **s) { (void)s; check_paths(NN_ATTN_SELF); }

/* The fused forms give the bits of the unfused sequence. */
static void check_fused(int B, int T, int C, int H, nn_attn_mode mode, unsigned seed)
{
    pa_fix f;
    pa_make(&f, B, T, C, H, seed);
    const int N = B * T, C3 = 3 * C;
    float *in = malloc(sizeof(float) * N * C), *w = malloc(sizeof(float) * C3 * C), *bias = malloc(sizeof(float) * C3);
    float *wt = malloc(sizeof(float) * C3 * C), *pw = malloc(sizeof(float) * C * C),
          *dy = malloc(sizeof(float) * N * C);
    float *q1 = malloc(sizeof(float) * N * C3), *q2 = malloc(sizeof(float) * N * C3);
    float *o1 = malloc(sizeof(float) * N * C), *o2 = malloc(sizeof(float) * N * C);
    float *p1 = malloc(sizeof(float) * B * H * T * T), *p2 = malloc(sizeof(float) * B * H * T * T);
    float *F1 = malloc(sizeof(float) * B * H * T * Q), *F2 = malloc(sizeof(float) * B * H * T * Q);
    float *g1 = malloc(sizeof(float) * N * C3), *g2 = malloc(sizeof(float) * N * C3);
    float *da1 = malloc(sizeof(float) * N * C), *da2 = malloc(sizeof(float) * N * C);
    float *dpw1 = calloc((size_t)C * C, sizeof(float)), *dpw2 = calloc((size_t)C * C, sizeof(float));
    float *dpb1 = calloc((size_t)C, sizeof(float)), *dpb2 = calloc((size_t)C, sizeof(float));
    float *dwb1 = calloc((size_t)H * Q, sizeof(float)), *dwb2 = calloc((size_t)H * Q, sizeof(float));
    float *dwv1 = calloc((size_t)C * Q, sizeof(float)), *dwv2 = calloc((size_t)C * Q, sizeof(float));
    unsigned st = seed + 100;
    tu_fill(in, (size_t)N * C, 1.f, &st); tu_fill(w, (size_t)C3 * C, 0.5f, &st); tu_fill(bias, C3, 0.3f, &st);
    tu_fill(pw, (size_t)C * C, 0.5f, &st); tu_fill(dy, (size_t)N * C, 1.f, &st);
    gemm_transpose(f.wvt, f.wv, C, Q);
    for (size_t i = 0; i < (size_t)N * C3; i++) q1[i] = 1234.5f;
    pairattn_linear_forward(q1, o1, p1, F1, in, w, bias, f.phi, f.phit, f.wb, f.wvt, B, T, C, H, mode, wt, f.scr);
    nn_linear_forward(q2, in, w, bias, N, C, C3, wt);
    pairattn_forward(o2, p2, F2, q2, f.phi, f.phit, f.wb, NULL, f.wvt, B, T, C, H, mode, f.scr);
    if (mode == NN_ATTN_JOINT) same_bits(q1, q2, (size_t)N * C3, "fused qkv");
    else /* self-only attention: the v columns only, q and k not written (nn.h) */
        for (int r = 0; r < N; r++) {
            same_bits(q1 + (size_t)r * C3 + 2 * C, q2 + (size_t)r * C3 + 2 * C, C, "fused qkv (v)");
            for (int j = 0; j < 2 * C; j++)
                if (q1[(size_t)r * C3 + j] != 1234.5f)
                    fail_msg("fused qkv row %d column %d (q or k) was written", r, j);
        }
    same_bits(o1, o2, (size_t)N * C, "fused pair attention out");
    same_bits(F1, F2, (size_t)B * H * T * Q, "fused pair mixes");
    pairattn_linear_backward(g1, da1, dpw1, dpb1, dwb1, dwv1, dy, o1, pw, q1, p1, F1, f.phi, f.phit, f.wv,
                             B, T, C, H, mode, f.scr);
    nn_linear_backward(da2, dpw2, dpb2, dy, o2, pw, N, C, C);
    pairattn_backward(g2, dwb2, dwv2, da2, q2, p2, F2, f.phi, f.phit, f.wv, B, T, C, H, mode, f.scr);
    same_bits(da1, da2, (size_t)N * C, "fused d/datt");
    same_bits(g1, g2, (size_t)N * C3, "fused d/dqkv");
    same_bits(dpw1, dpw2, (size_t)C * C, "fused d/dproj");
    same_bits(dpb1, dpb2, (size_t)C, "fused d/dproj bias");
    same_bits(dwb1, dwb2, (size_t)H * Q, "fused d/dwb");
    same_bits(dwv1, dwv2, (size_t)C * Q, "fused d/dwv");
    free(in); free(w); free(bias); free(wt); free(pw); free(dy); free(q1); free(q2); free(o1); free(o2);
    free(p1); free(p2); free(F1); free(F2); free(g1); free(g2); free(da1); free(da2);
    free(dpw1); free(dpw2); free(dpb1); free(dpb2); free(dwb1); free(dwb2); free(dwv1); free(dwv2);
    pa_free(&f);
}
static void test_fused_matches_unfused_joint(void **s) { (void)s; check_fused(3, 24, 64, 4, NN_ATTN_JOINT, 41); }
static void test_fused_matches_unfused_odd(void **s) { (void)s; check_fused(3, 5, 12, 3, NN_ATTN_JOINT, 42); }
static void test_fused_matches_unfused_self(void **s) { (void)s; check_fused(3, 5, 12, 3, NN_ATTN_SELF, 43); }

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_features_by_hand),
        cmocka_unit_test(test_features_match_trigonometry),
        cmocka_unit_test(test_geometry_standardises_both_layouts),
        cmocka_unit_test(test_geometry_naive_every_path_reference),
        cmocka_unit_test(test_geometry_naive_every_path_ragged),
        cmocka_unit_test(test_layer_joint_tiny),
        cmocka_unit_test(test_layer_self_tiny),
        cmocka_unit_test(test_layer_joint_reference_patch),
        cmocka_unit_test(test_layer_self_reference_patch),
        cmocka_unit_test(test_bit_identical_on_every_gemm_path_joint),
        cmocka_unit_test(test_bit_identical_on_every_gemm_path_self),
        cmocka_unit_test(test_fused_matches_unfused_joint),
        cmocka_unit_test(test_fused_matches_unfused_odd),
        cmocka_unit_test(test_fused_matches_unfused_self),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
