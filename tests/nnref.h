/* Naive double-precision reference kernels for src/model/nn.c (and, via
 * tests/modelref.h, for the whole model). Written for clarity, not speed:
 * straight loops, exact libm tanh/exp. The gradient tests differentiate these
 * by central finite differences and compare with the float backward kernels. */
#ifndef NNREF_H
#define NNREF_H
#include <math.h>
#include <stdlib.h>
#include <string.h>

static void ref_linear(double *out, const double *in, const double *w, const double *b,
                       int M, int K, int N)
{
    for (int r = 0; r < M; r++)
        for (int n = 0; n < N; n++) {
            double s = b ? b[n] : 0.0;
            for (int k = 0; k < K; k++) s += in[r * K + k] * w[n * K + k];
            out[r * N + n] = s;
        }
}

static void ref_layernorm(double *out, const double *in, const double *g, const double *b,
                          int M, int C)
{
    for (int r = 0; r < M; r++) {
        double mu = 0, var = 0;
        for (int c = 0; c < C; c++) mu += in[r * C + c];
        mu /= C;
        for (int c = 0; c < C; c++) var += (in[r * C + c] - mu) * (in[r * C + c] - mu);
        var /= C;
        double rs = 1.0 / sqrt(var + 1e-5);
        for (int c = 0; c < C; c++) out[r * C + c] = (in[r * C + c] - mu) * rs * g[c] + b[c];
    }
}

static void ref_gelu(double *out, const double *in, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        double x = in[i];
        out[i] = 0.5 * x * (1.0 + tanh(sqrt(2.0 / M_PI) * (x + 0.044715 * x * x * x)));
    }
}

/* mode 0 joint, 1 self (each token attends only to itself). */
static void ref_attention(double *out, const double *qkv, int B, int T, int C, int H, int mode)
{
    int hd = C / H, C3 = 3 * C;
    double *s = malloc(sizeof(double) * T);
    for (int b = 0; b < B; b++)
        for (int h = 0; h < H; h++)
            for (int i = 0; i < T; i++) {
                const double *q = qkv + (size_t)(b * T + i) * C3 + h * hd;
                double mx = -INFINITY;
                for (int j = 0; j < T; j++) {
                    const double *k = qkv + (size_t)(b * T + j) * C3 + C + h * hd;
                    double d = 0;
                    for (int e = 0; e < hd; e++) d += q[e] * k[e];
                    s[j] = (mode == 1 && j != i) ? -INFINITY : d / sqrt((double)hd);
                    if (s[j] > mx) mx = s[j];
                }
                double z = 0;
                for (int j = 0; j < T; j++) { s[j] = exp(s[j] - mx); z += s[j]; }
                for (int e = 0; e < hd; e++) {
                    double o = 0;
                    for (int j = 0; j < T; j++) o += s[j] / z * qkv[(size_t)(b * T + j) * C3 + 2 * C + h * hd + e];
                    out[(size_t)(b * T + i) * C + h * hd + e] = o;
                }
            }
    free(s);
}

/* ---- helpers -------------------------------------------------------------- */
static void tu_f2d(double *d, const float *f, size_t n) { for (size_t i = 0; i < n; i++) d[i] = f[i]; }

static double tu_dot(const double *a, const double *b, size_t n)
{
    double s = 0;
    for (size_t i = 0; i < n; i++) s += a[i] * b[i];
    return s;
}

/* Deterministic pseudo-random fill in [-a, a] (xorshift; tests only). */
static void tu_fill(float *x, size_t n, float a, unsigned *state)
{
    for (size_t i = 0; i < n; i++) {
        unsigned s = *state;
        s ^= s << 13; s ^= s >> 17; s ^= s << 5;
        *state = s;
        x[i] = a * (2.0f * (float)(s >> 8) / 16777216.0f - 1.0f);
    }
}

typedef double (*tu_loss_fn)(void *ctx);

/* Central finite differences of fn w.r.t. x[0..n) (perturbed in place, restored). */
static void tu_fd_grad(double *g, double *x, size_t n, tu_loss_fn fn, void *ctx, double h)
{
    for (size_t i = 0; i < n; i++) {
        double x0 = x[i];
        x[i] = x0 + h; double lp = fn(ctx);
        x[i] = x0 - h; double lm = fn(ctx);
        x[i] = x0;
        g[i] = (lp - lm) / (2 * h);
    }
}

/* max |a - b| relative to max(1, max|b|); prints the worst entry on failure. */
static double tu_maxrel(const float *a, const double *b, size_t n, size_t *worst)
{
    double scale = 1.0, m = 0;
    for (size_t i = 0; i < n; i++) if (fabs(b[i]) > scale) scale = fabs(b[i]);
    *worst = 0;
    for (size_t i = 0; i < n; i++) {
        double e = fabs((double)a[i] - b[i]) / scale;
        if (e > m) { m = e; *worst = i; }
    }
    return m;
}

#define ASSERT_GRAD(analytic, numeric, n, tol, what) do { \
    size_t w_; double e_ = tu_maxrel((analytic), (numeric), (n), &w_); \
    if (!(e_ <= (tol))) { \
        print_error("%s: max rel error %.3g at %zu (analytic %.9g, numeric %.9g)\n", \
                    (what), e_, w_, (double)(analytic)[w_], (numeric)[w_]); \
        fail(); } } while (0)
#endif
