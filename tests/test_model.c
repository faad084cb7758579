/* Tests for src/model/model.c: parameter layout, forward agreement with the double
 * reference (tests/modelref.h), whole-model gradients against central finite
 * differences for both arms, the independence of the self-attention arm, and
 * the flow-matching loss pieces (paper Eq. 2). Tiny configuration. */
#include "testutil.h"
#include "modelref.h"
#include "model.h"
#include "pairattn.h"
#include <gsl/gsl_randist.h>

/* pair: the pair reading (standardised features, pair-aware attention) */
static model_cfg tiny2(int joint, int pair)
{
    model_cfg c = {.T = 5, .P = 6, .nfeat = 3, .ncond = 2, .ntime = 4,
                   .C = 8, .L = 2, .H = 2, .F = 12, .joint = joint, .pair = pair};
    return c;
}
static model_cfg tiny(int joint) { return tiny2(joint, 0); }
/* A tiny configuration under reading r, with nfeat = 5 so that the paper
 * reading's three features are fewer than all of them. */
static model_cfg tiny_reading(int joint, model_reading r)
{
    model_cfg c = tiny2(joint, 0);
    c.nfeat = 5;
    model_cfg_set_reading(&c, r);
    return c;
}

typedef struct {
    model *m; int B;
    float *xt, *feat, *cond, *t, *v, *dv;
    double *p, *xt_d, *feat_d, *cond_d, *t_d, *v_d, *dv_d;
} fx;

static void fx_make_cfg(fx *f, model_cfg c, int B, unsigned seed);
static void fx_make2(fx *f, int joint, int pair, int B, unsigned seed) { fx_make_cfg(f, tiny2(joint, pair), B, seed); }
static void fx_make_cfg(fx *f, model_cfg c, int B, unsigned seed)
{
    assert_int_equal(model_alloc(&f->m, &c, B), CS_OK);
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(r, 11);
    model_init(f->m, r);
    gsl_rng_free(r);
    /* Perturb everything so LN gains/biases and zero-initialised biases matter. */
    unsigned st = seed;
    float *noise = malloc(sizeof(float) * f->m->nparams);
    tu_fill(noise, f->m->nparams, 0.3f, &st);
    for (size_t i = 0; i < f->m->nparams; i++) f->m->params[i] += noise[i];
    free(noise);
    f->B = B;
    size_t nx = (size_t)B * c.T * c.P;
    f->xt = malloc(sizeof(float) * nx); f->v = malloc(sizeof(float) * nx); f->dv = malloc(sizeof(float) * nx);
    f->feat = malloc(sizeof(float) * B * c.T * c.nfeat); f->cond = malloc(sizeof(float) * B * c.ncond);
    f->t = malloc(sizeof(float) * B);
    tu_fill(f->xt, nx, 1.5f, &st); tu_fill(f->dv, nx, 1, &st);
    tu_fill(f->feat, (size_t)B * c.T * c.nfeat, 1, &st); tu_fill(f->cond, (size_t)B * c.ncond, 1, &st);
    for (int b = 0; b < B; b++) f->t[b] = 0.2f + 0.5f * b;
    f->p = malloc(sizeof(double) * f->m->nparams); tu_f2d(f->p, f->m->params, f->m->nparams);
    f->xt_d = malloc(sizeof(double) * nx); tu_f2d(f->xt_d, f->xt, nx);
    f->dv_d = malloc(sizeof(double) * nx); tu_f2d(f->dv_d, f->dv, nx);
    f->v_d = malloc(sizeof(double) * nx);
    f->feat_d = malloc(sizeof(double) * B * c.T * c.nfeat); tu_f2d(f->feat_d, f->feat, (size_t)B * c.T * c.nfeat);
    f->cond_d = malloc(sizeof(double) * B * c.ncond); tu_f2d(f->cond_d, f->cond, (size_t)B * c.ncond);
    f->t_d = malloc(sizeof(double) * B); tu_f2d(f->t_d, f->t, B);
    if (model_cfg_stdz(&c) || c.pair) { /* z-scores of these very features, so standardisation is not the identity */
        for (int i = 0; i < B * c.T; i++) f->feat[i * c.nfeat + 2] = 0.3f + 0.1f * f->feat[i * c.nfeat + 2];
        tu_f2d(f->feat_d, f->feat, (size_t)B * c.T * c.nfeat);
        assert_int_equal(model_norm_fit(f->m, f->feat, B), CS_OK);
    }
}
static void fx_make(fx *f, int joint, int B, unsigned seed) { fx_make2(f, joint, 0, B, seed); }

static void fx_free(fx *f)
{
    model_free(f->m);
    free(f->xt); free(f->feat); free(f->cond); free(f->t); free(f->v); free(f->dv);
    free(f->p); free(f->xt_d); free(f->feat_d); free(f->cond_d); free(f->t_d); free(f->v_d); free(f->dv_d);
}

static double fx_loss(void *ctx)
{
    fx *f = ctx;
    ref_model_forward(f->m, f->p, f->B, f->xt_d, f->feat_d, f->cond_d, f->t_d, f->v_d);
    return tu_dot(f->v_d, f->dv_d, (size_t)f->B * f->m->cfg.T * f->m->cfg.P);
}

static void test_arms_have_identical_parameter_count(void **s)
{
    (void)s;
    model_cfg j = tiny(1), i = tiny(0);
    assert_int_equal(model_nparams(&j), model_nparams(&i));
    model_cfg rj = model_cfg_reference(5), ri = rj;
    ri.joint = 0;
    assert_int_equal(model_nparams(&rj), model_nparams(&ri));
    model *mj, *mi;
    assert_int_equal(model_alloc(&mj, &rj, 2), CS_OK);
    assert_int_equal(model_alloc(&mi, &ri, 2), CS_OK);
    assert_int_equal(mj->nparams, mi->nparams);
    assert_int_equal(mj->nparams, model_nparams(&rj));
    model_free(mj); model_free(mi);
}

static void test_bad_config_is_rejected(void **s)
{
    (void)s;
    model_cfg c = tiny(1);
    c.H = 3; /* 8 % 3 != 0 */
    model *m = NULL;
    assert_int_equal(model_alloc(&m, &c, 2), CS_EINPUT);
    assert_null(m);
    assert_non_null(strstr(cs_errmsg(), "heads"));
    c = tiny2(1, 1);
    c.nfeat = 2; /* the pair geometry needs x, y and rbar */
    assert_int_equal(model_alloc(&m, &c, 2), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "nfeat"));
    c = tiny2(1, 2);
    assert_int_equal(model_alloc(&m, &c, 2), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "pair"));
}

static void check_forward2(int joint, int pair)
{
    fx f;
    fx_make2(&f, joint, pair, 2, 21);
    assert_int_equal(model_forward(f.m, f.B, f.xt, f.feat, f.cond, f.t, f.v), CS_OK);
    fx_loss(&f);
    ASSERT_GRAD(f.v, f.v_d, (size_t)f.B * 5 * 6, 2e-5, "model forward");
    fx_free(&f);
}
static void check_forward(int joint) { check_forward2(joint, 0); }
static void test_forward_matches_reference_joint(void **s) { (void)s; check_forward(1); }
static void test_pair_forward_matches_reference_joint(void **s) { (void)s; check_forward2(1, 1); }
static void test_pair_forward_matches_reference_independent(void **s) { (void)s; check_forward2(0, 1); }
static void test_forward_matches_reference_independent(void **s) { (void)s; check_forward(0); }

static void check_gradients2(int joint, int pair)
{
    fx f;
    fx_make2(&f, joint, pair, 2, 31 + joint);
    assert_int_equal(model_forward(f.m, f.B, f.xt, f.feat, f.cond, f.t, f.v), CS_OK);
    model_backward(f.m, f.dv);
    double *g = malloc(sizeof(double) * f.m->nparams);
    tu_fd_grad(g, f.p, f.m->nparams, fx_loss, &f, 1e-5);
    ASSERT_GRAD(f.m->grads, g, f.m->nparams, 5e-4, joint ? "joint model d/dparams" : "independent model d/dparams");
    if (pair) { /* the pair parameters, with %.17g, and the self arm's dead score weights */
        for (int l = 0; l < f.m->cfg.L; l++) {
            const model_block_off *o = &f.m->blk[l];
            size_t nb = (size_t)f.m->cfg.H * 8, nv = (size_t)f.m->cfg.C * 8, w;
            double e = tu_maxrel(f.m->grads + o->pv_w, g + o->pv_w, nv, &w);
            if (!(e <= 5e-4)) { print_error("block %d d/dpv_w[%zu]: observed %.17g, expected %.17g\n", l, w,
                                            (double)f.m->grads[o->pv_w + w], g[o->pv_w + w]); fail(); }
            e = tu_maxrel(f.m->grads + o->pb_w, g + o->pb_w, nb, &w);
            if (!(e <= 5e-4)) { print_error("block %d d/dpb_w[%zu]: observed %.17g, expected %.17g\n", l, w,
                                            (double)f.m->grads[o->pb_w + w], g[o->pb_w + w]); fail(); }
            /* joint: every value weight is live (self pairs alone leave the
             * antisymmetric features dx, dy, cos, sin at their mean, 0) */
            for (size_t i = 0; joint && i < nv; i++) assert_true(g[o->pv_w + i] != 0.0);
            for (size_t i = 0; !joint && i < nb; i++) ASSERT_EXACT(f.m->grads[o->pb_w + i], 0.0);
        }
    }
    free(g);
    fx_free(&f);
}
static void check_gradients(int joint) { check_gradients2(joint, 0); }
static void test_gradients_joint(void **s) { (void)s; check_gradients(1); }
static void test_pair_gradients_joint(void **s) { (void)s; check_gradients2(1, 1); }
static void test_pair_gradients_independent(void **s) { (void)s; check_gradients2(0, 1); }
static void test_gradients_independent(void **s) { (void)s; check_gradients(0); }

/* Changing every other token of the patch leaves token 0's velocity bit-identical
 * in the independent arm, and changes it in the joint arm. */
static void check_isolation2(int joint, int pair)
{
    fx f;
    fx_make2(&f, joint, pair, 1, 41);
    const int T = 5, P = 6, nf = 3;
    float out_a[T * P], out_b[T * P];
    assert_int_equal(model_forward(f.m, 1, f.xt, f.feat, f.cond, f.t, out_a), CS_OK);
    for (int i = 1; i < T; i++) {
        for (int k = 0; k < P; k++) f.xt[i * P + k] += 0.7f;
        for (int k = 0; k < nf; k++) f.feat[i * nf + k] -= 0.4f;
    }
    assert_int_equal(model_forward(f.m, 1, f.xt, f.feat, f.cond, f.t, out_b), CS_OK);
    int same = 1;
    for (int k = 0; k < P; k++) same &= (out_a[k] == out_b[k]);
    assert_int_equal(same, !joint);
    fx_free(&f);
}
static void check_isolation(int joint) { check_isolation2(joint, 0); }
static void test_independent_token_ignores_other_tokens(void **s) { (void)s; check_isolation(0); }
static void test_pair_independent_token_ignores_other_tokens(void **s) { (void)s; check_isolation2(0, 1); }
static void test_pair_joint_token_sees_other_tokens(void **s) { (void)s; check_isolation2(1, 1); }

/* The pair parameters come after every parameter of the model without pair
 * terms (whose layout and
 * initial draws stay as they were), L x (H + C) x Q of them, decayed; both
 * arms have them. */
static void test_pair_layout_extends_the_plain_layout(void **s)
{
    (void)s;
    model_cfg c0 = model_cfg_reference(5), c1 = c0, i1 = c0;
    c1.pair = 1; i1.pair = 1; i1.joint = 0;
    assert_int_equal(model_nparams(&c1), model_nparams(&c0) + (size_t)c0.L * (c0.H + c0.C) * 8);
    assert_int_equal(model_nparams(&c1), model_nparams(&i1));
    model *m0, *m1;
    assert_int_equal(model_alloc(&m0, &c0, 1), CS_OK);
    assert_int_equal(model_alloc(&m1, &c1, 1), CS_OK);
    assert_int_equal(m1->ndecay, m0->ndecay + (size_t)c0.L * (c0.H + c0.C) * 8);
    assert_int_equal(m1->head_w, m0->head_w);
    assert_int_equal(m1->blk[0].pb_w, m0->ndecay);
    assert_int_equal(m1->nnorm, 2 * (size_t)c0.nfeat + 16);
    assert_int_equal(m0->nnorm, 0);
    gsl_rng *rng0 = gsl_rng_alloc(gsl_rng_mt19937), *rng1 = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng0, 4); gsl_rng_set(rng1, 4);
    model_init(m0, rng0); model_init(m1, rng1);
    assert_memory_equal(m0->params, m1->params, sizeof(float) * m0->ndecay);
    gsl_rng_free(rng0); gsl_rng_free(rng1);
    model_free(m0); model_free(m1);
}

/* z-scores: mean 0 and sd 1 of each standardised token feature and of the
 * pair features over the pairs i != j. */
static void test_pair_norm_fit_standardises(void **s)
{
    (void)s;
    enum { B = 3 };
    model_cfg c = tiny2(1, 1);
    model *m;
    assert_int_equal(model_alloc(&m, &c, B), CS_OK);
    float feat[B * 5 * 3];
    unsigned st = 61;
    tu_fill(feat, B * 5 * 3, 2.f, &st);
    assert_int_equal(model_norm_fit(m, feat, B), CS_OK);
    for (int k = 0; k < 3; k++) {
        double sum = 0, ss = 0;
        for (int i = 0; i < B * 5; i++) {
            double z = ((double)feat[i * 3 + k] - m->norm[k]) * m->norm[3 + k];
            sum += z;
            ss += z * z;
        }
        ASSERT_NEAR(sum / (B * 5), 0.0, 1e-6);
        ASSERT_NEAR(ss / (B * 5), 1.0, 1e-5);
    }
    float f[25 * 8];
    double sum[8] = {0}, ss[8] = {0};
    for (int b = 0; b < B; b++) {
        pairattn_features(f, feat + b * 15, 3, 5);
        for (int e = 0; e < 25; e++)
            for (int q = 0; e % 6 && q < 8; q++) {
                double z = ((double)f[e * 8 + q] - m->norm[6 + q]) * m->norm[14 + q];
                sum[q] += z; ss[q] += z * z;
            }
    }
    for (int q = 0; q < 8; q++) {
        ASSERT_NEAR(sum[q] / (B * 20), 0.0, 1e-6);
        ASSERT_NEAR(ss[q] / (B * 20), 1.0, 1e-5);
    }
    model_free(m);
}
static void test_joint_token_sees_other_tokens(void **s) { (void)s; check_isolation(1); }

static void test_fm_draw_is_linear_path(void **s)
{
    (void)s;
    enum { B = 3, n = 7 };
    float x1[B * n], xt[B * n], u[B * n], t[B];
    unsigned st = 5;
    tu_fill(x1, B * n, 2, &st);
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937), *rng_ref = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(r, 3); gsl_rng_set(rng_ref, 3);
    model_fm_draw(r, B, n, x1, xt, u, t);
    for (int b = 0; b < B; b++) {
        ASSERT_EXACT(t[b], (float)gsl_rng_uniform(rng_ref));
        assert_true(t[b] >= 0.f && t[b] < 1.f);
        for (int k = 0; k < n; k++) {
            float x0 = (float)gsl_ran_gaussian_ziggurat(rng_ref, 1.0);
            ASSERT_EXACT(u[b * n + k], x1[b * n + k] - x0);
            ASSERT_EXACT(xt[b * n + k], (1.f - t[b]) * x0 + t[b] * x1[b * n + k]);
        }
    }
    gsl_rng_free(r); gsl_rng_free(rng_ref);
}

static void test_fm_loss_is_mse_with_its_gradient(void **s)
{
    (void)s;
    float v[4] = {1, 2, 3, 4}, u[4] = {0, 2, 5, 4}, dv[4];
    ASSERT_NEAR(model_fm_loss(v, u, 4, dv), (1.0 + 0 + 4 + 0) / 4, 1e-12);
    ASSERT_NEAR(dv[0], 0.5, 1e-7);
    ASSERT_NEAR(dv[2], -1.0, 1e-7);
    ASSERT_EXACT(dv[1], 0.0);
}

/* A reference-shape model for batch B run in passes of `micro` patches,
 * initialised from *r = mt19937(seed), which the caller goes on drawing from. */
static model *pass_model(const model_cfg *c, int B, int micro, unsigned long seed, gsl_rng **r)
{
    model *m = NULL;
    assert_int_equal(model_alloc(&m, c, B), CS_OK);
    *r = gsl_rng_alloc(gsl_rng_mt19937);
    assert_non_null(*r);
    gsl_rng_set(*r, seed);
    model_init(m, *r);
    m->micro = micro;
    return m;
}

/* model_fm_grad runs the batch in passes of m->micro patches (so that a
 * pass's activations stay in cache). Every gradient element is still one
 * chain over the batch's rows in order, and the loss one sum in order, so
 * gradients and loss are bit-identical for any pass size: whole batch, 3
 * (passes of 3, 3, 1) and 1. Reference shapes, so the attention kernels of
 * the training runs are the ones exercised. */
static void check_fm_grad_passes(int pair)
{
    enum { B = 7 };
    model_cfg c = model_cfg_reference(3);
    c.pair = pair;
    const size_t n = (size_t)c.T * c.P;
    float *x1 = malloc(sizeof(float) * B * n), *feat = malloc(sizeof(float) * B * c.T * c.nfeat);
    float cond[B * 3];
    unsigned st = 77;
    tu_fill(x1, B * n, 1, &st); tu_fill(feat, (size_t)B * c.T * c.nfeat, 1, &st); tu_fill(cond, B * 3, 1, &st);
    const int passes[] = {B, 3, 1};
    float *g0 = NULL, *v0 = NULL;
    double l0 = 0;
    for (int k = 0; k < 3; k++) {
        gsl_rng *r = NULL;
        model *m = pass_model(&c, B, passes[k], 5, &r);
        double l = 0;
        assert_int_equal(model_fm_grad(m, r, B, x1, feat, cond, &l), CS_OK);
        if (k == 0) {
            g0 = malloc(sizeof(float) * m->nparams); v0 = malloc(sizeof(float) * B * n);
            memcpy(g0, m->grads, sizeof(float) * m->nparams); memcpy(v0, m->fm_v, sizeof(float) * B * n);
            l0 = l;
        } else {
            if (l != l0) { print_error("pass %d: loss %.17g, whole batch %.17g\n", passes[k], l, l0); fail(); }
            for (size_t i = 0; i < m->nparams; i++)
                if (memcmp(&m->grads[i], &g0[i], sizeof(float)) != 0) {
                    print_error("pass %d: grad %zu = %.17g, whole batch %.17g\n", passes[k], i,
                                (double)m->grads[i], (double)g0[i]);
                    fail();
                }
            assert_memory_equal(m->fm_v, v0, sizeof(float) * B * n);
        }
        gsl_rng_free(r);
        model_free(m);
    }
    free(g0); free(v0); free(x1); free(feat);
}
static void test_fm_grad_same_bits_for_any_pass_size(void **s) { (void)s; check_fm_grad_passes(0); }
static void test_pair_fm_grad_same_bits_for_any_pass_size(void **s) { (void)s; check_fm_grad_passes(1); }

/* model_sample runs each Euler step's forward in passes of m->micro patches
 * (patches do not interact in the forward): the same samples for any pass
 * size. */
static void check_sample_passes(int pair)
{
    enum { B = 5, STEPS = 3 };
    model_cfg c = model_cfg_reference(3);
    c.pair = pair;
    const size_t n = (size_t)B * c.T * c.P;
    float *feat = malloc(sizeof(float) * B * c.T * c.nfeat), cond[B * 3];
    float *x0 = malloc(sizeof(float) * n), *x1 = malloc(sizeof(float) * n);
    unsigned st = 91;
    tu_fill(feat, (size_t)B * c.T * c.nfeat, 1, &st); tu_fill(cond, B * 3, 1, &st);
    const int passes[] = {B, 2};
    for (int k = 0; k < 2; k++) {
        gsl_rng *r = NULL;
        model *m = pass_model(&c, B, passes[k], 8, &r);
        assert_int_equal(model_sample(m, r, B, feat, cond, STEPS, k ? x1 : x0), CS_OK);
        gsl_rng_free(r);
        model_free(m);
    }
    assert_memory_equal(x0, x1, sizeof(float) * n);
    free(feat); free(x0); free(x1);
}
static void test_sample_same_bits_for_any_pass_size(void **s) { (void)s; check_sample_passes(0); }
static void test_pair_sample_same_bits_for_any_pass_size(void **s) { (void)s; check_sample_passes(1); }

/* model_sample runs a forward-only pass (nothing a backward reads is kept;
 * the MLP's GELU stores only its output, nn.h). Reference: the sampler as
 * an Euler loop on model_forward, the training forward that keeps every
 * activation, drawing the start noise in the same order. The samples must
 * be bit-identical on every gemm path this CPU has (the layer kernels
 * follow the path), and the paths must agree with each other. Reference
 * shapes, so the register-blocked kernels of the runs are the ones used. */
static void euler_on_model_forward(model *m, gsl_rng *r, int B, const float *feat, const float *cond,
                                   int steps, float *x)
{
    const size_t n = (size_t)B * m->cfg.T * m->cfg.P;
    float *v = malloc(sizeof(float) * n), *t = malloc(sizeof(float) * B);
    for (size_t i = 0; i < n; i++) x[i] = (float)gsl_ran_gaussian_ziggurat(r, 1.0);
    const float dt = 1.f / (float)steps;
    for (int k = 0; k < steps; k++) {
        for (int b = 0; b < B; b++) t[b] = (float)k / (float)steps;
        assert_int_equal(model_forward(m, B, x, feat, cond, t, v), CS_OK);
        for (size_t i = 0; i < n; i++) x[i] += dt * v[i];
    }
    free(v); free(t);
}

static void check_sample_forward_only(int pair, int joint)
{
    enum { B = 6, STEPS = 3 };
    model_cfg c = model_cfg_reference(3);
    c.pair = pair;
    c.joint = joint;
    const size_t n = (size_t)B * c.T * c.P;
    float *feat = malloc(sizeof(float) * B * c.T * c.nfeat), cond[B * 3];
    float *xr = malloc(sizeof(float) * n), *xs = malloc(sizeof(float) * n), *x0 = malloc(sizeof(float) * n);
    unsigned st = 29;
    tu_fill(feat, (size_t)B * c.T * c.nfeat, 1, &st); tu_fill(cond, B * 3, 1, &st);
    const gemm_isa paths[] = {GEMM_AVX512, GEMM_AVX2, GEMM_SCALAR};
    const gemm_isa before = gemm_get_isa();
    int first = 1;
    for (int q = 0; q < 3; q++) {
        if (!gemm_isa_available(paths[q])) continue;
        gemm_set_isa(paths[q]);
        gsl_rng *r = NULL;
        model *m = pass_model(&c, B, 4, 12, &r); /* passes of 4 and 2 patches */
        if (pair) {
            assert_int_equal(model_norm_fit(m, feat, B), CS_OK);
        }
        gsl_rng *rref = gsl_rng_clone(r);
        assert_int_equal(model_sample(m, r, B, feat, cond, STEPS, xs), CS_OK);
        euler_on_model_forward(m, rref, B, feat, cond, STEPS, xr);
        if (memcmp(xs, xr, sizeof(float) * n) != 0) {
            print_error("path %d: the forward-only sampler differs from the Euler loop on model_forward\n",
                        (int)paths[q]);
            fail();
        }
        if (first) memcpy(x0, xs, sizeof(float) * n);
        else assert_memory_equal(xs, x0, sizeof(float) * n);
        first = 0;
        gsl_rng_free(r); gsl_rng_free(rref);
        model_free(m);
    }
    gemm_set_isa(before);
    free(feat); free(xr); free(xs); free(x0);
}
static void test_sample_is_the_euler_loop_on_model_forward(void **s) { (void)s; check_sample_forward_only(0, 1); }
static void test_pair_sample_is_the_euler_loop_on_model_forward(void **s) { (void)s; check_sample_forward_only(1, 1); }
static void test_pair_indep_sample_is_the_euler_loop_on_model_forward(void **s)
{
    (void)s;
    check_sample_forward_only(1, 0);
}

static void test_forward_rejects_oversized_batch(void **s)
{
    (void)s;
    fx f;
    fx_make(&f, 1, 1, 51);
    assert_int_equal(model_forward(f.m, 2, f.xt, f.feat, f.cond, f.t, f.v), CS_EINPUT);
    fx_free(&f);
}

/* ---- readings (model.h): one code path, ingredients switchable ---------------- */

/* Every reading's names round-trip, and the plain and pair readings are the
 * configurations written before the readings existed (stdz AUTO, nuse 0). */
static void test_reading_names_and_legacy_configurations(void **s)
{
    (void)s;
    for (int r = 0; r < MODEL_NREADING; r++) {
        model_reading q;
        assert_int_equal(model_reading_parse(model_reading_name((model_reading)r), &q), CS_OK);
        assert_int_equal(q, r);
        model_cfg c = tiny_reading(1, (model_reading)r);
        assert_int_equal(model_cfg_reading(&c), r);
        assert_int_equal(model_cfg_check(&c), CS_OK);
    }
    model_reading q;
    assert_int_equal(model_reading_parse("pairs", &q), CS_EUSAGE);
    assert_non_null(strstr(cs_errmsg(), "paper-fourier"));
    model_cfg p0 = tiny2(1, 0), p1 = tiny2(1, 1), q0 = p0, q1 = p1;
    model_cfg_set_reading(&q0, MODEL_PLAIN);
    model_cfg_set_reading(&q1, MODEL_PAIR);
    assert_memory_equal(&p0, &q0, sizeof p0);
    assert_memory_equal(&p1, &q1, sizeof p1);
    assert_int_equal(model_cfg_reading(&p0), MODEL_PLAIN);
    assert_int_equal(model_cfg_reading(&p1), MODEL_PAIR);
    model_cfg bad = tiny2(1, 0);
    bad.stdz = 3;
    assert_int_equal(model_cfg_check(&bad), CS_EINPUT);
    bad = tiny2(1, 0);
    bad.nuse = 4;
    assert_int_equal(model_cfg_check(&bad), CS_EINPUT);
}

/* Gradients of every reading and arm against central finite differences of
 * the double reference, and its forward. */
static void check_reading(int joint, model_reading r)
{
    fx f;
    fx_make_cfg(&f, tiny_reading(joint, r), 2, 71 + 2 * r + joint);
    assert_int_equal(model_forward(f.m, f.B, f.xt, f.feat, f.cond, f.t, f.v), CS_OK);
    fx_loss(&f);
    ASSERT_GRAD(f.v, f.v_d, (size_t)f.B * 5 * 6, 2e-5, model_reading_name(r));
    model_backward(f.m, f.dv);
    double *g = malloc(sizeof(double) * f.m->nparams);
    tu_fd_grad(g, f.p, f.m->nparams, fx_loss, &f, 1e-5);
    ASSERT_GRAD(f.m->grads, g, f.m->nparams, 5e-4, model_reading_name(r));
    free(g);
    fx_free(&f);
}
static void test_reading_gradients(void **s)
{
    (void)s;
    for (int r = 0; r < MODEL_NREADING; r++) { check_reading(1, (model_reading)r); check_reading(0, (model_reading)r); }
}

/* Parameter counts: the paper reading's token embedding has nuse = 3 inputs
 * instead of nfeat; the pair terms are the only other difference; both arms
 * of a reading have the same count. z-scores: token ones only when
 * standardised, pair ones only with pair attention. */
static void test_reading_parameter_counts(void **s)
{
    (void)s;
    size_t n[MODEL_NREADING], nn[MODEL_NREADING];
    for (int r = 0; r < MODEL_NREADING; r++) {
        model_cfg c = tiny_reading(1, (model_reading)r), i = tiny_reading(0, (model_reading)r);
        n[r] = model_nparams(&c);
        nn[r] = model_nnorm(&c);
        assert_int_equal(n[r], model_nparams(&i));
    }
    const model_cfg c = tiny2(1, 0);
    assert_int_equal(n[MODEL_PLAIN], n[MODEL_PAPER_FOURIER]);
    assert_int_equal(n[MODEL_PLAIN] - n[MODEL_PAPER], (size_t)c.C * (5 - 3));
    assert_int_equal(n[MODEL_PAIR] - n[MODEL_PAPER_FOURIER], (size_t)c.L * (c.H + c.C) * PAIRATTN_Q);
    assert_int_equal(nn[MODEL_PLAIN], 0);
    assert_int_equal(nn[MODEL_PAPER], 2 * 3);
    assert_int_equal(nn[MODEL_PAPER_FOURIER], 2 * 5);
    assert_int_equal(nn[MODEL_PAIR], 2 * 5 + 2 * PAIRATTN_Q);
}

/* Each ingredient off is really off:
 *  - the paper reading's velocity does not move (bit for bit) when the
 *    features it does not embed (3..nfeat-1) change, while paper-fourier's does;
 *  - standardisation on equals the model without it (same parameters) fed the
 *    standardised features, bit for bit; off, the raw features go in;
 *  - without pair attention the velocity does not depend on the pair z-scores
 *    (there are none: nnorm holds the token ones only). */
static void test_reading_ingredients_off_are_off(void **s)
{
    (void)s;
    enum { B = 2, T = 5, P = 6, NF = 5 };
    float out_a[B * T * P], out_b[B * T * P];
    for (int r = MODEL_PAPER; r <= MODEL_PAPER_FOURIER; r++) {
        fx f;
        fx_make_cfg(&f, tiny_reading(1, (model_reading)r), B, 81);
        assert_int_equal(model_forward(f.m, B, f.xt, f.feat, f.cond, f.t, out_a), CS_OK);
        for (int i = 0; i < B * T; i++) f.feat[i * NF + 3] += 0.9f, f.feat[i * NF + 4] -= 0.6f;
        assert_int_equal(model_forward(f.m, B, f.xt, f.feat, f.cond, f.t, out_b), CS_OK);
        int same = !memcmp(out_a, out_b, sizeof out_a);
        assert_int_equal(same, r == MODEL_PAPER);
        fx_free(&f);
    }
    /* standardisation: paper-fourier vs plain with the same parameters */
    fx f;
    fx_make_cfg(&f, tiny_reading(1, MODEL_PAPER_FOURIER), B, 83);
    assert_true(f.m->norm[0] != 0.f && f.m->norm[NF] != 1.f);
    model_cfg pc = tiny_reading(1, MODEL_PLAIN);
    model *pm;
    assert_int_equal(model_alloc(&pm, &pc, B), CS_OK);
    assert_int_equal(pm->nparams, f.m->nparams);
    memcpy(pm->params, f.m->params, sizeof(float) * pm->nparams);
    float zf[B * T * NF];
    for (int i = 0; i < B * T; i++)
        for (int k = 0; k < NF; k++) zf[i * NF + k] = (f.feat[i * NF + k] - f.m->norm[k]) * f.m->norm[NF + k];
    assert_int_equal(model_forward(f.m, B, f.xt, f.feat, f.cond, f.t, out_a), CS_OK);
    assert_int_equal(model_forward(pm, B, f.xt, zf, f.cond, f.t, out_b), CS_OK);
    assert_memory_equal(out_a, out_b, sizeof out_a);
    /* and the plain model with the raw features differs (it does not standardise) */
    assert_int_equal(model_forward(pm, B, f.xt, f.feat, f.cond, f.t, out_b), CS_OK);
    assert_true(memcmp(out_a, out_b, sizeof out_a) != 0);
    model_free(pm);
    fx_free(&f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_arms_have_identical_parameter_count),
        cmocka_unit_test(test_bad_config_is_rejected),
        cmocka_unit_test(test_forward_matches_reference_joint),
        cmocka_unit_test(test_forward_matches_reference_independent),
        cmocka_unit_test(test_gradients_joint),
        cmocka_unit_test(test_gradients_independent),
        cmocka_unit_test(test_independent_token_ignores_other_tokens),
        cmocka_unit_test(test_joint_token_sees_other_tokens),
        cmocka_unit_test(test_fm_draw_is_linear_path),
        cmocka_unit_test(test_fm_loss_is_mse_with_its_gradient),
        cmocka_unit_test(test_forward_rejects_oversized_batch),
        cmocka_unit_test(test_pair_forward_matches_reference_joint),
        cmocka_unit_test(test_pair_forward_matches_reference_independent),
        cmocka_unit_test(test_pair_gradients_joint),
        cmocka_unit_test(test_pair_gradients_independent),
        cmocka_unit_test(test_pair_independent_token_ignores_other_tokens),
        cmocka_unit_test(test_pair_joint_token_sees_other_tokens),
        cmocka_unit_test(test_pair_layout_extends_the_plain_layout),
        cmocka_unit_test(test_pair_norm_fit_standardises),
        cmocka_unit_test(test_fm_grad_same_bits_for_any_pass_size),
        cmocka_unit_test(test_sample_same_bits_for_any_pass_size),
        cmocka_unit_test(test_pair_fm_grad_same_bits_for_any_pass_size),
        cmocka_unit_test(test_pair_sample_same_bits_for_any_pass_size),
        cmocka_unit_test(test_sample_is_the_euler_loop_on_model_forward),
        cmocka_unit_test(test_pair_sample_is_the_euler_loop_on_model_forward),
        cmocka_unit_test(test_pair_indep_sample_is_the_euler_loop_on_model_forward),
        cmocka_unit_test(test_reading_names_and_legacy_configurations),
        cmocka_unit_test(test_reading_gradients),
        cmocka_unit_test(test_reading_parameter_counts),
        cmocka_unit_test(test_reading_ingredients_off_are_off),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
