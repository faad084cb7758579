/* Tests for src/model/adamw.c and src/model/train.c: the AdamW step, the learning-rate
 * schedule, toy learning (a known profile; a neighbour-dependent target that
 * only the joint arm can learn, paper Eq. 6), bit-identical determinism and
 * kill-and-resume, and rejection of truncated / tampered / foreign checkpoints. */
#include "testutil.h"
#include "train.h"
#include "gemm.h"
#include <gsl/gsl_randist.h>
#include <unistd.h>

static model_cfg small_cfg2(int joint, int pair)
{
    model_cfg c = {.T = PATCH_T, .P = PATCH_P, .nfeat = PATCH_NFEAT, .ncond = PATCH_NCOND,
                   .ntime = 4, .C = 32, .L = 1, .H = 2, .F = 64, .joint = joint, .pair = pair};
    return c;
}
static model_cfg small_cfg(int joint) { return small_cfg2(joint, 0); }

/* A set of n patches with target x1 = S * u (u_s = sqrt(2) cos theta_s, unit RMS).
 * mode 0: S = +1 everywhere (a known profile);
 * mode 1: each token carries a random sign a_i in its third feature and every
 *         token's target uses S = sign(sum of the patch's a_i) (redrawn until
 *         non-zero): a token's profile depends on its neighbours' features, which
 *         only attention across the patch can see. */
static patch_set *toy_set(int n, int mode, unsigned long seed)
{
    patch_set *s;
    assert_int_equal(patch_set_alloc(&s, n), CS_OK);
    gsl_rng *g = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(g, seed);
    s->n = n;
    for (int k = 0; k < n; k++) {
        float a[PATCH_T], sum = 0;
        do {
            sum = 0;
            for (int i = 0; i < PATCH_T; i++) { a[i] = gsl_rng_uniform(g) < 0.5 ? -1.f : 1.f; sum += a[i]; }
        } while (sum == 0);
        float sign = mode ? (sum > 0 ? 1.f : -1.f) : 1.f;
        for (int i = 0; i < PATCH_T; i++) {
            float *f = s->feat + ((size_t)k * PATCH_T + i) * PATCH_NFEAT;
            memset(f, 0, sizeof(float) * PATCH_NFEAT); /* the features not drawn below are 0 */
            f[0] = (float)gsl_ran_gaussian(g, 1.0);
            f[1] = (float)gsl_ran_gaussian(g, 1.0);
            f[2] = mode ? a[i] : 0.5f;
            for (int j = 0; j < PATCH_P; j++)
                s->x1[((size_t)k * PATCH_T + i) * PATCH_P + j] =
                    sign * (float)(sqrt(2.0) * cos(2 * M_PI * j / PATCH_P));
        }
        for (int c = 0; c < PATCH_NCOND; c++) s->cond[k * PATCH_NCOND + c] = 0.2f * c;
    }
    s->scale = 1.0;
    gsl_rng_free(g);
    return s;
}

static train_opts small_opts(long steps)
{
    train_opts o = train_opts_default();
    o.batch = 16;
    o.steps = steps;
    o.lr = 5e-3;
    return o;
}

/* ---- AdamW ------------------------------------------------------------------ */
static void test_adamw_first_step_by_hand(void **s)
{
    (void)s;
    float p[2] = {1.0f, 1.0f}, g[2] = {0.5f, 0.5f}, m[2] = {0}, v[2] = {0};
    adamw_hp hp = adamw_defaults();
    adamw_update(p, g, m, v, 2, 1, 1, 0.1, &hp);
    /* step 1: mhat = g, vhat = g^2 -> update = g/(|g| + eps) ~ 1 */
    ASSERT_NEAR(p[0], 1.0 * (1 - 0.1 * 0.01) - 0.1 * 0.5 / (0.5 + 1e-8), 1e-6); /* decayed */
    ASSERT_NEAR(p[1], 1.0 - 0.1 * 0.5 / (0.5 + 1e-8), 1e-6);                    /* not decayed */
    ASSERT_NEAR(m[0], 0.05, 1e-7);
    ASSERT_NEAR(v[0], 0.00025, 1e-8);
}

/* The vectorised update equals the scalar expression of adamw.h bit for bit
 * (n = 1003: full vectors, a decay boundary inside a vector, and a tail), on
 * every gemm path (the update takes the path's vector width). */
static void adamw_check(void)
{
    enum { n = 1003, nd = 517 };
    static float p[n], g[n], m[n], v[n], pc[n], mc[n], vc[n];
    unsigned st = 71;
    /* LCG values in (-1, 1); parameters small next to the step (about 5e-3), so
     * that a rounding difference in the step is not absorbed by p */
    for (int i = 0; i < n; i++) {
        float u[4];
        for (int k = 0; k < 4; k++) { st = st * 1664525u + 1013904223u; u[k] = (float)(st >> 8) / 8388608.f - 1.f; }
        p[i] = 1e-4f * u[0]; g[i] = 0.1f * u[1]; m[i] = 0.05f * u[2]; v[i] = 0.01f * fabsf(u[3]);
    }
    memcpy(pc, p, sizeof p); memcpy(mc, m, sizeof m); memcpy(vc, v, sizeof v);
    adamw_hp hp = adamw_defaults();
    const long t = 7;
    const double lr = 3e-3;
    adamw_update(p, g, m, v, n, nd, t, lr, &hp);
    const float b1 = (float)hp.beta1, b2 = (float)hp.beta2, c1 = 1.f - b1, c2 = 1.f - b2;
    const float a = (float)(lr / (1.0 - pow(hp.beta1, (double)t))),
                cv = (float)(1.0 / (1.0 - pow(hp.beta2, (double)t)));
    const float eps = (float)hp.eps;
    for (int i = 0; i < n; i++) {
        float keep = i < nd ? (float)(1.0 - lr * hp.wd) : 1.f;
        float mi = b1 * mc[i] + c1 * g[i];
        float vi = b2 * vc[i] + c2 * (g[i] * g[i]);
        float pi = pc[i] * keep - a * mi / (sqrtf(vi * cv) + eps);
        ASSERT_EXACT(m[i], mi);
        ASSERT_EXACT(v[i], vi);
        ASSERT_EXACT(p[i], pi);
    }
}

static void test_adamw_matches_scalar_expression(void **s)
{
    (void)s;
    for (int isa = GEMM_SCALAR; isa <= GEMM_AVX512; isa++) {
        if (!gemm_isa_available((gemm_isa)isa)) continue;
        gemm_isa before = gemm_set_isa((gemm_isa)isa);
        adamw_check();
        gemm_set_isa(before);
    }
}

static void test_lr_schedule_warms_up_and_decays(void **s)
{
    (void)s;
    train_opts o = small_opts(1000);
    ASSERT_NEAR(train_lr(&o, 25), o.lr * 0.5, 1e-12);
    ASSERT_NEAR(train_lr(&o, 50), o.lr, 1e-12);
    ASSERT_NEAR(train_lr(&o, 1000), o.lr * o.lr_final, 1e-12);
    assert_true(train_lr(&o, 500) < o.lr && train_lr(&o, 500) > o.lr * o.lr_final);
}

/* ---- toy learning -------------------------------------------------------------- */
static void test_known_profile_is_learned_and_sampled(void **s)
{
    (void)s;
    patch_set *d = toy_set(32, 0, 1);
    model_cfg c = small_cfg(1);
    train_opts o = small_opts(600);
    train *t;
    assert_int_equal(train_alloc(&t, &c, d, &o), CS_OK);
    double l0, l1;
    assert_int_equal(train_eval_loss(t, d, 2, 99, &l0), CS_OK);
    assert_int_equal(train_run(t, o.steps, NULL, 0, NULL), CS_OK);
    assert_int_equal(train_eval_loss(t, d, 2, 99, &l1), CS_OK);
    print_message("known profile: eval loss %.4f -> %.4f\n", l0, l1);
    assert_true(l1 < 0.1 * l0);
    /* 100 Euler steps from noise land on u */
    const int B = 4;
    float *x = malloc(sizeof(float) * B * PATCH_T * PATCH_P);
    gsl_rng *g = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(g, 5);
    assert_int_equal(model_sample(t->m, g, B, d->feat, d->cond, 100, x), CS_OK);
    double se = 0;
    for (int i = 0; i < B * PATCH_T * PATCH_P; i++) {
        double e = x[i] - d->x1[i];
        se += e * e;
    }
    double rms = sqrt(se / (B * PATCH_T * PATCH_P));
    print_message("known profile: sample RMS error %.4f (target RMS 1)\n", rms);
    assert_true(rms < 0.15);
    free(x);
    gsl_rng_free(g);
    train_free(t);
    patch_set_free(d);
}

/* Held-out eval loss and the fraction of sampled tokens whose profile has the
 * sign of its target (projection on u). */
static void toy_pair(int joint, double *loss, double *signacc)
{
    patch_set *d = toy_set(256, 1, 2), *e = toy_set(32, 1, 3);
    model_cfg c = small_cfg(joint);
    train_opts o = small_opts(400);
    train *t;
    assert_int_equal(train_alloc(&t, &c, d, &o), CS_OK);
    assert_int_equal(train_run(t, o.steps, NULL, 0, NULL), CS_OK);
    assert_int_equal(train_eval_loss(t, e, 2, 77, loss), CS_OK);
    const int B = 8;
    float *x = malloc(sizeof(float) * B * PATCH_T * PATCH_P);
    gsl_rng *g = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(g, 5);
    assert_int_equal(model_sample(t->m, g, B, e->feat, e->cond, 100, x), CS_OK);
    int ok = 0;
    for (int k = 0; k < B * PATCH_T; k++) {
        double ps = 0, ts = 0;
        for (int j = 0; j < PATCH_P; j++) {
            ps += x[k * PATCH_P + j] * cos(2 * M_PI * j / PATCH_P);
            ts += e->x1[k * PATCH_P + j] * cos(2 * M_PI * j / PATCH_P);
        }
        ok += (ps > 0) == (ts > 0);
    }
    *signacc = (double)ok / (B * PATCH_T);
    free(x);
    gsl_rng_free(g);
    train_free(t);
    patch_set_free(d);
    patch_set_free(e);
}

static void test_joint_arm_learns_neighbour_dependence_independent_cannot(void **s)
{
    (void)s;
    double lj, li, aj, ai;
    toy_pair(1, &lj, &aj);
    toy_pair(0, &li, &ai);
    print_message("neighbour toy (held-out): eval loss joint %.4f, independent %.4f; "
                  "sample sign accuracy joint %.3f, independent %.3f\n", lj, li, aj, ai);
    assert_true(lj < 0.6 * li);
    assert_true(aj > 0.75);
    assert_true(ai < 0.62);
}

/* ---- determinism, checkpoints ------------------------------------------------------ */
static void test_training_is_bit_identical_across_runs(void **s)
{
    (void)s;
    patch_set *d = toy_set(40, 1, 4);
    model_cfg c = small_cfg(1);
    train_opts o = small_opts(12);
    train *a, *b;
    assert_int_equal(train_alloc(&a, &c, d, &o), CS_OK);
    assert_int_equal(train_alloc(&b, &c, d, &o), CS_OK);
    assert_int_equal(train_run(a, 12, NULL, 0, NULL), CS_OK);
    assert_int_equal(train_run(b, 12, NULL, 0, NULL), CS_OK);
    assert_memory_equal(a->m->params, b->m->params, sizeof(float) * a->m->nparams);
    train_free(a); train_free(b);
    patch_set_free(d);
}

/* The same training on every gemm path this CPU has gives the same bits, so a
 * run reproduces exactly on a machine without AVX-512 (or without AVX2). */
static void check_gemm_paths(int pair)
{
    patch_set *d = toy_set(40, 1, 4);
    model_cfg c = small_cfg2(1, pair);
    train_opts o = small_opts(6);
    train *ref;
    gemm_isa before = gemm_set_isa(GEMM_SCALAR);
    assert_int_equal(train_alloc(&ref, &c, d, &o), CS_OK);
    assert_int_equal(train_run(ref, 6, NULL, 0, NULL), CS_OK);
    for (int isa = GEMM_AVX2; isa <= GEMM_AVX512; isa++) {
        if (!gemm_isa_available((gemm_isa)isa)) {
            print_message("gemm path %d not on this CPU: skipped\n", isa);
            continue;
        }
        gemm_set_isa((gemm_isa)isa);
        train *t;
        assert_int_equal(train_alloc(&t, &c, d, &o), CS_OK);
        assert_int_equal(train_run(t, 6, NULL, 0, NULL), CS_OK);
        assert_memory_equal(t->m->params, ref->m->params, sizeof(float) * ref->m->nparams);
        assert_memory_equal(t->av, ref->av, sizeof(float) * ref->m->nparams);
        train_free(t);
    }
    gemm_set_isa(before);
    train_free(ref);
    patch_set_free(d);
}

static void test_training_is_bit_identical_on_every_gemm_path(void **s) { (void)s; check_gemm_paths(0); }
static void test_pair_training_is_bit_identical_on_every_gemm_path(void **s) { (void)s; check_gemm_paths(1); }

static void check_resume2(int joint, int pair)
{
    patch_set *d = toy_set(40, 1, 5); /* 40 patches, batch 16: epochs of 2 steps, cursor mid-epoch */
    model_cfg c = small_cfg2(joint, pair);
    train_opts o = small_opts(20);
    const char *dir = tu_tmpdir(pair    ? (joint ? "resume_pair_joint" : "resume_pair_indep")
                                : joint ? "resume_joint"
                                        : "resume_indep");
    char path[600];
    snprintf(path, sizeof path, "%s/run.ckpt", dir);
    train *straight, *first, *second;
    assert_int_equal(train_alloc(&straight, &c, d, &o), CS_OK);
    assert_int_equal(train_run(straight, 20, NULL, 0, NULL), CS_OK);
    /* killed run: checkpoints every 3 steps; only the checkpoint of step 9 survives */
    assert_int_equal(train_alloc(&first, &c, d, &o), CS_OK);
    assert_int_equal(train_run(first, 11, path, 3, NULL), CS_OK);
    train_free(first);
    assert_int_equal(train_alloc(&first, &c, d, &o), CS_OK);
    assert_int_equal(train_run(first, 9, path, 3, NULL), CS_OK);
    for (int k = 0; k < 2; k++) assert_int_equal(train_step(first, NULL), CS_OK); /* lost work */
    train_free(first);
    assert_int_equal(train_alloc(&second, &c, d, &o), CS_OK);
    assert_int_equal(train_load(second, path), CS_OK);
    assert_int_equal(second->step, 9);
    assert_int_equal(train_run(second, 20, path, 3, NULL), CS_OK);
    assert_int_equal(second->step, 20);
    size_t nb = sizeof(float) * straight->m->nparams;
    assert_memory_equal(second->m->params, straight->m->params, nb);
    assert_memory_equal(second->am, straight->am, nb);
    assert_memory_equal(second->av, straight->av, nb);
    assert_int_equal(second->m->nnorm, straight->m->nnorm);
    assert_memory_equal(second->m->norm, straight->m->norm, sizeof(float) * straight->m->nnorm);
    train_free(straight); train_free(second);
    patch_set_free(d);
}
static void check_resume(int joint) { check_resume2(joint, 0); }
static void test_kill_and_resume_is_bit_identical_joint(void **s) { (void)s; check_resume(1); }
static void test_pair_kill_and_resume_is_bit_identical_joint(void **s) { (void)s; check_resume2(1, 1); }
static void test_pair_kill_and_resume_is_bit_identical_independent(void **s) { (void)s; check_resume2(0, 1); }
static void test_kill_and_resume_is_bit_identical_independent(void **s) { (void)s; check_resume(0); }

/* The joint model, plain or pair, two steps into a toy set of 20 patches
 * (mode 1, the neighbour-dependent one, for the pair model) that *d gets;
 * ckpt and ckpt_every as train_run takes them. */
static train *toy_trained(int pair, const char *ckpt, long ckpt_every, patch_set **d)
{
    *d = toy_set(20, pair, 6);
    model_cfg c = small_cfg2(1, pair);
    train_opts o = small_opts(4);
    train *t;
    assert_int_equal(train_alloc(&t, &c, *d, &o), CS_OK);
    assert_int_equal(train_run(t, 2, ckpt, ckpt_every, NULL), CS_OK);
    return t;
}

static void write_ckpt(const char *name, char *path, size_t n, train **t, patch_set **d)
{
    snprintf(path, n, "%s/c.ckpt", tu_tmpdir(name));
    *t = toy_trained(0, path, 0, d);
}

/* A unit killed between its last checkpoint and its table resumes
 * at the last step and takes none; it must not report a final loss of 0. */
static void test_resumed_at_last_step_reports_no_loss(void **s)
{
    (void)s;
    char path[600];
    train *t, *r;
    patch_set *d;
    write_ckpt("resume_end", path, sizeof path, &t, &d); /* 2 steps, checkpoint at step 2 */
    assert_false(isnan(t->loss));
    model_cfg c = small_cfg(1);
    train_opts o = small_opts(4);
    assert_int_equal(train_alloc(&r, &c, d, &o), CS_OK);
    assert_true(isnan(r->loss));
    assert_int_equal(train_load(r, path), CS_OK);
    assert_int_equal(r->step, 2);
    assert_int_equal(train_run(r, 2, path, 1, NULL), CS_OK); /* nothing left to do */
    if (!isnan(r->loss)) fail_msg("a run resumed at its last step reports loss %.17g, not 'none' (NaN)", r->loss);
    train_free(r);
    train_free(t);
    patch_set_free(d);
}

static long file_size(const char *p) { struct stat st; return stat(p, &st) == 0 ? (long)st.st_size : -1; }

static void test_truncated_checkpoint_is_rejected(void **s)
{
    (void)s;
    char path[600];
    train *t; patch_set *d;
    write_ckpt("ckpt_trunc", path, sizeof path, &t, &d);
    assert_int_equal(truncate(path, file_size(path) - 100), 0);
    assert_int_equal(train_load(t, path), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "truncated"));
    assert_int_equal(truncate(path, 5), 0);
    assert_int_equal(train_load(t, path), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "truncated"));
    train_free(t); patch_set_free(d);
}

static void test_tampered_checkpoint_is_rejected(void **s)
{
    (void)s;
    char path[600];
    train *t; patch_set *d;
    write_ckpt("ckpt_tamper", path, sizeof path, &t, &d);
    FILE *f = fopen(path, "r+b");
    assert_non_null(f);
    fseek(f, file_size(path) / 2, SEEK_SET);
    int ch = fgetc(f);
    fseek(f, file_size(path) / 2, SEEK_SET);
    fputc(ch ^ 0x10, f);
    fclose(f);
    float before = t->m->params[0];
    assert_int_equal(train_load(t, path), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "checksum"));
    ASSERT_EXACT(t->m->params[0], before); /* state untouched */
    train_free(t); patch_set_free(d);
}

static void test_foreign_missing_and_mismatched_checkpoints_are_rejected(void **s)
{
    (void)s;
    char path[600], other[700];
    train *t, *u; patch_set *d;
    write_ckpt("ckpt_foreign", path, sizeof path, &t, &d);
    snprintf(other, sizeof other, "%s.txt", path);
    tu_write(other, "this is not a checkpoint at all, just some text that is long enough to have a "
                    "header............................................................................................"
                    "..............................................\n");
    assert_int_equal(train_load(t, other), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "magic"));
    snprintf(other, sizeof other, "%s.missing", path);
    assert_int_equal(train_load(t, other), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "cannot open"));
    model_cfg c = small_cfg(0); /* independent arm: same size, different model */
    train_opts o = small_opts(4);
    assert_int_equal(train_alloc(&u, &c, d, &o), CS_OK);
    assert_int_equal(train_load(u, path), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "model configuration"));
    train_free(u);
    train_free(t); patch_set_free(d);
}

/* A checkpoint of format version 1 (before the pair model) is refused with a
 * message naming its version and what to do. */
static void test_version_1_checkpoint_is_refused_clearly(void **s)
{
    (void)s;
    char path[600];
    train *t; patch_set *d;
    write_ckpt("ckpt_v1", path, sizeof path, &t, &d);
    FILE *f = fopen(path, "r+b");
    assert_non_null(f);
    const uint32_t format1 = 1;
    assert_int_equal(fseek(f, 8, SEEK_SET), 0);
    assert_int_equal(fwrite(&format1, 4, 1, f), 1);
    fclose(f);
    assert_int_equal(train_load(t, path), CS_EINPUT);
    print_message("%s\n", cs_errmsg());
    assert_non_null(strstr(cs_errmsg(), "version 1 is no longer read"));
    assert_non_null(strstr(cs_errmsg(), "delete it"));
    model *m = NULL;
    assert_int_equal(train_load_model(path, &m, 2, NULL), CS_EINPUT);
    assert_null(m);
    train_free(t); patch_set_free(d);
}

/* The pair model's z-scores travel with its parameters. */
static void test_pair_model_loads_with_its_z_scores(void **s)
{
    (void)s;
    char path[600];
    snprintf(path, sizeof path, "%s/p.ckpt", tu_tmpdir("ckpt_pair_model"));
    patch_set *d;
    train *t = toy_trained(1, path, 0, &d);
    assert_true(t->m->norm[0] != 0.f && t->m->norm[PATCH_NFEAT] != 1.f); /* fitted, not the identity */
    model *m;
    assert_int_equal(train_load_model(path, &m, 3, NULL), CS_OK);
    assert_int_equal(m->cfg.pair, 1);
    assert_memory_equal(m->norm, t->m->norm, sizeof(float) * t->m->nnorm);
    assert_memory_equal(m->params, t->m->params, sizeof(float) * m->nparams);
    /* and samples as the trained model does */
    float x1[2 * PATCH_T * PATCH_P], x2[2 * PATCH_T * PATCH_P];
    gsl_rng *g = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(g, 9);
    assert_int_equal(model_sample(m, g, 2, d->feat, d->cond, 3, x1), CS_OK);
    gsl_rng_set(g, 9);
    assert_int_equal(model_sample(t->m, g, 2, d->feat, d->cond, 3, x2), CS_OK);
    assert_memory_equal(x1, x2, sizeof x1);
    gsl_rng_free(g);
    model_free(m);
    train_free(t); patch_set_free(d);
}

/* Readings (model.h) travel in the headers' former pad: zero for plain and
 * pair (their files are those written before the readings), the stdz and
 * nuse of paper and paper-fourier otherwise; every reading round-trips through
 * a weights file and a checkpoint, and samples as the trained model does. */
static void test_readings_round_trip_in_weights_and_checkpoints(void **s)
{
    (void)s;
    patch_set *d = toy_set(20, 1, 6);
    const char *dir = tu_tmpdir("readings_files");
    for (int r = 0; r < MODEL_NREADING; r++) {
        model_cfg c = small_cfg(1);
        model_cfg_set_reading(&c, (model_reading)r);
        train_opts o = small_opts(4);
        char wp[600], cp[600];
        snprintf(wp, sizeof wp, "%s/w%d.ckpt", dir, r);
        snprintf(cp, sizeof cp, "%s/c%d.ckpt", dir, r);
        train *t;
        assert_int_equal(train_alloc(&t, &c, d, &o), CS_OK);
        assert_int_equal(train_run(t, 2, cp, 0, NULL), CS_OK);
        assert_int_equal(train_save_weights(t, wp), CS_OK);
        FILE *f = fopen(wp, "rb");
        int32_t ingr = -1;
        assert_int_equal(fseek(f, 12 + 11 * 4, SEEK_SET), 0);
        assert_int_equal(fread(&ingr, 4, 1, f), 1);
        fclose(f);
        if (r == MODEL_PLAIN || r == MODEL_PAIR) assert_int_equal(ingr, 0);
        else assert_true(ingr != 0);
        for (int k = 0; k < 2; k++) {
            model *m;
            assert_int_equal(train_load_model(k ? cp : wp, &m, 3, NULL), CS_OK);
            assert_int_equal(model_cfg_reading(&m->cfg), r);
            assert_int_equal(m->nparams, t->m->nparams);
            assert_memory_equal(m->norm, t->m->norm, sizeof(float) * t->m->nnorm);
            assert_memory_equal(m->params, t->m->params, sizeof(float) * m->nparams);
            float x1[2 * PATCH_T * PATCH_P], x2[2 * PATCH_T * PATCH_P];
            gsl_rng *g = gsl_rng_alloc(gsl_rng_mt19937);
            gsl_rng_set(g, 9);
            assert_int_equal(model_sample(m, g, 2, d->feat, d->cond, 3, x1), CS_OK);
            gsl_rng_set(g, 9);
            assert_int_equal(model_sample(t->m, g, 2, d->feat, d->cond, 3, x2), CS_OK);
            assert_memory_equal(x1, x2, sizeof x1);
            gsl_rng_free(g);
            model_free(m);
        }
        /* a checkpoint of another reading belongs to another run */
        model_cfg c2 = small_cfg(1);
        model_cfg_set_reading(&c2, (model_reading)((r + 1) % MODEL_NREADING));
        train *u;
        assert_int_equal(train_alloc(&u, &c2, d, &o), CS_OK);
        assert_int_equal(train_load(u, cp), CS_EINPUT);
        train_free(u);
        train_free(t);
    }
    patch_set_free(d);
}

/* The frozen weights of the pair-aware runs (written before the readings)
 * load as the pair reading with the reference shape. */
static void test_frozen_weights_load_as_the_pair_reading(void **s)
{
    (void)s;
    static const char *arms[2] = {"joint", "indep"};
    for (int a = 0; a < 2; a++) {
        char p[256];
        snprintf(p, sizeof p, "frozen/extension-pair-16-stands/main/weights_s01_%s.ckpt", arms[a]);
        model *m;
        double scale = 0;
        assert_int_equal(train_load_model(p, &m, 2, &scale), CS_OK);
        assert_int_equal(model_cfg_reading(&m->cfg), MODEL_PAIR);
        assert_int_equal(m->cfg.joint, !a);
        assert_int_equal(m->nparams, 161208);
        assert_true(scale > 0);
        model_free(m);
    }
}

/* A checkpoint or weights file is written under a temporary name of its own:
 * another writer's temporary file at "<path>.tmp" (here a folder in its way)
 * neither blocks the write nor is touched, and nothing is left behind. */
static void test_sealed_writes_take_a_temporary_name_of_their_own(void **s)
{
    (void)s;
    const char *dir = tu_tmpdir("sealed_tmp");
    char path[600], other[640], cmd[1400];
    snprintf(path, sizeof path, "%s/w.ckpt", dir);
    snprintf(other, sizeof other, "%s.tmp", path);
    assert_int_equal(mkdir(other, 0777), 0);
    patch_set *d;
    train *t = toy_trained(1, path, 1, &d);
    assert_int_equal(train_save_weights(t, path), CS_OK);
    struct stat sb;
    assert_int_equal(stat(other, &sb), 0);
    assert_true(S_ISDIR(sb.st_mode));
    snprintf(cmd, sizeof cmd, "test $(ls '%s' | wc -l) -eq 2", dir); /* w.ckpt and the other writer's folder */
    assert_int_equal(system(cmd), 0);
    train_free(t);
    patch_set_free(d);
}

/* Weights files: the model, its z-scores and scale only, sealed; a tampered
 * or truncated file is refused. */
static void test_weights_file_round_trips_and_is_sealed(void **s)
{
    (void)s;
    const char *dir = tu_tmpdir("weights_file");
    char path[600], bad[640];
    snprintf(path, sizeof path, "%s/w.ckpt", dir);
    patch_set *d;
    train *t = toy_trained(1, NULL, 0, &d);
    assert_int_equal(train_save_weights(t, path), CS_OK);
    model *m;
    double scale = 0;
    assert_int_equal(train_load_model(path, &m, 3, &scale), CS_OK);
    ASSERT_EXACT(scale, d->scale);
    assert_int_equal(m->cfg.pair, 1);
    assert_int_equal(m->cfg.joint, 1);
    assert_memory_equal(m->norm, t->m->norm, sizeof(float) * t->m->nnorm);
    assert_memory_equal(m->params, t->m->params, sizeof(float) * m->nparams);
    model_free(m);
    /* one flipped byte in the parameters, then a truncated copy */
    FILE *f = fopen(path, "rb");
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    rewind(f);
    unsigned char *b = malloc((size_t)n);
    assert_int_equal(fread(b, 1, (size_t)n, f), (size_t)n);
    fclose(f);
    snprintf(bad, sizeof bad, "%s/bad.ckpt", dir);
    b[n / 2] ^= 1;
    f = fopen(bad, "wb"); fwrite(b, 1, (size_t)n, f); fclose(f);
    assert_int_equal(train_load_model(bad, &m, 3, NULL), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "checksum"));
    b[n / 2] ^= 1;
    f = fopen(bad, "wb"); fwrite(b, 1, (size_t)n - 9, f); fclose(f);
    assert_int_equal(train_load_model(bad, &m, 3, NULL), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "truncated"));
    free(b);
    train_free(t); patch_set_free(d);
}

static void test_model_loads_from_checkpoint(void **s)
{
    (void)s;
    char path[600];
    train *t; patch_set *d;
    write_ckpt("ckpt_model", path, sizeof path, &t, &d);
    model *m;
    double scale = 0;
    assert_int_equal(train_load_model(path, &m, 3, &scale), CS_OK);
    ASSERT_EXACT(scale, 1.0);
    assert_int_equal(m->nparams, t->m->nparams);
    assert_memory_equal(m->params, t->m->params, sizeof(float) * m->nparams);
    model_free(m);
    train_free(t); patch_set_free(d);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_adamw_first_step_by_hand),
        cmocka_unit_test(test_adamw_matches_scalar_expression),
        cmocka_unit_test(test_lr_schedule_warms_up_and_decays),
        cmocka_unit_test(test_known_profile_is_learned_and_sampled),
        cmocka_unit_test(test_joint_arm_learns_neighbour_dependence_independent_cannot),
        cmocka_unit_test(test_training_is_bit_identical_across_runs),
        cmocka_unit_test(test_training_is_bit_identical_on_every_gemm_path),
        cmocka_unit_test(test_kill_and_resume_is_bit_identical_joint),
        cmocka_unit_test(test_kill_and_resume_is_bit_identical_independent),
        cmocka_unit_test(test_truncated_checkpoint_is_rejected),
        cmocka_unit_test(test_resumed_at_last_step_reports_no_loss),
        cmocka_unit_test(test_tampered_checkpoint_is_rejected),
        cmocka_unit_test(test_foreign_missing_and_mismatched_checkpoints_are_rejected),
        cmocka_unit_test(test_model_loads_from_checkpoint),
        cmocka_unit_test(test_pair_training_is_bit_identical_on_every_gemm_path),
        cmocka_unit_test(test_pair_kill_and_resume_is_bit_identical_joint),
        cmocka_unit_test(test_pair_kill_and_resume_is_bit_identical_independent),
        cmocka_unit_test(test_version_1_checkpoint_is_refused_clearly),
        cmocka_unit_test(test_pair_model_loads_with_its_z_scores),
        cmocka_unit_test(test_readings_round_trip_in_weights_and_checkpoints),
        cmocka_unit_test(test_frozen_weights_load_as_the_pair_reading),
        cmocka_unit_test(test_weights_file_round_trips_and_is_sealed),
        cmocka_unit_test(test_sealed_writes_take_a_temporary_name_of_their_own),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
