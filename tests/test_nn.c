/* Tests for src/model/nn.c: every float kernel against its naive double reference
 * (tests/nnref.h), forward values and backward gradients (central finite
 * differences in double precision). Odd sizes exercise the scalar tails. */
#include "testutil.h"
#include "nnref.h"
#include "nn.h"
#include "gemm.h"

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
    float wt[K * N];
    nn_linear_forward(out, in, w, b, M, K, N, wt);
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

/* w == NULL: wt already holds w^T and is used as it is (what the model does
 * when it transposes once for several forwards); the same bits as passing w.
 * wt is filled with the transpose of a different matrix to show it is read. */
static void test_linear_forward_pretransposed_weights(void **s)
{
    (void)s;
    enum { M = 9, K = 16, N = 24 };
    unsigned st = 3;
    float in[M * K], w[N * K], w2[N * K], b[N], out1[M * N], out2[M * N], wt[K * N];
    tu_fill(in, M * K, 1, &st); tu_fill(w, N * K, 1, &st); tu_fill(w2, N * K, 1, &st); tu_fill(b, N, 1, &st);
    nn_linear_forward(out1, in, w2, b, M, K, N, wt);
    nn_linear_forward(out2, in, NULL, b, M, K, N, wt); /* wt = w2^T from the call before */
    assert_memory_equal(out1, out2, sizeof out1);
    nn_linear_forward(out1, in, w, b, M, K, N, wt);
    assert_memory_not_equal(out1, out2, sizeof out1);
    nn_linear_forward(out2, in, NULL, b, M, K, N, wt);
    assert_memory_equal(out1, out2, sizeof out1);
}

/* The bias gradient is one sum per column over the rows in order, added to
 * what db held (what lets a batch run in passes): bit for bit the scalar loop.
 * 150 columns: full 64-column blocks, an 8-column block and a scalar tail. */
/* db += column sums, each db[c] one chain of additions over the rows in
 * order (the naive loop), at a ragged shape and at the model's pass shapes. */
static void check_bias_grad(int M, int K, int N, unsigned st)
{
    float *in = malloc(sizeof(float) * M * K), *w = malloc(sizeof(float) * N * K),
          *dout = malloc(sizeof(float) * M * N), *dw = calloc((size_t)N * K, sizeof(float)),
          *db = malloc(sizeof(float) * N), *want = malloc(sizeof(float) * N);
    tu_fill(in, (size_t)M * K, 1, &st);
    tu_fill(w, (size_t)N * K, 1, &st);
    tu_fill(dout, (size_t)M * N, 3, &st);
    tu_fill(db, N, 1, &st);
    for (int c = 0; c < N; c++) {
        float e = db[c];
        for (int r = 0; r < M; r++) e += dout[r * N + c];
        want[c] = e;
    }
    nn_linear_backward(NULL, dw, db, dout, in, w, M, K, N);
    for (int c = 0; c < N; c++)
        if (memcmp(&db[c], &want[c], sizeof(float)) != 0) {
            print_error("db[%d] = %.17g, row-ordered sum %.17g (M %d, N %d)\n", c, (double)db[c], (double)want[c], M,
                        N);
            fail();
        }
    free(in); free(w); free(dout); free(dw); free(db); free(want);
}

static void test_linear_backward_bias_grad_is_row_ordered_sum(void **s)
{
    (void)s;
    check_bias_grad(11, 3, 150, 4);
    check_bias_grad(96, 4, 64, 5);
    check_bias_grad(96, 4, 256, 6);
    check_bias_grad(96, 4, 21, 7);
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

/* Whole calls (four rows at a time where C is a multiple of 8) against one
 * row per call, bit for bit: mean, 1/sd, output, input gradient and the
 * accumulated dg, db, at the model's width, a narrow one and one with a
 * tail. */
static void check_layernorm_rows(int M, int C, unsigned st)
{
    const size_t n = (size_t)M * C;
    float *x = malloc(sizeof(float) * n), *dy = malloc(sizeof(float) * n), *g = malloc(sizeof(float) * C),
          *b = malloc(sizeof(float) * C), *y1 = malloc(sizeof(float) * n), *y2 = malloc(sizeof(float) * n),
          *dx1 = malloc(sizeof(float) * n), *dx2 = malloc(sizeof(float) * n), *mu1 = malloc(sizeof(float) * M),
          *mu2 = malloc(sizeof(float) * M), *rs1 = malloc(sizeof(float) * M), *rs2 = malloc(sizeof(float) * M),
          *dg1 = malloc(sizeof(float) * C), *dg2 = malloc(sizeof(float) * C), *db1 = malloc(sizeof(float) * C),
          *db2 = malloc(sizeof(float) * C);
    tu_fill(x, n, 3, &st); tu_fill(dy, n, 1, &st); tu_fill(g, C, 1, &st); tu_fill(b, C, 1, &st);
    tu_fill(dx1, n, 1, &st); memcpy(dx2, dx1, sizeof(float) * n);
    tu_fill(dg1, C, 1, &st); memcpy(dg2, dg1, sizeof(float) * C);
    tu_fill(db1, C, 1, &st); memcpy(db2, db1, sizeof(float) * C);
    nn_layernorm_forward(y1, mu1, rs1, x, g, b, M, C);
    for (int r = 0; r < M; r++)
        nn_layernorm_forward(y2 + (size_t)r * C, mu2 + r, rs2 + r, x + (size_t)r * C, g, b, 1, C);
    nn_layernorm_backward(dx1, dg1, db1, dy, x, mu1, rs1, g, M, C);
    for (int r = 0; r < M; r++)
        nn_layernorm_backward(dx2 + (size_t)r * C, dg2, db2, dy + (size_t)r * C, x + (size_t)r * C, mu2 + r,
                              rs2 + r, g, 1, C);
    for (int r = 0; r < M; r++) { ASSERT_EXACT(mu1[r], mu2[r]); ASSERT_EXACT(rs1[r], rs2[r]); }
    for (size_t i = 0; i < n; i++) { ASSERT_EXACT(y1[i], y2[i]); ASSERT_EXACT(dx1[i], dx2[i]); }
    for (int c = 0; c < C; c++) { ASSERT_EXACT(dg1[c], dg2[c]); ASSERT_EXACT(db1[c], db2[c]); }
    free(x); free(dy); free(g); free(b); free(y1); free(y2); free(dx1); free(dx2); free(mu1); free(mu2);
    free(rs1); free(rs2); free(dg1); free(dg2); free(db1); free(db2);
}

static void test_layernorm_four_rows_match_one_row(void **s)
{
    (void)s;
    check_layernorm_rows(11, 64, 41);
    check_layernorm_rows(9, 8, 42);
    check_layernorm_rows(7, 20, 43);
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
    for (int i = 0; i < M * N; i++) {
        ASSERT_EXACT(h[i], h2[i]);
        ASSERT_EXACT(sig[i], sig2[i]);
        ASSERT_EXACT(o1[i], o2[i]);
    }
    nn_bias_residual_forward(o1, h, b, x, M, N);
    for (int r = 0; r < M; r++)
        for (int c = 0; c < N; c++) ASSERT_EXACT(o1[r * N + c], (h[r * N + c] + b[c]) + x[r * N + c]);
}

/* ---- fused linear layers: bit-identical to the unfused sequences ---------------- */
/* M = 13 rows gives two full strips and a short one; N, K not multiples of 16. */
enum { FM = 13, FK = 19, FN = 37 };
typedef struct { float in[FM * FK], w[FN * FK], b[FN], x[FM * FN], g[FN], beta[FN], wt[FK * FN]; } fused_in;
static void fused_fill(fused_in *f, unsigned seed)
{
    tu_fill(f->in, FM * FK, 1, &seed); tu_fill(f->w, FN * FK, 1, &seed); tu_fill(f->b, FN, 1, &seed);
    tu_fill(f->x, FM * FN, 2, &seed); tu_fill(f->g, FN, 1, &seed); tu_fill(f->beta, FN, 1, &seed);
}
static void same_bits(const float *a, const float *b, size_t n, const char *what)
{
    for (size_t i = 0; i < n; i++)
        if (memcmp(a + i, b + i, sizeof(float)) != 0) {
            print_error("%s[%zu]: fused %.17g, unfused %.17g\n", what, i, (double)a[i], (double)b[i]);
            fail();
        }
}

/* The fused bias + GELU (16-lane on the AVX-512 path, four vectors of chains
 * interleaved) against bias, then the one-vector-at-a-time GELU, on every
 * gemm path, at widths with and without a tail; values reach both clamps of
 * the exponential. */
static void test_fused_bias_gelu_interleaved_matches_unfused(void **s)
{
    (void)s;
    enum { M = 6, NMAX = 256 };
    const int widths[] = {21, 64, 100, 256};
    static float h[M * NMAX], h2[M * NMAX], b[NMAX], sig[M * NMAX], sig2[M * NMAX], o1[M * NMAX], o2[M * NMAX];
    for (int isa = GEMM_SCALAR; isa <= GEMM_AVX512; isa++) {
        if (!gemm_isa_available((gemm_isa)isa)) continue;
        gemm_isa before = gemm_set_isa((gemm_isa)isa);
        for (size_t w = 0; w < sizeof widths / sizeof *widths; w++) {
            const int N = widths[w];
            unsigned st = 31 + (unsigned)N;
            tu_fill(h, (size_t)M * N, 8, &st); tu_fill(b, N, 1, &st);
            h[3] = 120.f; h[N + 5] = -150.f; h[2 * N + 7] = 90.f; h[3 * N + 1] = -1e-30f;
            for (int r = 0; r < M; r++)
                for (int c = 0; c < N; c++) h2[r * N + c] = h[r * N + c] + b[c];
            nn_gelu_forward_save(o2, sig2, h2, (size_t)M * N);
            nn_bias_gelu_forward_save(h, sig, o1, b, M, N);
            for (int i = 0; i < M * N; i++) {
                ASSERT_EXACT(h[i], h2[i]);
                ASSERT_EXACT(sig[i], sig2[i]);
                ASSERT_EXACT(o1[i], o2[i]);
            }
        }
        gemm_set_isa(before);
    }
}

static void test_fused_linear_gelu_matches_unfused(void **s)
{
    (void)s;
    static fused_in f;
    fused_fill(&f, 31);
    float h1[FM * FN], s1[FM * FN], o1[FM * FN], h2[FM * FN], s2[FM * FN], o2[FM * FN];
    nn_linear_bias_gelu_forward(h1, s1, o1, f.in, f.w, f.b, FM, FK, FN, f.wt);
    nn_linear_forward(h2, f.in, f.w, NULL, FM, FK, FN, f.wt);
    nn_bias_gelu_forward_save(h2, s2, o2, f.b, FM, FN);
    same_bits(h1, h2, FM * FN, "h"); same_bits(s1, s2, FM * FN, "sig"); same_bits(o1, o2, FM * FN, "gelu");
}

static void test_fused_linear_residual_layernorm_matches_unfused(void **s)
{
    (void)s;
    static fused_in f;
    fused_fill(&f, 37);
    float y1[FM * FN], l1[FM * FN], m1[FM], rstd1[FM], y2[FM * FN], l2[FM * FN], m2[FM], rstd2[FM];
    nn_linear_bias_residual_forward(y1, f.in, f.w, f.b, f.x, l1, m1, rstd1, f.g, f.beta, FM, FK, FN, f.wt);
    nn_linear_forward(y2, f.in, f.w, NULL, FM, FK, FN, f.wt);
    nn_bias_residual_forward(y2, y2, f.b, f.x, FM, FN);
    nn_layernorm_forward(l2, m2, rstd2, y2, f.g, f.beta, FM, FN);
    same_bits(y1, y2, FM * FN, "residual"); same_bits(l1, l2, FM * FN, "ln");
    same_bits(m1, m2, FM, "mean"); same_bits(rstd1, rstd2, FM, "rstd");
    /* without a layer norm only the residual is written */
    float y3[FM * FN];
    nn_linear_bias_residual_forward(y3, f.in, f.w, f.b, f.x, NULL, NULL, NULL, NULL, NULL, FM, FK, FN, f.wt);
    same_bits(y3, y2, FM * FN, "residual without ln");
}

static void test_fused_linear_backward_gelu_matches_unfused(void **s)
{
    (void)s;
    static fused_in f;
    fused_fill(&f, 41);
    /* layer in[FM x FK] -> out[FM x FN]; h, sig are the GELU's saved input side of `in` */
    float dout[FM * FN], h[FM * FK], sig[FM * FK], gl[FM * FK];
    unsigned st = 43;
    tu_fill(dout, FM * FN, 1, &st); tu_fill(h, FM * FK, 3, &st);
    nn_gelu_forward_save(gl, sig, h, FM * FK);
    float d1[FM * FK], d2[FM * FK], dw1[FN * FK] = {0}, dw2[FN * FK] = {0}, db1[FN] = {0}, db2[FN] = {0};
    nn_linear_backward_gelu(d1, dw1, db1, dout, f.in, f.w, h, sig, FM, FK, FN);
    nn_linear_backward(d2, dw2, db2, dout, f.in, f.w, FM, FK, FN);
    nn_gelu_backward_saved(d2, d2, h, sig, FM * FK);
    same_bits(d1, d2, FM * FK, "dinp"); same_bits(dw1, dw2, FN * FK, "dw"); same_bits(db1, db2, FN, "db");
}

/* The fused qkv product against the unfused one: every column, or under
 * self-only attention the v columns, the q and k columns left as they were
 * (SENTINEL: nn.h, the v columns are all that mode reads). */
#define SENTINEL 1234.5f
static void same_qkv(const float *fused, const float *plain, size_t N, int C, nn_attn_mode mode)
{
    if (mode != NN_ATTN_SELF) { same_bits(fused, plain, N * 3 * C, "qkv"); return; }
    for (size_t r = 0; r < N; r++) {
        same_bits(fused + r * 3 * C + 2 * C, plain + r * 3 * C + 2 * C, C, "qkv (v)");
        for (int j = 0; j < 2 * C; j++)
            if (fused[r * 3 * C + j] != SENTINEL) fail_msg("qkv row %zu column %d (q or k) was written", r, j);
    }
}

/* The qkv backward on the v block alone (self-only attention) gives the bits of
 * the full product: dq and dk are zero there, and every chain they would join
 * is +0 at that point (nn.h). Weight and bias gradients start from nonzero
 * values, as they do after an earlier pass. */
static void check_qkv_backward(const float *dqkv, const float *in, const float *w, int N, int C, nn_attn_mode mode,
                               unsigned seed)
{
    const size_t C3 = 3 * (size_t)C;
    float *d1 = malloc(sizeof(float) * N * C), *d2 = malloc(sizeof(float) * N * C);
    float *w1 = malloc(sizeof(float) * C3 * C), *w2 = malloc(sizeof(float) * C3 * C);
    float *b1 = malloc(sizeof(float) * C3), *b2 = malloc(sizeof(float) * C3);
    tu_fill(w1, C3 * C, 1, &seed); tu_fill(b1, C3, 1, &seed);
    memcpy(w2, w1, sizeof(float) * C3 * C); memcpy(b2, b1, sizeof(float) * C3);
    nn_linear_backward_qkv(d1, w1, b1, dqkv, in, w, N, C, mode);
    nn_linear_backward(d2, w2, b2, dqkv, in, w, N, C, (int)C3);
    same_bits(d1, d2, (size_t)N * C, "qkv backward dinp");
    same_bits(w1, w2, C3 * C, "qkv backward dw");
    same_bits(b1, b2, C3, "qkv backward db");
    free(d1); free(d2); free(w1); free(w2); free(b1); free(b2);
}

/* T = 5 puts patch ends inside the 6-row strips; T = 24 is the reference patch. */
static void check_fused_attention(int B, int T, int C, int H, nn_attn_mode mode, unsigned seed)
{
    const size_t N = (size_t)B * T, C3 = 3 * (size_t)C, np = (size_t)B * H * T * T;
    float *in = malloc(sizeof(float) * N * C), *w = malloc(sizeof(float) * C3 * C), *b = malloc(sizeof(float) * C3);
    float *wp = malloc(sizeof(float) * C * C), *dout = malloc(sizeof(float) * N * C),
          *wt = malloc(sizeof(float) * C3 * C);
    float *scr = malloc(sizeof(float) * nn_attention_scratch_len(T, C, H));
    float *q1 = malloc(sizeof(float) * N * C3), *q2 = malloc(sizeof(float) * N * C3);
    float *o1 = malloc(sizeof(float) * N * C), *o2 = malloc(sizeof(float) * N * C);
    float *p1 = calloc(np, sizeof(float)), *p2 = calloc(np, sizeof(float));
    float *g1 = malloc(sizeof(float) * N * C3), *g2 = malloc(sizeof(float) * N * C3);
    float *da1 = malloc(sizeof(float) * N * C), *da2 = malloc(sizeof(float) * N * C);
    float *dw1 = calloc((size_t)C * C, sizeof(float)), *dw2 = calloc((size_t)C * C, sizeof(float));
    float *db1 = calloc(C, sizeof(float)), *db2 = calloc(C, sizeof(float));
    tu_fill(in, N * C, 1, &seed); tu_fill(w, C3 * C, 1, &seed); tu_fill(b, C3, 1, &seed);
    tu_fill(wp, (size_t)C * C, 1, &seed); tu_fill(dout, N * C, 1, &seed);
    for (size_t i = 0; i < N * C3; i++) q1[i] = SENTINEL;
    nn_linear_attention_forward(q1, o1, p1, in, w, b, B, T, C, H, mode, wt, scr);
    nn_linear_forward(q2, in, w, b, (int)N, C, (int)C3, wt);
    nn_attention_forward(o2, p2, q2, B, T, C, H, mode, scr);
    same_qkv(q1, q2, N, C, mode); same_bits(o1, o2, N * C, "attention out");
    if (mode == NN_ATTN_JOINT) same_bits(p1, p2, np, "probabilities");
    nn_linear_backward_attention(g1, da1, dw1, db1, dout, o1, wp, q1, p1, B, T, C, H, mode, scr);
    nn_linear_backward(da2, dw2, db2, dout, o2, wp, (int)N, C, C);
    nn_attention_backward(g2, da2, q2, p2, B, T, C, H, mode, scr);
    same_bits(g1, g2, N * C3, "dqkv"); same_bits(da1, da2, N * C, "datt");
    same_bits(dw1, dw2, (size_t)C * C, "dw"); same_bits(db1, db2, C, "db");
    check_qkv_backward(g2, in, w, (int)N, C, mode, seed + 7);
    free(in); free(w); free(b); free(wp); free(dout); free(wt); free(scr); free(q1); free(q2);
    free(o1); free(o2); free(p1); free(p2); free(g1); free(g2); free(da1); free(da2);
    free(dw1); free(dw2); free(db1); free(db2);
}

static void test_fused_attention_odd_patch_matches_unfused(void **s)
{
    (void)s;
    check_fused_attention(3, 5, 12, 3, NN_ATTN_JOINT, 51);
}
static void test_fused_attention_reference_patch_matches_unfused(void **s)
{
    (void)s;
    check_fused_attention(2, 24, 64, 4, NN_ATTN_JOINT, 53);
}
static void test_fused_attention_self_mode_matches_unfused(void **s)
{
    (void)s;
    check_fused_attention(3, 5, 12, 3, NN_ATTN_SELF, 57);
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
static void test_attention_joint_reference_head_width(void **s)
{
    (void)s;
    check_attention(2, 24, 32, 2, NN_ATTN_JOINT, 9);
}
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
        cmocka_unit_test(test_linear_forward_pretransposed_weights),
        cmocka_unit_test(test_linear_backward_bias_grad_is_row_ordered_sum),
        cmocka_unit_test(test_linear_backward_accumulates_weight_grads),
        cmocka_unit_test(test_layernorm_forward_and_gradients),
        cmocka_unit_test(test_layernorm_four_rows_match_one_row),
        cmocka_unit_test(test_gelu_forward_and_gradient),
        cmocka_unit_test(test_residual_forward_and_backward),
        cmocka_unit_test(test_fused_bias_passes_match_unfused),
        cmocka_unit_test(test_fused_bias_gelu_interleaved_matches_unfused),
        cmocka_unit_test(test_fused_linear_gelu_matches_unfused),
        cmocka_unit_test(test_fused_linear_residual_layernorm_matches_unfused),
        cmocka_unit_test(test_fused_linear_backward_gelu_matches_unfused),
        cmocka_unit_test(test_fused_attention_odd_patch_matches_unfused),
        cmocka_unit_test(test_fused_attention_reference_patch_matches_unfused),
        cmocka_unit_test(test_fused_attention_self_mode_matches_unfused),
        cmocka_unit_test(test_attention_joint_odd_sizes),
        cmocka_unit_test(test_attention_joint_patch_of_24),
        cmocka_unit_test(test_attention_joint_reference_head_width),
        cmocka_unit_test(test_attention_self_gradients),
        cmocka_unit_test(test_gelu_saved_path_matches_plain_path),
        cmocka_unit_test(test_attention_self_ignores_other_tokens),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
