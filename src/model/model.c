/* model: flow-matching set transformer (see model.h; paper §4.2, Eq. 2 and 6;
 * design.md §8). The block is pre-LN: x += Proj(MHA(LN1 x)); x += FC2(GELU(FC1(LN2 x))).
 * Time features: sin/cos of pi*2^k*t, k < ntime/2 (t in [0,1]). */
#include "model.h"
#include "patch.h"
#include "gemm.h"
#include "pairattn.h"
#include <gsl/gsl_randist.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

model_cfg model_cfg_reference(int ncond)
{
    model_cfg c = {.T = 24, .P = 24, .nfeat = PATCH_NFEAT, .ncond = ncond, .ntime = 16,
                   .C = 64, .L = 3, .H = 4, .F = 256, .joint = 1};
    return c;
}

static const char *const reading_names[MODEL_NREADING] = {"plain", "paper", "paper-fourier", "pair"};

const char *model_reading_name(model_reading r)
{
    return r >= 0 && r < MODEL_NREADING ? reading_names[r] : "none";
}

cs_status model_reading_parse(const char *s, model_reading *r)
{
    for (int k = 0; k < MODEL_NREADING; k++)
        if (s && !strcmp(s, reading_names[k])) { *r = (model_reading)k; return CS_OK; }
    return cs_err(CS_EUSAGE, "unknown generator reading '%s' (plain, paper, paper-fourier or pair)", s ? s : "");
}

void model_cfg_set_reading(model_cfg *c, model_reading r)
{
    c->pair = r == MODEL_PAIR;
    c->stdz = r == MODEL_PAPER || r == MODEL_PAPER_FOURIER ? MODEL_STDZ_ON : MODEL_STDZ_AUTO;
    c->nuse = r == MODEL_PAPER ? PATCH_FEAT_RBAR + 1 : 0;
}

int model_cfg_stdz(const model_cfg *c) { return c->stdz == MODEL_STDZ_AUTO ? c->pair : c->stdz == MODEL_STDZ_ON; }
int model_cfg_nuse(const model_cfg *c) { return c->nuse ? c->nuse : c->nfeat; }

model_reading model_cfg_reading(const model_cfg *c)
{
    const int z = model_cfg_stdz(c), all = model_cfg_nuse(c) == c->nfeat;
    if (c->pair) return z && all ? MODEL_PAIR : MODEL_NREADING;
    if (!z) return all ? MODEL_PLAIN : MODEL_NREADING;
    if (all) return MODEL_PAPER_FOURIER;
    return model_cfg_nuse(c) == PATCH_FEAT_RBAR + 1 ? MODEL_PAPER : MODEL_NREADING;
}

cs_status model_cfg_check(const model_cfg *c)
{
#define POS(f) if (c->f < 1) return cs_err(CS_EINPUT, "model config: " #f " = %d must be >= 1", c->f)
    POS(T); POS(P); POS(nfeat); POS(ncond); POS(ntime); POS(C); POS(L); POS(H); POS(F);
#undef POS
    if (c->C % c->H) return cs_err(CS_EINPUT, "model config: width C = %d not divisible by heads H = %d", c->C, c->H);
    if (c->ntime % 2) return cs_err(CS_EINPUT, "model config: ntime = %d must be even", c->ntime);
    if (c->joint != 0 && c->joint != 1) return cs_err(CS_EINPUT, "model config: joint = %d must be 0 or 1", c->joint);
    if (c->pair != 0 && c->pair != 1) return cs_err(CS_EINPUT, "model config: pair = %d must be 0 or 1", c->pair);
    if (c->pair && c->nfeat < 3)
        return cs_err(CS_EINPUT, "model config: the pair model needs nfeat >= 3 (x, y, rbar), got %d", c->nfeat);
    if (c->stdz < MODEL_STDZ_AUTO || c->stdz > MODEL_STDZ_OFF)
        return cs_err(CS_EINPUT, "model config: stdz = %d must be 0 (as pair), 1 (on) or 2 (off)", c->stdz);
    if (c->nuse < 0 || c->nuse > c->nfeat)
        return cs_err(CS_EINPUT, "model config: nuse = %d must be 0 (all) .. nfeat = %d", c->nuse, c->nfeat);
    return CS_OK;
}

/* Assign offsets (m may be NULL to only count). Matrices first, then vectors. */
static size_t layout(const model_cfg *c, model *m, size_t *ndecay)
{
    size_t o = 0;
    const size_t C = c->C, F = c->F, E = c->ncond + c->ntime, I = c->P + model_cfg_nuse(c);
#define PUT(field, n) do { if (m) m->field = o; o += (n); } while (0)
#define PUTB(l, field, n) do { if (m) m->blk[l].field = o; o += (n); } while (0)
    PUT(tok_w, C * I);
    PUT(e1_w, C * E);
    PUT(e2_w, C * C);
    for (int l = 0; l < c->L; l++) {
        PUTB(l, qkv_w, 3 * C * C);
        PUTB(l, proj_w, C * C);
        PUTB(l, fc1_w, F * C);
        PUTB(l, fc2_w, C * F);
    }
    PUT(head_w, (size_t)c->P * C);
    if (c->pair) /* after every matrix of the model without pair terms, so pair = 0 keeps its layout */
        for (int l = 0; l < c->L; l++) {
            PUTB(l, pb_w, (size_t)c->H * PAIRATTN_Q);
            PUTB(l, pv_w, C * PAIRATTN_Q);
        }
    if (ndecay) *ndecay = o;
    PUT(tok_b, C);
    PUT(e1_b, C);
    PUT(e2_b, C);
    for (int l = 0; l < c->L; l++) {
        PUTB(l, ln1_g, C); PUTB(l, ln1_b, C);
        PUTB(l, qkv_b, 3 * C); PUTB(l, proj_b, C);
        PUTB(l, ln2_g, C); PUTB(l, ln2_b, C);
        PUTB(l, fc1_b, F); PUTB(l, fc2_b, C);
    }
    PUT(lnf_g, C);
    PUT(lnf_b, C);
    PUT(head_b, c->P);
#undef PUT
#undef PUTB
    return o;
}

size_t model_nparams(const model_cfg *cfg) { return layout(cfg, NULL, NULL); }

size_t model_nnorm(const model_cfg *cfg)
{
    return (model_cfg_stdz(cfg) ? 2 * (size_t)model_cfg_nuse(cfg) : 0) + (cfg->pair ? 2 * PAIRATTN_Q : 0);
}

/* Offset of the pair z-scores in m->norm (after the token z-scores, if any). */
static size_t pair_norm_off(const model_cfg *c) { return model_cfg_stdz(c) ? 2 * (size_t)model_cfg_nuse(c) : 0; }

/* mean and population sd (double) of n values x[k*stride]; isd = 1/sd (1 if sd is 0) */
static void zscore(const float *x, size_t n, size_t stride, const unsigned char *skip, float *mu, float *isd)
{
    double s = 0, ss = 0;
    size_t cnt = 0;
    for (size_t k = 0; k < n; k++) if (!skip || !skip[k]) { s += x[k * stride]; cnt++; }
    double m = cnt ? s / (double)cnt : 0.0;
    for (size_t k = 0; k < n; k++) if (!skip || !skip[k]) { double d = x[k * stride] - m; ss += d * d; }
    double sd = cnt ? sqrt(ss / (double)cnt) : 0.0;
    *mu = (float)m;
    *isd = sd > 0 ? (float)(1.0 / sd) : 1.f;
}

cs_status model_norm_fit(model *m, const float *feat, int n)
{
    const model_cfg *c = &m->cfg;
    if (!model_cfg_stdz(c) && !c->pair) return CS_OK;
    if (n < 1) return cs_err(CS_EINPUT, "model_norm_fit: no patches");
    const int T = c->T, nf = c->nfeat, nu = model_cfg_nuse(c), Q = PAIRATTN_Q;
    const size_t TT = (size_t)T * T, npairs = (size_t)n * TT;
    for (int k = 0; model_cfg_stdz(c) && k < nu; k++)
        zscore(feat + k, (size_t)n * T, nf, NULL, m->norm + k, m->norm + nu + k);
    if (!c->pair) return CS_OK;
    float *pn = m->norm + pair_norm_off(c);
    float *f = malloc(sizeof(float) * npairs * Q);
    unsigned char *self = malloc(npairs);
    if (!f || !self) { free(f); free(self); return cs_err(CS_ENOMEM, "model_norm_fit: out of memory"); }
    for (int b = 0; b < n; b++) {
        pairattn_features(f + (size_t)b * TT * Q, feat + (size_t)b * T * nf, nf, T);
        for (size_t e = 0; e < TT; e++) self[(size_t)b * TT + e] = e % (T + 1) == 0;
    }
    for (int q = 0; q < Q; q++)
        zscore(f + q, npairs, Q, self, pn + q, pn + Q + q);
    free(f);
    free(self);
    return CS_OK;
}

/* Zeroed floats on a 64-byte boundary: a 512-bit load of a row that starts
 * there touches one cache line, not two (every row length of the reference
 * configuration is a multiple of 16 floats, so the rows stay aligned). */
enum { MODEL_ALIGN = 16 }; /* floats per 64 bytes */
static size_t pad16(size_t n) { return (n + MODEL_ALIGN - 1) / MODEL_ALIGN * MODEL_ALIGN; }
static float *falloc(size_t n)
{
    const size_t bytes = sizeof(float) * pad16(n ? n : 1);
    float *p = aligned_alloc(64, bytes);
    if (p) memset(p, 0, bytes);
    return p;
}

void model_free(model *m)
{
    if (!m) return;
    free(m->params); free(m->grads); free(m->wtall); free(m->mem); free(m->blk); free(m->norm);
    free(m->x); /* the per-block pointer arrays share one allocation */
    free(m);
}

cs_status model_alloc(model **out, const model_cfg *cfg, int Bmax)
{
    *out = NULL;
    cs_status st = model_cfg_check(cfg);
    if (st) return st;
    if (Bmax < 1) return cs_err(CS_EINPUT, "model: batch capacity %d must be >= 1", Bmax);
    model *m = calloc(1, sizeof *m);
    if (!m) return cs_err(CS_ENOMEM, "model: out of memory");
    m->cfg = *cfg;
    m->Bmax = Bmax;
    m->micro = MODEL_MICRO;
    const int L = cfg->L;
    m->blk = calloc((size_t)L, sizeof *m->blk);
    float **ptrs = calloc((size_t)15 * (L + 1), sizeof *ptrs);
    if (!m->blk || !ptrs) { free(ptrs); model_free(m); return cs_err(CS_ENOMEM, "model: out of memory"); }
    m->x = ptrs; m->ln1 = ptrs + (L + 1); m->mu1 = m->ln1 + L; m->rs1 = m->mu1 + L;
    m->qkv = m->rs1 + L; m->prob = m->qkv + L; m->att = m->prob + L; m->xm = m->att + L;
    m->ln2 = m->xm + L;
    m->mu2 = m->ln2 + L;
    m->rs2 = m->mu2 + L;
    m->h = m->rs2 + L;
    m->hs = m->h + L;
    m->hg = m->hs + L;
    m->Phi = m->hg + L;
    m->nparams = layout(cfg, m, &m->ndecay);
    m->params = falloc(m->nparams);
    m->grads = falloc(m->nparams);
    m->wtall = falloc(m->ndecay);
    m->nnorm = model_nnorm(cfg);
    m->norm = calloc(m->nnorm ? m->nnorm : 1, sizeof(float));
    if (m->norm) { /* identity z-scores (mean 0, 1/sd 1) until model_norm_fit */
        const int nu = model_cfg_nuse(cfg);
        for (int k = 0; model_cfg_stdz(cfg) && k < nu; k++) m->norm[nu + k] = 1.f;
        for (int q = 0; cfg->pair && q < PAIRATTN_Q; q++) m->norm[pair_norm_off(cfg) + PAIRATTN_Q + q] = 1.f;
    }

    const size_t N = (size_t)Bmax * cfg->T, C = cfg->C, F = cfg->F, B = Bmax;
    const size_t I = cfg->P + model_cfg_nuse(cfg), E = cfg->ncond + cfg->ntime, TP = (size_t)cfg->T * cfg->P;
    const size_t probn = cfg->joint ? B * cfg->H * cfg->T * cfg->T : 0;
    const size_t TTQ = cfg->pair ? (size_t)cfg->T * cfg->T * PAIRATTN_Q : 0;
    const size_t Phin = cfg->pair ? N * cfg->H * PAIRATTN_Q : 0;
    const size_t ascrn = cfg->pair ? pairattn_scratch_len(cfg->T, cfg->C, cfg->H)
                                   : nn_attention_scratch_len(cfg->T, cfg->C, cfg->H);
    if (!m->params || !m->grads || !m->wtall || !m->norm) {
        model_free(m);
        return cs_err(CS_ENOMEM, "model: out of memory");
    }
    /* Pass 0 counts the floats (every array rounded up to 64 bytes, so each
     * starts on a cache line), pass 1 hands them out. */
    for (int pass = 0; pass < 2; pass++) {
        size_t o = 0;
#define TAKE(n) (o += pad16(n), pass ? m->mem + o - pad16(n) : NULL)
        m->tin = TAKE(N * I); m->cin = TAKE(B * E);
        m->e1 = TAKE(B * C); m->e1g = TAKE(B * C); m->e = TAKE(B * C);
        m->lnf = TAKE(N * C); m->muf = TAKE(N); m->rsf = TAKE(N); m->out = TAKE(N * cfg->P);
        for (int l = 0; l <= L; l++) m->x[l] = TAKE(N * C);
        for (int l = 0; l < L; l++) {
            m->ln1[l] = TAKE(N * C); m->mu1[l] = TAKE(N); m->rs1[l] = TAKE(N);
            m->qkv[l] = TAKE(N * 3 * C); m->prob[l] = TAKE(probn); m->att[l] = TAKE(N * C);
            m->xm[l] = TAKE(N * C); m->ln2[l] = TAKE(N * C); m->mu2[l] = TAKE(N); m->rs2[l] = TAKE(N);
            m->h[l] = TAKE(N * F); m->hs[l] = TAKE(N * F); m->hg[l] = TAKE(N * F);
            m->Phi[l] = TAKE(Phin);
        }
        m->dx = TAKE(N * C); m->dtmp = TAKE(N * C); m->dln = TAKE(N * C);
        m->dqkv = TAKE(N * 3 * C); m->dh = TAKE(N * F); m->de = TAKE(B * C); m->de1 = TAKE(B * C);
        m->ascr = TAKE(ascrn);
        m->fm_xt = TAKE(B * TP); m->fm_u = TAKE(B * TP); m->fm_v = TAKE(B * TP); m->fm_dv = TAKE(B * TP);
        m->fm_t = TAKE(B);
        m->phi = TAKE(B * TTQ); m->phit = TAKE(B * TTQ);
#undef TAKE
        if (!pass && !(m->mem = falloc(o))) { model_free(m); return cs_err(CS_ENOMEM, "model: out of memory"); }
    }
    *out = m;
    return CS_OK;
}

static void init_matrix(float *w, size_t nout, size_t nin, double gain, gsl_rng *r)
{
    double sd = gain / sqrt((double)nin);
    for (size_t i = 0; i < nout * nin; i++) w[i] = (float)(sd * gsl_ran_gaussian_ziggurat(r, 1.0));
}

void model_init(model *m, gsl_rng *r)
{
    const model_cfg *c = &m->cfg;
    float *p = m->params;
    memset(p, 0, m->nparams * sizeof(float));
    const size_t C = c->C, F = c->F;
    const double res = 1.0 / sqrt(2.0 * c->L);
    init_matrix(p + m->tok_w, C, c->P + model_cfg_nuse(c), 1.0, r);
    init_matrix(p + m->e1_w, C, c->ncond + c->ntime, 1.0, r);
    init_matrix(p + m->e2_w, C, C, 1.0, r);
    for (int l = 0; l < c->L; l++) {
        init_matrix(p + m->blk[l].qkv_w, 3 * C, C, 1.0, r);
        init_matrix(p + m->blk[l].proj_w, C, C, res, r);
        init_matrix(p + m->blk[l].fc1_w, F, C, 1.0, r);
        init_matrix(p + m->blk[l].fc2_w, C, F, res, r);
        for (size_t i = 0; i < C; i++) p[m->blk[l].ln1_g + i] = p[m->blk[l].ln2_g + i] = 1.f;
    }
    init_matrix(p + m->head_w, c->P, C, 0.1, r);
    for (size_t i = 0; i < C; i++) p[m->lnf_g + i] = 1.f;
    /* pair weights last, so the draws of the model without pair terms are unchanged */
    for (int l = 0; c->pair && l < c->L; l++) {
        init_matrix(p + m->blk[l].pb_w, c->H, PAIRATTN_Q, 1.0, r);
        init_matrix(p + m->blk[l].pv_w, C, PAIRATTN_Q, 1.0, r);
    }
}

/* w^T of every weight matrix (the forward's B operands) into m->wtall, each
 * at its matrix's offset: once per training step or sampling call instead of
 * once per forward pass. */
static void transpose_all(model *m)
{
    const model_cfg *c = &m->cfg;
    const int C = c->C, F = c->F, I = c->P + model_cfg_nuse(c), E = c->ncond + c->ntime;
    const float *w = m->params;
    float *t = m->wtall;
    gemm_transpose(t + m->tok_w, w + m->tok_w, C, I);
    gemm_transpose(t + m->e1_w, w + m->e1_w, C, E);
    gemm_transpose(t + m->e2_w, w + m->e2_w, C, C);
    for (int l = 0; l < c->L; l++) {
        const model_block_off *o = &m->blk[l];
        gemm_transpose(t + o->qkv_w, w + o->qkv_w, 3 * C, C);
        gemm_transpose(t + o->proj_w, w + o->proj_w, C, C);
        gemm_transpose(t + o->fc1_w, w + o->fc1_w, F, C);
        gemm_transpose(t + o->fc2_w, w + o->fc2_w, C, F);
    }
    gemm_transpose(t + m->head_w, w + m->head_w, c->P, C);
    for (int l = 0; c->pair && l < c->L; l++)
        gemm_transpose(t + m->blk[l].pv_w, w + m->blk[l].pv_w, C, PAIRATTN_Q);
}

/* The pair geometry of B patches (pair model) from their raw features into
 * phi/phit (B*T*T*Q floats each); it depends on the features alone, so a
 * sampling call computes it once for all its Euler steps. */
static void pair_geometry(model *m, float *phi, float *phit, const float *feat, int B)
{
    const model_cfg *c = &m->cfg;
    const size_t TTQ = (size_t)c->T * c->T * PAIRATTN_Q;
    const float *pn = m->norm + pair_norm_off(c);
    for (int b = 0; c->pair && b < B; b++)
        pairattn_geometry(phi + b * TTQ, phit + b * TTQ, feat + (size_t)b * c->T * c->nfeat, c->nfeat,
                          c->T, pn, pn + PAIRATTN_Q);
}

/* model_forward on weights already transposed by transpose_all and (pair
 * model) the patches' geometry in phi/phit; 1 <= B <= Bmax checked by the
 * callers. keep = 0 (sampling) leaves out what only a backward reads: the
 * MLP's pre-activations and sigmoids are not stored (nn.h); v is the same. */
static void forward(model *m, int B, const float *xt, const float *feat, const float *cond,
                    const float *t, float *v, const float *phi, const float *phit, int keep)
{
    const model_cfg *c = &m->cfg;
    const int T = c->T, P = c->P, C = c->C, F = c->F, N = B * T;
    const int nu = model_cfg_nuse(c), I = P + nu, E = c->ncond + c->ntime, nh = c->ntime / 2;
    const float *w = m->params;
    float *wt = m->wtall;
    const nn_attn_mode mode = c->joint ? NN_ATTN_JOINT : NN_ATTN_SELF;
    m->B = B;
    const int nf = c->nfeat, stdz = model_cfg_stdz(c);
    for (int r = 0; r < N; r++) {
        memcpy(m->tin + (size_t)r * I, xt + (size_t)r * P, sizeof(float) * P);
        if (!stdz) memcpy(m->tin + (size_t)r * I + P, feat + (size_t)r * nf, sizeof(float) * nu);
        else /* standardised features */
            for (int k = 0; k < nu; k++)
                m->tin[(size_t)r * I + P + k] = (feat[(size_t)r * nf + k] - m->norm[k]) * m->norm[nu + k];
    }
    for (int b = 0; b < B; b++) {
        float *ci = m->cin + (size_t)b * E;
        memcpy(ci, cond + (size_t)b * c->ncond, sizeof(float) * c->ncond);
        double w0 = M_PI;
        for (int k = 0; k < nh; k++, w0 *= 2) {
            ci[c->ncond + k] = (float)sin(w0 * t[b]);
            ci[c->ncond + nh + k] = (float)cos(w0 * t[b]);
        }
    }
    nn_linear_forward(m->e1, m->cin, NULL, w + m->e1_b, B, E, C, wt + m->e1_w);
    nn_gelu_forward(m->e1g, m->e1, (size_t)B * C);
    nn_linear_forward(m->e, m->e1g, NULL, w + m->e2_b, B, C, C, wt + m->e2_w);
    nn_linear_forward(m->x[0], m->tin, NULL, w + m->tok_b, N, I, C, wt + m->tok_w);
    for (int b = 0; b < B; b++)
        for (int i = 0; i < T; i++) {
            float *row = m->x[0] + ((size_t)b * T + i) * C;
            nn_residual_forward(row, row, m->e + (size_t)b * C, C);
        }
    nn_layernorm_forward(m->ln1[0], m->mu1[0], m->rs1[0], m->x[0], w + m->blk[0].ln1_g,
                         w + m->blk[0].ln1_b, N, C);
    for (int l = 0; l < c->L; l++) {
        const model_block_off *o = &m->blk[l];
        /* Every layer runs fused with its product (nn.h): each strip of rows
         * gets its attention (per patch), bias, residual and the following
         * layer norm, or bias and GELU, while in cache; values as unfused. */
        if (c->pair)
            pairattn_linear_forward(m->qkv[l], m->att[l], m->prob[l], m->Phi[l], m->ln1[l], NULL,
                                    w + o->qkv_b, phi, phit, w + o->pb_w, wt + o->pv_w, B, T, C,
                                    c->H, mode, wt + o->qkv_w, m->ascr);
        else
            nn_linear_attention_forward(m->qkv[l], m->att[l], m->prob[l], m->ln1[l], NULL,
                                        w + o->qkv_b, B, T, C, c->H, mode, wt + o->qkv_w, m->ascr);
        nn_linear_bias_residual_forward(m->xm[l], m->att[l], NULL, w + o->proj_b, m->x[l],
                                        m->ln2[l], m->mu2[l], m->rs2[l], w + o->ln2_g, w + o->ln2_b,
                                        N, C, C, wt + o->proj_w);
        nn_linear_bias_gelu_forward(m->h[l], keep ? m->hs[l] : NULL, m->hg[l], m->ln2[l], NULL, w + o->fc1_b,
                                    N, C, F, wt + o->fc1_w);
        const int last = l + 1 == c->L;
        const size_t g_next = last ? m->lnf_g : m->blk[l + 1].ln1_g, b_next = last ? m->lnf_b : m->blk[l + 1].ln1_b;
        nn_linear_bias_residual_forward(m->x[l + 1], m->hg[l], NULL, w + o->fc2_b, m->xm[l],
                                        last ? m->lnf : m->ln1[l + 1], last ? m->muf : m->mu1[l + 1],
                                        last ? m->rsf : m->rs1[l + 1], w + g_next, w + b_next,
                                        N, F, C, wt + o->fc2_w);
    }
    nn_linear_forward(v, m->lnf, NULL, w + m->head_b, N, C, P, wt + m->head_w);
}

/* forward() on patches [b0, b0 + nb) of batch-wide arrays (xt and v hold T*P
 * values per patch): one pass of model_fm_grad or model_sample. The pass's
 * geometry is computed here into the front of m->phi (training), or, when
 * geom_all is set, was computed for the whole batch (sampling). */
static void forward_pass(model *m, int b0, int nb, const float *xt, const float *feat,
                         const float *cond, const float *t, float *v, int geom_all, int keep)
{
    const model_cfg *c = &m->cfg;
    const size_t TP = (size_t)c->T * c->P, TTQ = (size_t)c->T * c->T * PAIRATTN_Q;
    const float *fb = feat + (size_t)b0 * c->T * c->nfeat;
    if (!geom_all) pair_geometry(m, m->phi, m->phit, fb, nb);
    const size_t g = geom_all ? b0 * TTQ : 0;
    forward(m, nb, xt + b0 * TP, fb, cond + (size_t)b0 * c->ncond, t + b0, v + b0 * TP, m->phi + g,
            m->phit + g, keep);
}

/* Patches per pass (m->micro, or the whole batch when unset). */
static int pass_size(const model *m, int B) { return m->micro >= 1 ? m->micro : B; }

cs_status model_forward(model *m, int B, const float *xt, const float *feat,
                        const float *cond, const float *t, float *v)
{
    if (B < 1 || B > m->Bmax) return cs_err(CS_EINPUT, "model_forward: batch %d outside 1..%d", B, m->Bmax);
    transpose_all(m);
    pair_geometry(m, m->phi, m->phit, feat, B);
    forward(m, B, xt, feat, cond, t, v, m->phi, m->phit, 1);
    return CS_OK;
}

/* zero = 0 adds this pass's gradients to m->grads (model_fm_grad's later
 * passes): every gradient is accumulated row by row or by an fma chain over
 * rows (nn.h), so a batch in passes gives the chains of the whole batch. */
static void backward(model *m, const float *dv, int zero)
{
    const model_cfg *c = &m->cfg;
    const int B = m->B, T = c->T, P = c->P, C = c->C, F = c->F, N = B * T;
    const int I = P + model_cfg_nuse(c), E = c->ncond + c->ntime;
    const float *w = m->params;
    float *g = m->grads;
    const nn_attn_mode mode = c->joint ? NN_ATTN_JOINT : NN_ATTN_SELF;
    if (zero) memset(g, 0, m->nparams * sizeof(float));
    nn_linear_backward(m->dln, g + m->head_w, g + m->head_b, dv, m->lnf, w + m->head_w, N, C, P);
    memset(m->dx, 0, sizeof(float) * (size_t)N * C);
    nn_layernorm_backward(m->dx, g + m->lnf_g, g + m->lnf_b, m->dln, m->x[c->L], m->muf, m->rsf, w + m->lnf_g, N, C);
    for (int l = c->L - 1; l >= 0; l--) {
        const model_block_off *o = &m->blk[l];
        /* dx holds d x[l+1]; the residual passes it straight to xm[l]. */
        nn_linear_backward_gelu(m->dh, g + o->fc2_w, g + o->fc2_b, m->dx, m->hg[l], w + o->fc2_w,
                                m->h[l], m->hs[l], N, F, C);
        nn_linear_backward(m->dln, g + o->fc1_w, g + o->fc1_b, m->dh, m->ln2[l], w + o->fc1_w, N, C, F);
        nn_layernorm_backward(m->dx, g + o->ln2_g, g + o->ln2_b, m->dln, m->xm[l], m->mu2[l], m->rs2[l], w + o->ln2_g,
                              N, C);
        if (c->pair)
            pairattn_linear_backward(m->dqkv, m->dtmp, g + o->proj_w, g + o->proj_b, g + o->pb_w,
                                     g + o->pv_w, m->dx, m->att[l], w + o->proj_w, m->qkv[l], m->prob[l],
                                     m->Phi[l], m->phi, m->phit, w + o->pv_w, B, T, C, c->H, mode, m->ascr);
        else
            nn_linear_backward_attention(m->dqkv, m->dtmp, g + o->proj_w, g + o->proj_b, m->dx, m->att[l],
                                         w + o->proj_w, m->qkv[l], m->prob[l], B, T, C, c->H, mode, m->ascr);
        nn_linear_backward_qkv(m->dln, g + o->qkv_w, g + o->qkv_b, m->dqkv, m->ln1[l], w + o->qkv_w, N, C, mode);
        nn_layernorm_backward(m->dx, g + o->ln1_g, g + o->ln1_b, m->dln, m->x[l], m->mu1[l], m->rs1[l], w + o->ln1_g, N,
                              C);
    }
    nn_linear_backward(NULL, g + m->tok_w, g + m->tok_b, m->dx, m->tin, w + m->tok_w, N, I, C);
    memset(m->de, 0, sizeof(float) * (size_t)B * C);
    for (int b = 0; b < B; b++)
        for (int i = 0; i < T; i++)
            nn_residual_backward(m->de + (size_t)b * C, m->dx + ((size_t)b * T + i) * C, C);
    nn_linear_backward(m->de1, g + m->e2_w, g + m->e2_b, m->de, m->e1g, w + m->e2_w, B, C, C);
    nn_gelu_backward(m->de1, m->de1, m->e1, (size_t)B * C);
    nn_linear_backward(NULL, g + m->e1_w, g + m->e1_b, m->de1, m->cin, w + m->e1_w, B, E, C);
}

void model_backward(model *m, const float *dv) { backward(m, dv, 1); }

void model_fm_draw(gsl_rng *noise, int B, int n, const float *x1, float *xt, float *u, float *t)
{
    for (int b = 0; b < B; b++) {
        float tb = (float)gsl_rng_uniform(noise);
        t[b] = tb;
        for (int k = 0; k < n; k++) {
            size_t i = (size_t)b * n + k;
            float x0 = (float)gsl_ran_gaussian_ziggurat(noise, 1.0);
            xt[i] = (1.f - tb) * x0 + tb * x1[i];
            u[i] = x1[i] - x0;
        }
    }
}

/* *s += sum of (v - u)^2 in index order (double); dv = k (v - u). */
static void fm_loss_add(const float *v, const float *u, size_t n, float k, float *dv, double *s)
{
    double acc = *s;
    for (size_t i = 0; i < n; i++) {
        float d = v[i] - u[i];
        acc += (double)d * d;
        if (dv) dv[i] = k * d;
    }
    *s = acc;
}

double model_fm_loss(const float *v, const float *u, size_t n, float *dv)
{
    double s = 0;
    fm_loss_add(v, u, n, 2.f / (float)n, dv, &s);
    return s / (double)n;
}

/* The batch goes through forward, loss and backward in passes of m->micro
 * patches: at the reference batch the activations of all 64 patches (about
 * 28 MB) spill out of the caches, those of MODEL_MICRO = 4 patches do not. The noise is
 * drawn for the whole batch first, the loss is one sum in order with the
 * whole batch's scale 2/n, and the gradients accumulate pass after pass, so
 * the results are those of one pass (tested bit for bit). */
cs_status model_fm_grad(model *m, gsl_rng *noise, int B, const float *x1,
                        const float *feat, const float *cond, double *loss)
{
    const model_cfg *c = &m->cfg;
    const int n = c->T * c->P;
    if (B < 1 || B > m->Bmax) return cs_err(CS_EINPUT, "model_fm_grad: batch %d outside 1..%d", B, m->Bmax);
    model_fm_draw(noise, B, n, x1, m->fm_xt, m->fm_u, m->fm_t);
    transpose_all(m);
    const int mb = pass_size(m, B);
    const size_t ntot = (size_t)B * n;
    const float k = 2.f / (float)ntot;
    double s = 0;
    for (int b0 = 0; b0 < B; b0 += mb) {
        const int nb = B - b0 < mb ? B - b0 : mb;
        const size_t o = (size_t)b0 * n;
        forward_pass(m, b0, nb, m->fm_xt, feat, cond, m->fm_t, m->fm_v, 0, 1);
        fm_loss_add(m->fm_v + o, m->fm_u + o, (size_t)nb * n, k, m->fm_dv + o, &s);
        if (!isfinite(s)) return cs_err(CS_ENUMERIC, "flow-matching loss is not finite (%g)", s / (double)ntot);
        backward(m, m->fm_dv + o, b0 == 0);
    }
    *loss = s / (double)ntot;
    return CS_OK;
}

cs_status model_sample(model *m, gsl_rng *noise, int B, const float *feat,
                       const float *cond, int nsteps, float *x)
{
    const size_t n = (size_t)B * m->cfg.T * m->cfg.P;
    if (B < 1 || B > m->Bmax) return cs_err(CS_EINPUT, "model_sample: batch %d outside 1..%d", B, m->Bmax);
    if (nsteps < 1) return cs_err(CS_EINPUT, "model_sample: nsteps %d must be >= 1", nsteps);
    for (size_t i = 0; i < n; i++) x[i] = (float)gsl_ran_gaussian_ziggurat(noise, 1.0);
    const float dt = 1.f / (float)nsteps;
    const int mb = pass_size(m, B);
    transpose_all(m);
    pair_geometry(m, m->phi, m->phit, feat, B);
    for (int k = 0; k < nsteps; k++) {
        float tk = (float)k / (float)nsteps;
        for (int b = 0; b < B; b++) m->fm_t[b] = tk;
        /* in passes of m->micro patches, as model_fm_grad: patches do not
         * interact in the forward, so v is the same as in one pass */
        for (int b0 = 0; b0 < B; b0 += mb)
            forward_pass(m, b0, B - b0 < mb ? B - b0 : mb, x, feat, cond, m->fm_t, m->fm_v, 1, 0);
        for (size_t i = 0; i < n; i++) x[i] += dt * m->fm_v[i];
    }
    for (size_t i = 0; i < n; i++)
        if (!isfinite(x[i])) return cs_err(CS_ENUMERIC, "model_sample: non-finite sample");
    return CS_OK;
}

double model_train_flops(const model_cfg *c, int B)
{
    const double N = (double)B * c->T, C = c->C, F = c->F, T = c->T, hd = (double)c->C / c->H;
    const double I = c->P + model_cfg_nuse(c), E = c->ncond + c->ntime;
    double gemm_fwd = 2 * N * (I * C + 3 * C * C * c->L + C * C * c->L + 2 * C * F * c->L + C * c->P)
                    + 2.0 * B * (E * C + C * C);
    /* backward: weight gradients for all, input gradients for all but the token and e1 layers */
    double gemm_bwd = 2 * gemm_fwd - 2 * N * I * C - 2.0 * B * E * C;
    double attn = c->joint ? 2.0 * B * c->H * T * T * hd * 2 * c->L : 0; /* QK^T and PV */
    /* pair terms per patch and block: beta, Phi, the value term and, backward,
     * dPhi, dWv, dP's term and dwb (joint); the value term, dPhi, dWv (self) */
    const double TT = T * T, Q = PAIRATTN_Q;
    double pair = !c->pair ? 0 : 2.0 * B * c->L * (c->joint ? 4 * c->H * TT * Q + 3 * T * C * Q : 3 * T * C * Q);
    return gemm_fwd + gemm_bwd + 3 * attn + pair; /* attention backward = 4 products = 2x forward */
}

cs_status model_sample_radii(model *m, int Bmax, const patch_set *ps, int n, int nsteps,
                                gsl_rng *noise, gsl_rng *perm, double *r)
{
    size_t tp = (size_t)PATCH_T * PATCH_P;
    float *x = malloc((size_t)Bmax * tp * sizeof *x);
    float *feat = malloc((size_t)Bmax * PATCH_T * PATCH_NFEAT * sizeof *feat);
    cs_status st = x && feat ? CS_OK : cs_err(CS_ENOMEM, "out of memory");
    for (int k0 = 0; k0 < n && !st; k0 += Bmax) {
        int b = n - k0 < Bmax ? n - k0 : Bmax;
        memcpy(feat, ps->feat + (size_t)k0 * PATCH_T * PATCH_NFEAT, (size_t)b * PATCH_T * PATCH_NFEAT * sizeof *feat);
        if (perm) patch_shuffle_positions(feat, b, perm);
        st = model_sample(m, noise, b, feat, ps->cond + (size_t)k0 * PATCH_NCOND, nsteps, x);
        for (int k = 0; k < b && !st; k++)
            patch_set_radii(ps, k0 + k, x + (size_t)k * tp, r + (size_t)(k0 + k) * tp);
    }
    free(x);
    free(feat);
    return st;
}

