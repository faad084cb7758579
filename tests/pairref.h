/* Naive double-precision reference of pair-aware attention (src/model/pairattn.h):
 * the pair features by trigonometry (atan2, cos, sin) instead of the
 * library's algebra, and the attention with its score bias and value term as
 * straight loops over (patch, head, i, j). Used for the forward agreement and
 * finite-difference checks of tests/test_pairattn.c and tests/modelref.h. */
#ifndef PAIRREF_H
#define PAIRREF_H
#include <math.h>
#include <stdlib.h>

enum { REF_PQ = 8 };

/* f[T x T x 8]: dx, dy, dist, free, cos th, sin th, cos 2th, sin 2th (the bearing terms 0 when i == j; free is then -2
 * rbar_i). */
static void ref_pair_features(double *f, const double *tok, int stride, int T)
{
    for (int i = 0; i < T; i++)
        for (int j = 0; j < T; j++) {
            double dx = tok[j * stride] - tok[i * stride], dy = tok[j * stride + 1] - tok[i * stride + 1];
            double dist = hypot(dx, dy), th = atan2(dy, dx);
            double *o = f + ((size_t)i * T + j) * REF_PQ;
            o[0] = dx; o[1] = dy; o[2] = dist;
            o[3] = dist - tok[i * stride + 2] - tok[j * stride + 2];
            o[4] = i == j ? 0 : cos(th); o[5] = i == j ? 0 : sin(th);
            o[6] = i == j ? 0 : cos(2 * th); o[7] = i == j ? 0 : sin(2 * th);
        }
}

/* out[B*T x C] from qkv[B*T x 3C], phi[B x T x T x 8], wb[H x 8], wv[C x 8];
 * mode 0 joint, 1 self. logits = (q.k + wb_h.phi_ij)/sqrt(hd);
 * out_i = sum_j a_ij (v_j + Wv_h phi_ij). */
static void ref_pair_attention(double *out, const double *qkv, const double *phi, const double *wb,
                               const double *wv, int B, int T, int C, int H, int mode)
{
    const int hd = C / H, C3 = 3 * C;
    double *a = malloc(sizeof(double) * T);
    for (int b = 0; b < B; b++)
        for (int h = 0; h < H; h++)
            for (int i = 0; i < T; i++) {
                const double *q = qkv + (size_t)(b * T + i) * C3 + h * hd;
                double mx = -INFINITY, z = 0;
                for (int j = 0; j < T; j++) {
                    const double *k = qkv + (size_t)(b * T + j) * C3 + C + h * hd;
                    const double *ph = phi + (((size_t)b * T + i) * T + j) * REF_PQ;
                    double s = 0, beta = 0;
                    for (int e = 0; e < hd; e++) s += q[e] * k[e];
                    for (int e = 0; e < REF_PQ; e++) beta += wb[h * REF_PQ + e] * ph[e];
                    a[j] = (mode == 1 && j != i) ? -INFINITY : (s + beta) / sqrt((double)hd);
                    if (a[j] > mx) mx = a[j];
                }
                for (int j = 0; j < T; j++) { a[j] = exp(a[j] - mx); z += a[j]; }
                for (int c = 0; c < hd; c++) {
                    double o = 0;
                    for (int j = 0; j < T; j++) {
                        const double *ph = phi + (((size_t)b * T + i) * T + j) * REF_PQ;
                        double u = qkv[(size_t)(b * T + j) * C3 + 2 * C + h * hd + c];
                        for (int e = 0; e < REF_PQ; e++) u += wv[(h * hd + c) * REF_PQ + e] * ph[e];
                        o += a[j] / z * u;
                    }
                    out[(size_t)(b * T + i) * C + h * hd + c] = o;
                }
            }
    free(a);
}
#endif
