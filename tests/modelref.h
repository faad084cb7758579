/* Double-precision reference forward of the whole model (src/model/model.c), built
 * from the naive kernels in tests/nnref.h and the model's parameter offsets.
 * Used for finite-difference gradient checks and forward agreement. */
#ifndef MODELREF_H
#define MODELREF_H
#include "nnref.h"
#include "pairref.h"
#include "model.h"

static void ref_model_forward(const model *m, const double *p, int B, const double *xt,
                              const double *feat, const double *cond, const double *t, double *v)
{
    const model_cfg *c = &m->cfg;
    const int nu = model_cfg_nuse(c), stdz = model_cfg_stdz(c);
    const int T = c->T, P = c->P, C = c->C, F = c->F, N = B * T, I = P + nu;
    const int E = c->ncond + c->ntime, nh = c->ntime / 2;
    double *tin = malloc(sizeof(double) * N * I), *cin = malloc(sizeof(double) * B * E);
    double *e1 = malloc(sizeof(double) * B * C), *e = malloc(sizeof(double) * B * C);
    double *x = malloc(sizeof(double) * N * C), *ln = malloc(sizeof(double) * N * C);
    double *qkv = malloc(sizeof(double) * N * 3 * C), *att = malloc(sizeof(double) * N * C);
    double *tmp = malloc(sizeof(double) * N * C), *h = malloc(sizeof(double) * N * F);
    for (int r = 0; r < N; r++) {
        for (int k = 0; k < P; k++) tin[r * I + k] = xt[r * P + k];
        for (int k = 0; k < nu; k++) /* standardised with m->norm, or as they are */
            tin[r * I + P + k] = stdz ? (feat[r * c->nfeat + k] - m->norm[k]) * m->norm[nu + k]
                                      : feat[r * c->nfeat + k];
    }
    /* pair model: standardised pair features of every patch from the raw features */
    double *phi = c->pair ? malloc(sizeof(double) * (size_t)B * T * T * REF_PQ) : NULL;
    for (int b = 0; c->pair && b < B; b++) {
        double *pb = phi + (size_t)b * T * T * REF_PQ;
        ref_pair_features(pb, feat + (size_t)b * T * c->nfeat, c->nfeat, T);
        const float *mu = m->norm + (stdz ? 2 * nu : 0), *isd = mu + REF_PQ;
        for (int e = 0; e < T * T * REF_PQ; e++) pb[e] = (pb[e] - mu[e % REF_PQ]) * isd[e % REF_PQ];
    }
    for (int b = 0; b < B; b++) {
        for (int k = 0; k < c->ncond; k++) cin[b * E + k] = cond[b * c->ncond + k];
        for (int k = 0; k < nh; k++) {
            double w = M_PI * ldexp(1.0, k);
            cin[b * E + c->ncond + k] = sin(w * t[b]);
            cin[b * E + c->ncond + nh + k] = cos(w * t[b]);
        }
    }
    ref_linear(e1, cin, p + m->e1_w, p + m->e1_b, B, E, C);
    ref_gelu(e1, e1, (size_t)B * C);
    ref_linear(e, e1, p + m->e2_w, p + m->e2_b, B, C, C);
    ref_linear(x, tin, p + m->tok_w, p + m->tok_b, N, I, C);
    for (int r = 0; r < N; r++)
        for (int k = 0; k < C; k++) x[r * C + k] += e[(r / T) * C + k];
    for (int l = 0; l < c->L; l++) {
        const model_block_off *o = &m->blk[l];
        ref_layernorm(ln, x, p + o->ln1_g, p + o->ln1_b, N, C);
        ref_linear(qkv, ln, p + o->qkv_w, p + o->qkv_b, N, C, 3 * C);
        if (c->pair) ref_pair_attention(att, qkv, phi, p + o->pb_w, p + o->pv_w, B, T, C, c->H, c->joint ? 0 : 1);
        else ref_attention(att, qkv, B, T, C, c->H, c->joint ? 0 : 1);
        ref_linear(tmp, att, p + o->proj_w, p + o->proj_b, N, C, C);
        for (int i = 0; i < N * C; i++) x[i] += tmp[i];
        ref_layernorm(ln, x, p + o->ln2_g, p + o->ln2_b, N, C);
        ref_linear(h, ln, p + o->fc1_w, p + o->fc1_b, N, C, F);
        ref_gelu(h, h, (size_t)N * F);
        ref_linear(tmp, h, p + o->fc2_w, p + o->fc2_b, N, F, C);
        for (int i = 0; i < N * C; i++) x[i] += tmp[i];
    }
    ref_layernorm(ln, x, p + m->lnf_g, p + m->lnf_b, N, C);
    ref_linear(v, ln, p + m->head_w, p + m->head_b, N, C, P);
    free(phi);
    free(tin); free(cin); free(e1); free(e); free(x); free(ln); free(qkv); free(att); free(tmp); free(h);
}
#endif
