/* model: the conditional flow-matching set transformer of paper §4.2 (design.md §8).
 * A patch is T tokens (T = 24 trees). Token i's input is its noisy deviation
 * profile x_t,i (P = 24 values) and nfeat features ((p_i - p_focal)/d, rbar_i/d);
 * the patch's condition vector (ncond values) and sinusoidal features of the
 * flow time t go through one two-layer embedding that is ADDED to every token.
 * Pre-LN blocks (LN -> MHA -> +, LN -> MLP(GELU) -> +), final LN, linear head to
 * P velocity outputs per token. Joint arm: attention across the patch; the
 * independent arm (joint = 0) lets each token attend only to itself and has
 * the same parameters (paper Eq. 6).
 *
 * Memory: one flat float buffer each for parameters and gradients, in the same
 * layout (all weight matrices first, then gains and biases: weight decay
 * applies to the first model_ndecay floats); activations for up to Bmax
 * patches are allocated once by model_alloc, so forward/backward never allocate.
 * Loss: paper Eq. 2 (linear path, MSE on velocity, all T tokens). Sampler:
 * Euler from N(0, I). */
#ifndef MODEL_H
#define MODEL_H
#include "cs.h"
#include "nn.h"
#include "patch.h"
#include <gsl/gsl_rng.h>
#include <stddef.h>

typedef struct {
    int T;     /* tokens per patch */
    int P;     /* profile values per token (sectors) */
    int nfeat; /* per-token features */
    int ncond; /* patch condition values */
    int ntime; /* sinusoidal time features (even) */
    int C;     /* width */
    int L;     /* blocks */
    int H;     /* heads (C % H == 0) */
    int F;     /* MLP width */
    int joint; /* 1: attention across the patch; 0: each token attends only to itself */
    int pair;  /* 1: pair-aware attention (src/model/pairattn.h) from features 0..2 =
                * (x, y, rbar) / d (design.md §8 "Pair awareness"); 0: plain
                * multi-head attention */
    int stdz;  /* token features standardised with the model's z-scores
                * (model_norm_fit): MODEL_STDZ_AUTO (0) as `pair` (the pair
                * model standardises, the plain one does not: the two models
                * written before the readings), MODEL_STDZ_ON, MODEL_STDZ_OFF */
    int nuse;  /* features 0..nuse-1 of each token's nfeat embedded (0: all);
                * the pair geometry always reads the raw features 0..2 */
} model_cfg;

enum { MODEL_STDZ_AUTO = 0, MODEL_STDZ_ON = 1, MODEL_STDZ_OFF = 2 };

/* The readings of the generator (design.md §8 "Readings of the generator"):
 *  plain          the features as they are (position, size and the polar
 *                 Fourier basis of src/model/patch.h), plain attention;
 *  paper          paper §4.2 as written: (p_i - p_focal)/d and rbar_i/d only,
 *                 standardised on the training data (a preprocessing the paper
 *                 neither states nor excludes), plain attention;
 *  paper-fourier  paper + the polar Fourier basis, standardised;
 *  pair           paper-fourier + pair-aware attention (the extension). */
typedef enum {
    MODEL_PLAIN = 0,
    MODEL_PAPER = 1,
    MODEL_PAPER_FOURIER = 2,
    MODEL_PAIR = 3,
    MODEL_NREADING = 4
} model_reading;
const char *model_reading_name(model_reading r);
/* CS_EUSAGE naming the choices when s is not a reading's name. */
cs_status model_reading_parse(const char *s, model_reading *r);
/* Set pair, stdz and nuse of c for reading r (c->nfeat must be set; the
 * paper reading embeds features 0..2). plain and pair set stdz AUTO and nuse 0,
 * so their configurations (and files) are those written before the readings. */
void model_cfg_set_reading(model_cfg *c, model_reading r);
/* The reading whose ingredients c has, or MODEL_NREADING if none. */
model_reading model_cfg_reading(const model_cfg *c);
/* Effective ingredients: 1 if token features are standardised; features embedded. */
int model_cfg_stdz(const model_cfg *c);
int model_cfg_nuse(const model_cfg *c);

typedef struct {
    size_t ln1_g, ln1_b, qkv_w, qkv_b, proj_w, proj_b, ln2_g, ln2_b, fc1_w, fc1_b, fc2_w, fc2_b;
    size_t pb_w, pv_w; /* pair model only: score weights [H x Q], value weights [C x Q] */
} model_block_off;

/* Patches per forward/backward pass of model_fm_grad (see model.c). */
enum { MODEL_MICRO = 4 };

typedef struct model {
    model_cfg cfg;
    int Bmax;
    size_t nparams, ndecay;
    float *params, *grads;
    /* private: the transposed weight matrices (params' offsets), see model.c */
    float *wtall;
    /* offsets into params/grads */
    size_t tok_w, tok_b, e1_w, e1_b, e2_w, e2_b, lnf_g, lnf_b, head_w, head_b;
    model_block_off *blk;
    /* z-scores fitted on the training data (model_norm_fit) and stored with
     * the parameters in checkpoints: fmu, fisd [nuse] of the token features
     * (when standardised), then pmu, pisd [PAIRATTN_Q] of the pair features
     * (pair model); model_nnorm floats (0 for the plain reading) */
    float *norm;
    size_t nnorm;
    /* patches per forward/backward pass of model_fm_grad (default
     * MODEL_MICRO; the results do not depend on it, only the speed) */
    int micro;
    /* private: activations and scratch of the last forward */
    int B;
    float *mem;
    float *tin, *cin, *e1, *e1g, *e, *lnf, *muf, *rsf, *out;
    float **x, **ln1, **mu1, **rs1, **qkv, **prob, **att, **xm, **ln2, **mu2, **rs2, **h, **hs, **hg;
    float *dx, *dtmp, *dln, *dqkv, *dh, *de, *de1, *ascr;
    float *fm_xt, *fm_u, *fm_t, *fm_v, *fm_dv;
    float *phi, *phit, **Phi; /* pair model: geometry of the pass, saved pair mixes */
} model;

/* The reference configuration of design.md §10: T = P = 24, nfeat = PATCH_NFEAT, ntime = 16,
 * width 64, 3 blocks, 4 heads, MLP 256, joint arm; ncond as given. */
model_cfg model_cfg_reference(int ncond);
/* CS_EINPUT with a message naming the offending field if cfg is unusable. */
cs_status model_cfg_check(const model_cfg *cfg);
/* Number of parameters (independent of cfg->joint). */
size_t model_nparams(const model_cfg *cfg);

/* Floats of m->norm for cfg: 2 nuse (token z-scores, when standardised) +
 * 2 PAIRATTN_Q (pair z-scores, pair model). */
size_t model_nnorm(const model_cfg *cfg);
/* z-scores of the embedded token features over all n*T tokens (when
 * standardised) and of the pair features over all ordered pairs i != j of the
 * n patches feat[n*T*nfeat] (pair model); mean and population sd in double,
 * sd 0 -> 1. No-op for the plain reading. */
cs_status model_norm_fit(model *m, const float *feat, int n);

cs_status model_alloc(model **out, const model_cfg *cfg, int Bmax);
void model_free(model *m);
/* Gaussian init (std 1/sqrt(fan_in); residual projections scaled by
 * 1/sqrt(2L); head by 0.1), LN gains 1, biases 0. Draws only from `init`. */
void model_init(model *m, gsl_rng *init);

/* Velocity v[B*T*P] for x_t[B*T*P], feat[B*T*nfeat], cond[B*ncond], t[B].
 * Keeps the activations for model_backward. B <= Bmax. */
cs_status model_forward(model *m, int B, const float *xt, const float *feat,
                        const float *cond, const float *t, float *v);
/* Gradient of <dv, v> w.r.t. all parameters into m->grads (overwritten),
 * for the activations of the last model_forward. */
void model_backward(model *m, const float *dv);

/* Flow-matching draw (paper Eq. 2): per patch t ~ U(0,1), then x0 ~ N(0, I)
 * per value; x_t = (1 - t) x0 + t x1 and the target u = x1 - x0.
 * n_per_patch = T*P. All draws from `noise`, in that order. */
void model_fm_draw(gsl_rng *noise, int B, int n_per_patch, const float *x1,
                   float *xt, float *u, float *t);
/* mean over n of (v - u)^2; dv = its gradient w.r.t. v (may be NULL).
 * This is paper Eq. 2 (squared norm over all T tokens x P values) divided by
 * the constant T*P, so that loss values do not depend on the patch size. */
double model_fm_loss(const float *v, const float *u, size_t n, float *dv);
/* One draw + forward + loss + backward on a batch; gradients in m->grads.
 * Runs in passes of m->micro patches with the results of one pass (model.c). */
cs_status model_fm_grad(model *m, gsl_rng *noise, int B, const float *x1,
                        const float *feat, const float *cond, double *loss);

/* Generate x[B*T*P]: x ~ N(0, I) from `noise`, then nsteps Euler steps
 * x += v(x, t_k)/nsteps, t_k = k/nsteps. Each v is a forward-only pass
 * (what only model_backward reads is not kept): the values of
 * model_forward, bit for bit. */
cs_status model_sample(model *m, gsl_rng *noise, int B, const float *feat,
                       const float *cond, int nsteps, float *x);

/* Model FLOPs of one training step (forward + backward) at batch B: GEMMs
 * (2MNK each) plus the attention score and mix products. */
double model_train_flops(const model_cfg *cfg, int B);

/* Generate the crowns (radii, m; r[n*T*P]) of patches [0, n) of ps with
 * model m and nsteps Euler steps, in chunks of Bmax, drawing from `noise`.
 * perm != NULL: before each chunk is sampled, the positional features of its
 * patches are permuted (the shuffled-geometry probe), drawing from perm.
 * Used by E3/E4 (exp_main) and E7 (exp_comp) alike. */
cs_status model_sample_radii(model *m, int Bmax, const patch_set *ps, int n, int nsteps,
                             gsl_rng *noise, gsl_rng *perm, double *r);

#endif
