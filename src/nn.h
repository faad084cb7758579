/* nn: layer kernels of the flow-matching set transformer (SPEC §8, paper §4.2):
 * linear (cblas_sgemm), layer norm, GELU (tanh form), residual add, and
 * multi-head self-attention over groups of T tokens (one group = one patch)
 * with two masks: joint (every token sees the whole patch) and self (each token
 * sees only itself, paper Eq. 6 "independent" arm; same parameters).
 *
 * Conventions: activations are row-major [rows x channels]; weights are stored
 * [out x in] so that y = x W^T + b. Backward kernels ACCUMULATE parameter
 * gradients (+=); input gradients are overwritten unless a comment says "+=".
 * Kernels never allocate and run on the calling thread; for one build on one
 * machine (one BLAS thread) they are bit-reproducible. Float only: tests keep
 * naive double-precision references for every kernel. */
#ifndef NN_H
#define NN_H
#include <stddef.h>

typedef enum { NN_ATTN_JOINT = 0, NN_ATTN_SELF = 1 } nn_attn_mode;

/* out[M x N] = in[M x K] . w[N x K]^T + b[N]   (b may be NULL). */
void nn_linear_forward(float *out, const float *in, const float *w, const float *b,
                       int M, int K, int N);
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
 * unfused kernels): h[M x N] += b row-wise, then nn_gelu_forward_save(out, sig, h). */
void nn_bias_gelu_forward_save(float *h, float *sig, float *out, const float *b, int M, int N);
/* out[M x N] = (y + b) + x, row-wise bias (out may alias y or x). */
void nn_bias_residual_forward(float *out, const float *y, const float *b, const float *x, int M, int N);

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
/* Floats of scratch the attention kernels need (T*T). */
size_t nn_attention_scratch_len(int T, int C, int H);

/* y[i] = exp(x[i]) with a range-reduced polynomial (|rel err| < 4e-7 on
 * [-87, 88]; inputs are clamped to that range). Vectorised; used by softmax
 * and GELU so that neither depends on libm speed. */
void nn_expf(float *y, const float *x, size_t n);

/* GFLOP/s of cblas_sgemm (NoTrans x Trans, as in nn_linear_forward) over all
 * shapes M x N x K with N, K in sizes[0..n), each run `reps` times, timed
 * together; 0 on allocation failure. For the benchmark of SPEC §10. */
double nn_sgemm_gflops(int M, const int *sizes, int n, int reps);

#endif
