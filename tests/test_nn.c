/* Tests for src/nn.c: every float kernel against its naive double reference
 * (tests/nnref.h), forward values and backward gradients (central finite
 * differences in double precision). Odd sizes exercise the scalar tails. */
#include "testutil.h"
#include "nnref.h"
#include "nn.h"

#define FD_H 1e-5
#define GRAD_TOL 2e-4
#define FWD_TOL 2e-5

/* ---- exp -------------------------------------------------------------------- */
static void test_expf_matches_libm(void **s)
{
    (void)s;
    enum { n = 4001 };
    static float x[n], y[n];
    for (int i = 0; i < n; i++) x[i] = -87.0f + 175.0f * (float)i / (n - 1);
    nn_expf(y, x, n);
    double worst = 0;
    for (int i = 0; i < n; i++) {
        double e = fabs(y[i] - exp((double)x[i])) / exp((double)x[i]);
        if (e > worst) worst = e;
    }
    ASSERT_NEAR(worst, 0.0, 4e-7);
}

/* ---- linear ------------------------------------------------------------------ */
typedef struct { int M, K, N; double *in, *w, *b, *dout, *out; } lin_ctx;
static double lin_loss(void *p)
{
    lin_ctx *c = p;
    ref_linear(c->out, c->in, c->w, c->b, c->M, c->K, c->N);
    return tu_dot(c->out, c->dout, (size_t)c->M * c->N);
}

static void test_linear_forward_and_gradients(void **s)
{
    (void)s;
    enum { M = 5, K = 7, N = 6 };
    unsigned st = 1;
    float in[M * K], w[N * K], b[N], dout[M * N], out[M * N], din[M * K], dw[N * K], db[N];
    tu_fill(in, M * K, 1, &st); tu_fill(w, N * K, 1, &st); tu_fill(b, N, 1, &st); tu_fill(dout, M * N, 1, &st);
    double din_d[M * K], w_d[N * K], b_d[N], dout_d[M * N], out_d[M * N], g[N * K];
    tu_f2d(din_d, in, M * K); tu_f2d(w_d, w, N * K); tu_f2d(b_d, b, N); tu_f2d(dout_d, dout, M * N);
    lin_ctx c = {M, K, N, din_d, w_d, b_d, dout_d, out_d};
    nn_linear_forward(out, in, w, b, M, K, N);
    lin_loss(&c);
    ASSERT_GRAD(out, out_d, M * N, FWD_TOL, "linear forward");
    memset(dw, 0, sizeof dw); memset(db, 0, sizeof db);
    nn_linear_backward(din, dw, db, dout, in, w, M, K, N);
    tu_fd_grad(g, din_d, M * K, lin_loss, &c, FD_H);
    ASSERT_GRAD(din, g, M * K, GRAD_TOL, "linear d/din");
    tu_fd_grad(g, w_d, N * K, lin_loss, &c, FD_H);
    ASSERT_GRAD(dw, g, N * K, GRAD_TOL, "linear d/dw");
    tu_fd_grad(g, b_d, N, lin_loss, &c, FD_H);
    ASSERT_GRAD(db, g, N, GRAD_TOL, "linear d/db");
}

static void test_linear_backward_accumulates_weight_grads(void **s)
{
    (void)s;
    enum { M = 3, K = 4, N = 5 };
    unsigned st = 2;
    float in[M * K], w[N * K], dout[M * N], dw1[N * K], dw2[N * K], db1[N], db2[N];
    tu_fill(in, M * K, 1, &st); tu_fill(w, N * K, 1, &st); tu_fill(dout, M * N, 1, &st);
    memset(dw1, 0, sizeof dw1); memset(db1, 0, sizeof db1);
    nn_linear_backward(NULL, dw1, db1, dout, in, w, M, K, N);
    for (int i = 0; i < N * K; i++) dw2[i] = 1.0f;
    for (int i = 0; i < N; i++) db2[i] = 1.0f;
    nn_linear_backward(NULL, dw2, db2, dout, in, w, M, K, N);
    for (int i = 0; i < N * K; i++) ASSERT_NEAR(dw2[i], dw1[i] + 1.0f, 1e-6);
    for (int i = 0; i < N; i++) ASSERT_NEAR(db2[i], db1[i] + 1.0f, 1e-6);
}

/* ---- layer norm ---------------------------------------------------------------- */
typedef struct { int M, C; double *in, *g, *b, *dout, *out; } ln_ctx;
static double ln_loss(void *p)
{
    ln_ctx *c = p;
    ref_layernorm(c->out, c->in, c->g, c->b, c->M, c->C);
    return tu_dot(c->out, c->dout, (size_t)c->M * c->C);
}

static void test_layernorm_forward_and_gradients(void **s)
{
    (void)s;
    enum { M = 4, C = 10 };
    unsigned st = 3;
    float in[M * C], g[C], b[C], dout[M * C], out[M * C], mean[M], rstd[M], din[M * C], dg[C], db[C];
    tu_fill(in, M * C, 2, &st); tu_fill(g, C, 1, &st); tu_fill(b, C, 1, &st); tu_fill(dout, M * C, 1, &st);
    double in_d[M * C], g_d[C], b_d[C], dout_d[M * C], out_d[M * C], gr[M * C];
    tu_f2d(in_d, in, M * C); tu_f2d(g_d, g, C); tu_f2d(b_d, b, C); tu_f2d(dout_d, dout, M * C);
    ln_ctx c = {M, C, in_d, g_d, b_d, dout_d, out_d};
    nn_layernorm_forward(out, mean, rstd, in, g, b, M, C);
    ln_loss(&c);
    ASSERT_GRAD(out, out_d, M * C, FWD_TOL, "layernorm forward");
    for (int i = 0; i < M * C; i++) din[i] = 0.5f; /* backward adds to what is there */
    memset(dg, 0, sizeof dg); memset(db, 0, sizeof db);
    nn_layernorm_backward(din, dg, db, dout, in, mean, rstd, g, M, C);
    for (int i = 0; i < M * C; i++) din[i] -= 0.5f;
    tu_fd_grad(gr, in_d, M * C, ln_loss, &c, FD_H);
    ASSERT_GRAD(din, gr, M * C, GRAD_TOL, "layernorm d/din");
    tu_fd_grad(gr, g_d, C, ln_loss, &c, FD_H);
    ASSERT_GRAD(dg, gr, C, GRAD_TOL, "layernorm d/dg");
    tu_fd_grad(gr, b_d, C, ln_loss, &c, FD_H);
    ASSERT_GRAD(db, gr, C, GRAD_TOL, "layernorm d/db");
}

/* ---- GELU ---------------------------------------------------------------------- */
typedef struct { size_t n; double *in, *dout, *out; } ge_ctx;
static double ge_loss(void *p)
{
    ge_ctx *c = p;
    ref_gelu(c->out, c->in, c->n);
    return tu_dot(c->out, c->dout, c->n);
}

static void test_gelu_forward_and_gradient(void **s)
{
    (void)s;
    enum { n = 203 };
    unsigned st = 4;
    float in[n], dout[n], out[n], din[n];
    tu_fill(in, n, 6, &st); tu_fill(dout, n, 1, &st);
    in[0] = 0.0f; in[1] = -40.0f; in[2] = 40.0f; /* centre and saturated tails */
    double in_d[n], dout_d[n], out_d[n], g[n];
    tu_f2d(in_d, in, n); tu_f2d(dout_d, dout, n);
    ge_ctx c = {n, in_d, dout_d, out_d};
    nn_gelu_forward(out, in, n);
    ge_loss(&c);
    ASSERT_GRAD(out, out_d, n, FWD_TOL, "gelu forward");
    nn_gelu_backward(din, dout, in, n);
    tu_fd_grad(g, in_d, n, ge_loss, &c, FD_H);
    ASSERT_GRAD(din, g, n, GRAD_TOL, "gelu d/din");
}

/* The saved-sigmoid forward/backward give exactly the plain kernels' values. */
static void test_gelu_saved_path_matches_plain_path(void **s)
{
    (void)s;
    enum { n = 37 };
    unsigned st = 12;
    float in[n], dout[n], o1[n], o2[n], sig[n], d1[n], d2[n];
    tu_fill(in, n, 5, &st); tu_fill(dout, n, 1, &st);
    nn_gelu_forward(o1, in, n);
    nn_gelu_forward_save(o2, sig, in, n);
    nn_gelu_backward(d1, dout, in, n);
    nn_gelu_backward_saved(d2, dout, in, sig, n);
    for (int i = 0; i < n; i++) { ASSERT_EXACT(o2[i], o1[i]); ASSERT_EXACT(d2[i], d1[i]); }
}

/* The fused bias passes give exactly the values of the unfused kernels. */
static void test_fused_bias_passes_match_unfused(void **s)
{
    (void)s;
    enum { M = 3, N = 21 };
    unsigned st = 13;
    float h[M * N], h2[M * N], b[N], x[M * N], sig[M * N], sig2[M * N], o1[M * N], o2[M * N];
    tu_fill(h, M * N, 3, &st); tu_fill(b, N, 1, &st); tu_fill(x, M * N, 1, &st);
    for (int r = 0; r < M; r++)
        for (int c = 0; c < N; c++) h2[r * N + c] = h[r * N + c] + b[c];
    nn_gelu_forward_save(o2, sig2, h2, M * N);
    nn_bias_gelu_forward_save(h, sig, o1, b, M, N);
    for (int i = 0; i < M * N; i++) { ASSERT_EXACT(h[i], h2[i]); ASSERT_EXACT(sig[i], sig2[i]); ASSERT_EXACT(o1[i], o2[i]); }
    nn_bias_residual_forward(o1, h, b, x, M, N);
    for (int r = 0; r < M; r++)
        for (int c = 0; c < N; c++) ASSERT_EXACT(o1[r * N + c], (h[r * N + c] + b[c]) + x[r * N + c]);
}

/* ---- residual ---------------------------------------------------------------------- */
static void test_residual_forward_and_backward(void **s)
{
    (void)s;
    float a[7] = {1, 2, 3, 4, 5, 6, 7}, b[7] = {7, 6, 5, 4, 3, 2, 1}, o[7], acc[7] = {0};
    nn_residual_forward(o, a, b, 7);
    for (int i = 0; i < 7; i++) ASSERT_EXACT(o[i], 8.0);
    nn_residual_backward(acc, a, 7);
    nn_residual_backward(acc, b, 7);
    for (int i = 0; i < 7; i++) ASSERT_EXACT(acc[i], 8.0);
}

/* ---- attention ------------------------------------------------------------------------ */
typedef struct { int B, T, C, H, mode; double *qkv, *dout, *out; } at_ctx;
static double at_loss(void *p)
{
    at_ctx *c = p;
    ref_attention(c->out, c->qkv, c->B, c->T, c->C, c->H, c->mode);
    return tu_dot(c->out, c->dout, (size_t)c->B * c->T * c->C);
}

static void check_attention(int B, int T, int C, int H, nn_attn_mode mode, unsigned seed)
{
    size_t nq = (size_t)B * T * 3 * C, no = (size_t)B * T * C;
    float *qkv = malloc(sizeof(float) * nq), *dqkv = malloc(sizeof(float) * nq);
    float *dout = malloc(sizeof(float) * no), *out = malloc(sizeof(float) * no);
    float *prob = malloc(sizeof(float) * B * H * T * T);
    float *scr = malloc(sizeof(float) * nn_attention_scratch_len(T, C, H));
    double *qkv_d = malloc(sizeof(double) * nq), *g = malloc(sizeof(double) * nq);
    double *dout_d = malloc(sizeof(double) * no), *out_d = malloc(sizeof(double) * no);
    unsigned st = seed;
    tu_fill(qkv, nq, 1.5f, &st); tu_fill(dout, no, 1, &st);
    tu_f2d(qkv_d, qkv, nq); tu_f2d(dout_d, dout, no);
    at_ctx c = {B, T, C, H, mode == NN_ATTN_SELF, qkv_d, dout_d, out_d};
    nn_attention_forward(out, prob, qkv, B, T, C, H, mode, scr);
    at_loss(&c);
    ASSERT_GRAD(out, out_d, no, FWD_TOL, "attention forward");
    nn_attention_backward(dqkv, dout, qkv, prob, B, T, C, H, mode, scr);
    tu_fd_grad(g, qkv_d, nq, at_loss, &c, FD_H);
    ASSERT_GRAD(dqkv, g, nq, GRAD_TOL, "attention d/dqkv");
    free(qkv); free(dqkv); free(dout); free(out); free(prob); free(scr);
    free(qkv_d); free(g); free(dout_d); free(out_d);
}

static void test_attention_joint_odd_sizes(void **s) { (void)s; check_attention(2, 5, 12, 2, NN_ATTN_JOINT, 5); }
static void test_attention_joint_patch_of_24(void **s) { (void)s; check_attention(1, 24, 16, 2, NN_ATTN_JOINT, 6); }
static void test_attention_joint_reference_head_width(void **s) { (void)s; check_attention(2, 24, 32, 2, NN_ATTN_JOINT, 9); }
static void test_attention_self_gradients(void **s) { (void)s; check_attention(2, 5, 12, 3, NN_ATTN_SELF, 7); }

static void test_attention_self_ignores_other_tokens(void **s)
{
    (void)s;
    enum { B = 1, T = 6, C = 8, H = 2 };
    float qkv[B * T * 3 * C], o1[B * T * C], o2[B * T * C], scr[64];
    unsigned st = 8;
    tu_fill(qkv, sizeof qkv / sizeof *qkv, 1, &st);
    nn_attention_forward(o1, NULL, qkv, B, T, C, H, NN_ATTN_SELF, scr);
    for (int j = 1; j < T; j++)
        for (int c = 0; c < 3 * C; c++) qkv[j * 3 * C + c] += 3.0f;
    nn_attention_forward(o2, NULL, qkv, B, T, C, H, NN_ATTN_SELF, scr);
    for (int c = 0; c < C; c++) ASSERT_EXACT(o2[c], o1[c]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_expf_matches_libm),
        cmocka_unit_test(test_linear_forward_and_gradients),
        cmocka_unit_test(test_linear_backward_accumulates_weight_grads),
        cmocka_unit_test(test_layernorm_forward_and_gradients),
        cmocka_unit_test(test_gelu_forward_and_gradient),
        cmocka_unit_test(test_residual_forward_and_backward),
        cmocka_unit_test(test_fused_bias_passes_match_unfused),
        cmocka_unit_test(test_attention_joint_odd_sizes),
        cmocka_unit_test(test_attention_joint_patch_of_24),
        cmocka_unit_test(test_attention_joint_reference_head_width),
        cmocka_unit_test(test_attention_self_gradients),
        cmocka_unit_test(test_gelu_saved_path_matches_plain_path),
        cmocka_unit_test(test_attention_self_ignores_other_tokens),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
