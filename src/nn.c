/* nn: layer kernels (see nn.h). The GEMMs go to cblas_sgemm; every other loop
 * is written on 4-wide GCC/Clang vector types because -O2 without fast-math
 * will not vectorise float reductions by itself (reassociation is forbidden),
 * and the baseline x86-64 target gives SSE2 only. Reductions use a fixed lane
 * order, so results are deterministic. Paper §4.2; SPEC §8, §10. */
#include "nn.h"
#include <cblas.h>
#include <math.h>
#include <string.h>

typedef float v4f __attribute__((vector_size(16)));
typedef int v4i __attribute__((vector_size(16)));

static inline v4f ld4(const float *p) { v4f v; memcpy(&v, p, sizeof v); return v; }
static inline void st4(float *p, v4f v) { memcpy(p, &v, sizeof v); }
static inline v4f splat(float a) { return (v4f){a, a, a, a}; }
static inline float hsum(v4f v) { return (v[0] + v[1]) + (v[2] + v[3]); }

/* y[0..n) += a * x[0..n) */
static inline void axpy(float *restrict y, float a, const float *restrict x, int n)
{
    int i = 0;
    v4f va = splat(a);
    for (; i + 4 <= n; i += 4) st4(y + i, ld4(y + i) + va * ld4(x + i));
    for (; i < n; i++) y[i] += a * x[i];
}

/* sum of x[0..n), fixed order: 4 lanes then the tail. */
static inline float vsum(const float *x, int n)
{
    v4f acc = splat(0.f);
    int i = 0;
    for (; i + 4 <= n; i += 4) acc += ld4(x + i);
    float s = hsum(acc);
    for (; i < n; i++) s += x[i];
    return s;
}

/* ---- exp ------------------------------------------------------------------ */
/* exp(x) = 2^n * p(r), x = n ln2 + r, |r| <= ln2/2, p = Taylor to degree 7. */
static inline v4f vexp(v4f x)
{
    const v4f lo = splat(-87.0f), hi = splat(88.0f);
    v4i mlo = x < lo, mhi = x > hi;
    x = (v4f)(((v4i)x & ~mlo) | ((v4i)lo & mlo));
    x = (v4f)(((v4i)x & ~mhi) | ((v4i)hi & mhi));
    const v4f shifter = splat(12582912.0f); /* 1.5*2^23: add-subtract rounds to nearest */
    v4f kn = (x * splat(1.44269504088896341f) + shifter) - shifter;
    v4f r = x - kn * splat(0.693145751953125f);      /* ln2 high part (exact kn*hi) */
    r = r - kn * splat(1.428606765330187e-06f);      /* ln2 low part */
    v4f p = splat(1.f / 5040.f);
    p = p * r + splat(1.f / 720.f);
    p = p * r + splat(1.f / 120.f);
    p = p * r + splat(1.f / 24.f);
    p = p * r + splat(1.f / 6.f);
    p = p * r + splat(0.5f);
    p = p * r + splat(1.f);
    p = p * r + splat(1.f);
    v4i n = __builtin_convertvector(kn, v4i);
    v4i bits = (n + 127) << 23;
    return p * (v4f)bits;
}

static inline float sexp(float x)
{
    v4f v = vexp(splat(x));
    return v[0];
}

void nn_expf(float *y, const float *x, size_t n)
{
    size_t i = 0;
    for (; i + 4 <= n; i += 4) st4(y + i, vexp(ld4(x + i)));
    for (; i < n; i++) y[i] = sexp(x[i]);
}

/* ---- linear ----------------------------------------------------------------- */
void nn_linear_forward(float *out, const float *in, const float *w, const float *b,
                       int M, int K, int N)
{
    float beta = 0.f;
    if (b) {
        for (int r = 0; r < M; r++) memcpy(out + (size_t)r * N, b, sizeof(float) * N);
        beta = 1.f;
    }
    cblas_sgemm(CblasRowMajor, CblasNoTrans, CblasTrans, M, N, K, 1.f, in, K, w, K,
                beta, out, N);
}

void nn_linear_backward(float *dinp, float *dw, float *db, const float *dout,
                        const float *in, const float *w, int M, int K, int N)
{
    if (dinp)
        cblas_sgemm(CblasRowMajor, CblasNoTrans, CblasNoTrans, M, K, N, 1.f, dout, N, w, K,
                    0.f, dinp, K);
    cblas_sgemm(CblasRowMajor, CblasTrans, CblasNoTrans, N, K, M, 1.f, dout, N, in, K,
                1.f, dw, K);
    if (db)
        for (int r = 0; r < M; r++) axpy(db, 1.f, dout + (size_t)r * N, N);
}

/* ---- layer norm ---------------------------------------------------------------- */
#define LN_EPS 1e-5f

void nn_layernorm_forward(float *out, float *mean, float *rstd, const float *in,
                          const float *g, const float *b, int M, int C)
{
    const float invC = 1.f / (float)C;
    for (int r = 0; r < M; r++) {
        const float *x = in + (size_t)r * C;
        float *y = out + (size_t)r * C;
        float mu = vsum(x, C) * invC;
        v4f acc = splat(0.f), vm = splat(mu);
        int c = 0;
        for (; c + 4 <= C; c += 4) { v4f d = ld4(x + c) - vm; acc += d * d; }
        float var = hsum(acc);
        for (; c < C; c++) { float d = x[c] - mu; var += d * d; }
        float rs = 1.f / sqrtf(var * invC + LN_EPS);
        v4f vr = splat(rs);
        for (c = 0; c + 4 <= C; c += 4)
            st4(y + c, (ld4(x + c) - vm) * vr * ld4(g + c) + ld4(b + c));
        for (; c < C; c++) y[c] = (x[c] - mu) * rs * g[c] + b[c];
        mean[r] = mu;
        rstd[r] = rs;
    }
}

void nn_layernorm_backward(float *dinp, float *dg, float *db, const float *dout,
                           const float *in, const float *mean, const float *rstd,
                           const float *g, int M, int C)
{
    const float invC = 1.f / (float)C;
    for (int r = 0; r < M; r++) {
        const float *x = in + (size_t)r * C, *dy = dout + (size_t)r * C;
        float *dx = dinp + (size_t)r * C;
        v4f vm = splat(mean[r]), vr = splat(rstd[r]);
        v4f s1 = splat(0.f), s2 = splat(0.f);
        int c = 0;
        for (; c + 4 <= C; c += 4) {
            v4f xh = (ld4(x + c) - vm) * vr, d = ld4(dy + c);
            v4f dxh = d * ld4(g + c);
            s1 += dxh;
            s2 += dxh * xh;
            st4(dg + c, ld4(dg + c) + d * xh);
            st4(db + c, ld4(db + c) + d);
        }
        float a1 = hsum(s1), a2 = hsum(s2);
        for (; c < C; c++) {
            float xh = (x[c] - mean[r]) * rstd[r], dxh = dy[c] * g[c];
            a1 += dxh;
            a2 += dxh * xh;
            dg[c] += dy[c] * xh;
            db[c] += dy[c];
        }
        a1 *= invC;
        a2 *= invC;
        v4f va1 = splat(a1), va2 = splat(a2);
        for (c = 0; c + 4 <= C; c += 4) {
            v4f xh = (ld4(x + c) - vm) * vr;
            v4f dxh = ld4(dy + c) * ld4(g + c);
            st4(dx + c, ld4(dx + c) + vr * (dxh - va1 - xh * va2));
        }
        for (; c < C; c++) {
            float xh = (x[c] - mean[r]) * rstd[r], dxh = dy[c] * g[c];
            dx[c] += rstd[r] * (dxh - a1 - xh * a2);
        }
    }
}

/* ---- GELU ------------------------------------------------------------------------ */
#define GELU_K 0.7978845608028654f /* sqrt(2/pi) */
#define GELU_A 0.044715f

static inline v4f vgelu(v4f x)
{
    v4f u = splat(GELU_K) * (x + splat(GELU_A) * x * x * x);
    return x / (splat(1.f) + vexp(splat(-2.f) * u));
}

static inline v4f vgelu_grad(v4f x)
{
    v4f x2 = x * x;
    v4f u = splat(GELU_K) * (x + splat(GELU_A) * x2 * x);
    v4f s = splat(1.f) / (splat(1.f) + vexp(splat(-2.f) * u));
    v4f du = splat(GELU_K) * (splat(1.f) + splat(3.f * GELU_A) * x2);
    return s + x * s * (splat(1.f) - s) * splat(2.f) * du;
}

void nn_gelu_forward(float *out, const float *in, size_t n)
{
    size_t i = 0;
    for (; i + 4 <= n; i += 4) st4(out + i, vgelu(ld4(in + i)));
    for (; i < n; i++) out[i] = vgelu(splat(in[i]))[0];
}

void nn_gelu_backward(float *dinp, const float *dout, const float *in, size_t n)
{
    size_t i = 0;
    for (; i + 4 <= n; i += 4) st4(dinp + i, ld4(dout + i) * vgelu_grad(ld4(in + i)));
    for (; i < n; i++) dinp[i] = dout[i] * vgelu_grad(splat(in[i]))[0];
}

/* ---- residual ---------------------------------------------------------------------- */
void nn_residual_forward(float *out, const float *a, const float *b, size_t n)
{
    size_t i = 0;
    for (; i + 4 <= n; i += 4) st4(out + i, ld4(a + i) + ld4(b + i));
    for (; i < n; i++) out[i] = a[i] + b[i];
}

void nn_residual_backward(float *acc, const float *x, size_t n)
{
    size_t i = 0;
    for (; i + 4 <= n; i += 4) st4(acc + i, ld4(acc + i) + ld4(x + i));
    for (; i < n; i++) acc[i] += x[i];
}

/* ---- attention -------------------------------------------------------------------- */
size_t nn_attention_scratch_len(int T, int C, int H)
{
    int hd = C / H;
    return (size_t)2 * hd * T + 2 * (size_t)T;
}

/* In place softmax of s[0..n). */
static inline void softmax_row(float *s, int n)
{
    float mx = s[0];
    for (int j = 1; j < n; j++) mx = s[j] > mx ? s[j] : mx;
    int j = 0;
    v4f vm = splat(mx);
    for (; j + 4 <= n; j += 4) st4(s + j, vexp(ld4(s + j) - vm));
    for (; j < n; j++) s[j] = sexp(s[j] - mx);
    float inv = 1.f / vsum(s, n);
    for (j = 0; j + 4 <= n; j += 4) st4(s + j, ld4(s + j) * splat(inv));
    for (; j < n; j++) s[j] *= inv;
}

void nn_attention_forward(float *out, float *prob, const float *qkv,
                          int B, int T, int C, int H, nn_attn_mode mode, float *scratch)
{
    const int hd = C / H, C3 = 3 * C;
    if (mode == NN_ATTN_SELF) {
        /* Softmax over one admissible key is exactly 1: the output is v itself. */
        for (int r = 0; r < B * T; r++)
            memcpy(out + (size_t)r * C, qkv + (size_t)r * C3 + 2 * C, sizeof(float) * C);
        return;
    }
    const float scale = 1.f / sqrtf((float)hd);
    float *kt = scratch; /* [hd x T]: K transposed so score rows vectorise over keys */
    for (int b = 0; b < B; b++) {
        const float *base = qkv + (size_t)b * T * C3;
        for (int h = 0; h < H; h++) {
            for (int j = 0; j < T; j++)
                for (int d = 0; d < hd; d++) kt[d * T + j] = base[(size_t)j * C3 + C + h * hd + d];
            for (int i = 0; i < T; i++) {
                const float *q = base + (size_t)i * C3 + h * hd;
                float *s = prob + (((size_t)b * H + h) * T + i) * T;
                memset(s, 0, sizeof(float) * T);
                for (int d = 0; d < hd; d++) axpy(s, q[d] * scale, kt + d * T, T);
                softmax_row(s, T);
                float *o = out + ((size_t)b * T + i) * C + h * hd;
                memset(o, 0, sizeof(float) * hd);
                for (int j = 0; j < T; j++) axpy(o, s[j], base + (size_t)j * C3 + 2 * C + h * hd, hd);
            }
        }
    }
}

void nn_attention_backward(float *dqkv, const float *dout, const float *qkv,
                           const float *prob, int B, int T, int C, int H,
                           nn_attn_mode mode, float *scratch)
{
    const int hd = C / H, C3 = 3 * C;
    if (mode == NN_ATTN_SELF) {
        for (int r = 0; r < B * T; r++) {
            float *g = dqkv + (size_t)r * C3;
            memset(g, 0, sizeof(float) * 2 * C); /* q and k receive no gradient */
            memcpy(g + 2 * C, dout + (size_t)r * C, sizeof(float) * C);
        }
        return;
    }
    const float scale = 1.f / sqrtf((float)hd);
    float *vt = scratch;            /* [hd x T] */
    float *dp = scratch + hd * T;   /* [T] */
    float *ds = dp + T;             /* [T] */
    memset(dqkv, 0, sizeof(float) * (size_t)B * T * C3);
    for (int b = 0; b < B; b++) {
        const float *base = qkv + (size_t)b * T * C3;
        float *gbase = dqkv + (size_t)b * T * C3;
        for (int h = 0; h < H; h++) {
            for (int j = 0; j < T; j++)
                for (int d = 0; d < hd; d++) vt[d * T + j] = base[(size_t)j * C3 + 2 * C + h * hd + d];
            for (int i = 0; i < T; i++) {
                const float *P = prob + (((size_t)b * H + h) * T + i) * T;
                const float *dO = dout + ((size_t)b * T + i) * C + h * hd;
                const float *q = base + (size_t)i * C3 + h * hd;
                memset(dp, 0, sizeof(float) * T);
                for (int d = 0; d < hd; d++) axpy(dp, dO[d], vt + d * T, T);
                for (int j = 0; j < T; j++) axpy(gbase + (size_t)j * C3 + 2 * C + h * hd, P[j], dO, hd);
                float dot = 0.f;
                for (int j = 0; j < T; j++) dot += P[j] * dp[j];
                int j = 0;
                for (; j + 4 <= T; j += 4)
                    st4(ds + j, ld4(P + j) * (ld4(dp + j) - splat(dot)) * splat(scale));
                for (; j < T; j++) ds[j] = P[j] * (dp[j] - dot) * scale;
                float *dq = gbase + (size_t)i * C3 + h * hd;
                for (j = 0; j < T; j++) {
                    axpy(dq, ds[j], base + (size_t)j * C3 + C + h * hd, hd);
                    axpy(gbase + (size_t)j * C3 + C + h * hd, ds[j], q, hd);
                }
            }
        }
    }
}
