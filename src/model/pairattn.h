/* pairattn: pair-aware multi-head attention (design.md §8 "Pair awareness",
 * §8.1; paper §4.2). Every pair (i, j) of a patch has a geometry
 *
 *   g_ij = ((p_j - p_i)/d, |p_j - p_i|/d, (|p_j - p_i| - rbar_i - rbar_j)/d)
 *
 * and a fixed featurisation of it, f_ij (PAIRATTN_Q values: the four of g_ij,
 * then cos theta_ij, sin theta_ij, cos 2 theta_ij, sin 2 theta_ij of the
 * bearing theta_ij from i to j), standardised with z-scores from the training
 * pairs i != j: phi_ij = (f_ij - mu) / sd. For the self pair the offset,
 * distance and bearing terms are 0 but the free space is -2 rbar_i / d, and
 * after standardisation none of phi_ii is 0: it is a fixed function of the
 * token's own rbar_i / d, which the token already carries, so the independent
 * arm's value term below sees nothing of another tree. Per block and
 * head h (hd = C/H, scale = 1/sqrt(hd)):
 *
 *   logits_ij = scale (q_i . k_j + beta_ij),  beta_ij = wb_h . phi_ij
 *   a_ij      = softmax_j(logits_ij)
 *   out_i     = sum_j a_ij v_j  +  Wv_h Phi_i,   Phi_i = sum_j a_ij phi_ij
 *
 * (the value term sum_j a_ij Wv_h phi_ij, with Wv_h the head's hd rows of
 * wv [C x Q]). A per-head constant added to beta would cancel in the softmax,
 * so there is none. The independent arm (NN_ATTN_SELF) attends only to
 * itself: a_ii = 1, out_i = v_i + Wv_h phi_ii, and wb gets no gradient; both
 * arms carry the same parameters.
 *
 * Layouts: phi[T x T x Q] (pair-major, row (i, j) = i*T + j) and its
 * transpose phit[Q x T x T], both per patch; Phi (saved by the forward for
 * the backward) [B x H x T x Q]. Weights wb[H x Q], wv[C x Q] (out x in).
 * Conventions of nn.h: parameter gradients accumulate (+=), input gradients
 * are overwritten; no allocation; the values do not depend on the ISA (every
 * product is gemm_fma, the softmax is nn.c's, the rest is scalar). */
#ifndef PAIRATTN_H
#define PAIRATTN_H
#include "nn.h"
#include <stddef.h>

enum { PAIRATTN_Q = 8 };

/* Raw pair features f[T x T x Q] of one patch whose token i has position
 * (tok[i*stride], tok[i*stride + 1]) and mean radius tok[i*stride + 2], all
 * in units of the spacing d (the model's features 0..2, src/model/patch.h);
 * computed in double and rounded to float. */
void pairattn_features(float *f, const float *tok, int stride, int T);
/* Standardised phi[T x T x Q] and phit[Q x T x T] of one patch:
 * phi = (f - mu[q]) * isd[q] in float, f = pairattn_features(tok, stride). */
void pairattn_geometry(float *phi, float *phit, const float *tok, int stride, int T,
                       const float *mu, const float *isd);

/* Floats of scratch pairattn_forward / _backward need. */
size_t pairattn_scratch_len(int T, int C, int H);

/* out[B*T x C] (and prob[B x H x T x T], Phi[B x H x T x Q]) from
 * qkv[B*T x 3C] and phi/phit of the B patches (B*T*T*Q floats each);
 * wvt[Q x C] receives wv^T (with wv == NULL it must already hold it). */
void pairattn_forward(float *out, float *prob, float *Phi, const float *qkv, const float *phi,
                      const float *phit, const float *wb, const float *wv, float *wvt,
                      int B, int T, int C, int H, nn_attn_mode mode, float *scratch);
/* dqkv[B*T x 3C] (overwritten); dwb[H x Q] += , dwv[C x Q] += . */
void pairattn_backward(float *dqkv, float *dwb, float *dwv, const float *dout, const float *qkv,
                       const float *prob, const float *Phi, const float *phi, const float *phit,
                       const float *wv, int B, int T, int C, int H, nn_attn_mode mode,
                       float *scratch);

/* Fused with the neighbouring products as nn_linear_attention_forward /
 * nn_linear_backward_attention (same values as the unfused sequence):
 * qkv = in w^T + b (w[3C x C]; wt as in nn_linear_forward), then pairattn_forward;
 * under NN_ATTN_SELF only the v columns of qkv (nn_linear_attention_forward). */
void pairattn_linear_forward(float *qkv, float *out, float *prob, float *Phi, const float *in,
                             const float *w, const float *b, const float *phi, const float *phit,
                             const float *wb, const float *wvt, int B, int T, int C, int H,
                             nn_attn_mode mode, float *wt, float *scratch);
/* For the output projection pw[C x C] applied to att: nn_linear_backward(datt,
 * dpw, dpb, dout, att, pw), then pairattn_backward(dqkv, dwb, dwv, datt, ...). */
void pairattn_linear_backward(float *dqkv, float *datt, float *dpw, float *dpb, float *dwb,
                              float *dwv, const float *dout, const float *att, const float *pw,
                              const float *qkv, const float *prob, const float *Phi,
                              const float *phi, const float *phit, const float *wv, int B, int T,
                              int C, int H, nn_attn_mode mode, float *scratch);

#endif
