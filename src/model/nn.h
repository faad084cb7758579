/* nn: layer kernels of the flow-matching set transformer (design.md §8, paper §4.2):
 * linear (gemm_fma), layer norm, GELU (tanh form), residual add, and
 * multi-head self-attention over groups of T tokens (one group = one patch)
 * with two masks: joint (every token sees the whole patch) and self (each token
 * sees only itself, paper Eq. 6 "independent" arm; same parameters).
 *
 * Conventions: activations are row-major [rows x channels]; weights are stored
 * [out x in] so that y = x W^T + b. Backward kernels ACCUMULATE parameter
 * gradients (+=); input gradients are overwritten unless a comment says "+=".
 * Kernels never allocate and run on the calling thread; their results are
 * bit-identical on every x86-64 machine (gemm.h; the vector loops below are
 * lane-wise IEEE in a fixed order). Float only: tests keep
 * naive double-precision references for every kernel. */
#ifndef NN_H
#define NN_H
#include "gemm.h"
#include <stddef.h>

typedef enum { NN_ATTN_JOINT = 0, NN_ATTN_SELF = 1 } nn_attn_mode;

/* out[M x N] = in[M x K] . w[N x K]^T + b[N]   (b may be NULL);
 * wt: K*N floats that receive w^T; with w == NULL they must already hold it
 * (a caller that runs several forwards with the same weights transposes
 * once). The same holds for every forward layer below that takes w and wt. */
void nn_linear_forward(float *out, const float *in, const float *w, const float *b,
                       int M, int K, int N, float *wt);
/* dinp[M x K] = dout . w (skipped when dinp == NULL);
 * dw[N x K] += dout^T . in;  db[N] += column sums of dout (skipped when NULL). */
void nn_linear_backward(float *dinp, float *dw, float *db, const float *dout,
                        const float *in, const float *w, int M, int K, int N);

/* Row-wise layer norm, eps = 1e-5: out[M x C]; saves mean[M], rstd[M]. */
void nn_layernorm_forward(float *out, float *mean, float *rstd, const float *in,
                          const float *g, const float *b, int M, int C);
/* dinp[M x C] += d/d(in); dg[C] += ; db[C] += . */
void nn_layernorm_backward(float *dinp, float *dg, float *db, const float *dout,
                           const float *in, const float *mean, const float *rstd,
                           const float *g, int M, int C);

/* GELU, tanh approximation written as x * sigmoid(2u), u = sqrt(2/pi)(x + 0.044715 x^3). */
void nn_gelu_forward(float *out, const float *in, size_t n);
/* dinp[n] = dout * gelu'(in) (dinp may alias dout). */
void nn_gelu_backward(float *dinp, const float *dout, const float *in, size_t n);
/* Forward that also saves sig[n] = sigmoid(2u) so that the backward needs no
 * exp or division; same out values as nn_gelu_forward. */
void nn_gelu_forward_save(float *out, float *sig, const float *in, size_t n);
void nn_gelu_backward_saved(float *dinp, const float *dout, const float *in,
                            const float *sig, size_t n);

/* Fused forms used by the model (one pass instead of two; same values as the
 * unfused kernels): h[M x N] += b row-wise, then nn_gelu_forward_save(out, sig, h).
 * sig == NULL: out[M x N] = gelu(h + b) alone, h and no sigmoid written. */
void nn_bias_gelu_forward_save(float *h, float *sig, float *out, const float *b, int M, int N);
/* out[M x N] = (y + b) + x, row-wise bias (out may alias y or x). */
void nn_bias_residual_forward(float *out, const float *y, const float *b, const float *x, int M, int N);

/* Fused linear layers (same values as the unfused sequences, one sweep):
 * nn_linear_forward(h, in, w, NULL) then nn_bias_gelu_forward_save(h, sig, out, b).
 * sig == NULL: forward only (sampling), out alone is the result; h then
 * holds the product without the bias, and no sigmoid is saved. */
void nn_linear_bias_gelu_forward(float *h, float *sig, float *out, const float *in,
                                 const float *w, const float *b, int M, int K, int N, float *wt);
/* nn_linear_forward(out, in, w, NULL), nn_bias_residual_forward(out, out, b, x), then,
 * unless ln == NULL, nn_layernorm_forward(ln, mean, rstd, out, g, beta). x must not alias out. */
void nn_linear_bias_residual_forward(float *out, const float *in, const float *w,
                                     const float *b, const float *x, float *ln, float *mean,
                                     float *rstd, const float *g, const float *beta,
                                     int M, int K, int N, float *wt);
/* nn_linear_backward(dinp, dw, db, dout, in, w) then
 * nn_gelu_backward_saved(dinp, dinp, h, sig) over the M x K input gradient. */
void nn_linear_backward_gelu(float *dinp, float *dw, float *db, const float *dout,
                             const float *in, const float *w, const float *h,
                             const float *sig, int M, int K, int N);

/* out[n] = a + b (out may alias a). */
void nn_residual_forward(float *out, const float *a, const float *b, size_t n);
/* acc[n] += x (backward of a residual add into one branch). */
void nn_residual_backward(float *acc, const float *x, size_t n);

/* Multi-head self-attention core (projections are separate nn_linear calls).
 * qkv[B*T x 3C] rows are [q | k | v], head h uses columns h*C/H .. (h+1)*C/H-1
 * of each part; out[B*T x C]; prob[B x H x T x T] saves the softmax (unused by
 * NN_ATTN_SELF, may be NULL there). Scores are scaled by 1/sqrt(C/H). */
void nn_attention_forward(float *out, float *prob, const float *qkv,
                          int B, int T, int C, int H, nn_attn_mode mode, float *scratch);
/* dqkv[B*T x 3C] = gradient w.r.t. qkv (overwritten). */
void nn_attention_backward(float *dqkv, const float *dout, const float *qkv,
                           const float *prob, int B, int T, int C, int H,
                           nn_attn_mode mode, float *scratch);
/* The same with additive terms for pair-aware attention (src/model/pairattn.h):
 * sbias[B x H x T x T] (NULL: none) is added to the scaled scores before the
 * softmax; dpadd[B x H x T x T] (NULL: none) is added to dP = dO V^T before
 * the softmax backward. Both are ignored by NN_ATTN_SELF. After a backward
 * with B = 1, scratch[0 .. H*T*T) holds that patch's dS, the gradient w.r.t.
 * the unscaled scores Q K^T (1/sqrt(C/H) times that w.r.t. the logits). */
void nn_attention_forward_biased(float *out, float *prob, const float *qkv, const float *sbias,
                                 int B, int T, int C, int H, nn_attn_mode mode, float *scratch);
void nn_attention_backward_biased(float *dqkv, const float *dout, const float *qkv,
                                  const float *prob, const float *dpadd, int B, int T, int C,
                                  int H, nn_attn_mode mode, float *scratch);
/* Floats of scratch the attention kernels need (H*T*T + T*C/H). */
size_t nn_attention_scratch_len(int T, int C, int H);

/* Attention fused with its neighbouring products (same values, better locality):
 * nn_linear_forward(qkv, in, w[3C x C], b) then nn_attention_forward(out, prob, qkv).
 * Self-only attention (NN_ATTN_SELF) reads only v: the q and k columns of qkv
 * are then neither computed nor written (design.md §10). */
void nn_linear_attention_forward(float *qkv, float *out, float *prob, const float *in,
                                 const float *w, const float *b, int B, int T, int C, int H,
                                 nn_attn_mode mode, float *wt, float *scratch);
/* For the output projection w[C x C] applied to att:
 * nn_linear_backward(datt, dw, db, dout, att, w) then
 * nn_attention_backward(dqkv, datt, qkv, prob). */
void nn_linear_backward_attention(float *dqkv, float *datt, float *dw, float *db,
                                  const float *dout, const float *att, const float *w,
                                  const float *qkv, const float *prob, int B, int T, int C,
                                  int H, nn_attn_mode mode, float *scratch);
/* The qkv projection's backward, nn_linear_backward(dinp, dw, db, dqkv, in, w,
 * M, C, 3C). Under NN_ATTN_SELF the q and k columns of dqkv are zero (the
 * output does not depend on them), so only the v block is multiplied: each
 * skipped term would have added fma(+0, w, c) or 1 * +0 to a chain that is
 * +0 there (the input gradient's chain over q and k comes before v's; the
 * weight and bias gradients of q and k stay as they are), so the bits are
 * those of the full product (tested). */
void nn_linear_backward_qkv(float *dinp, float *dw, float *db, const float *dqkv,
                            const float *in, const float *w, int M, int C, nn_attn_mode mode);

/* y[i] = exp(x[i]) with a range-reduced polynomial (|rel err| < 4e-7 on
 * [-87, 88]; inputs are clamped to that range). Vectorised; used by softmax
 * and GELU so that neither depends on libm speed. */
void nn_expf(float *y, const float *x, size_t n);

/* The linear layers with an epilogue on each finished strip (the fused
 * kernels of nn.c and nn_attn.c use them). */
/* out = in w^T (+ b), then epi on each finished strip (may be NULL); w == NULL
 * means wt already holds the transpose. Every forward linear layer. */
void nn_linear_forward_epi(float *out, const float *in, const float *w, const float *b,
                           int M, int K, int N, float *wt, gemm_epilogue epi, void *ctx);
/* dinp = dout w with epi on its strips (both skipped when dinp == NULL),
 * dw += dout^T in, db += column sums; every backward linear layer. */
void nn_linear_backward_epi(float *dinp, float *dw, float *db, const float *dout,
                            const float *in, const float *w, int M, int K, int N,
                            gemm_epilogue epi, void *ctx);

#endif
