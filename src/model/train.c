/* train: trainer and checkpoints (see train.h; paper §4.2, Eq. 2;
 * design.md §8, §10, §11). */
#include "train.h"
#include "afile.h"
#include "paths.h"
#include <errno.h>
#include <stddef.h>
#include <gsl/gsl_randist.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#define CKPT_MAGIC "CSHYCKPT"
/* Version 2: the configuration gains `pair`, the header nnorm,
 * and the model's z-scores (nnorm floats) follow the permutation. Version 1
 * files are refused with a message saying so. */
#define CKPT_VERSION 2u

train_opts train_opts_default(void)
{
    train_opts o = {.batch = 64, .steps = 1000, .lr = 2e-3, .warmup = 0.05, .lr_final = 0.1,
                    .hp = adamw_defaults(), .seed_init = 1, .seed_batch = 2, .seed_noise = 3};
    return o;
}

static uint64_t fnv1a(uint64_t h, const void *p, size_t n)
{
    const unsigned char *c = p;
    for (size_t i = 0; i < n; i++) { h ^= c[i]; h *= 1099511628211ull; }
    return h;
}
#define FNV0 14695981039346656037ull

static uint64_t data_fingerprint(const patch_set *d)
{
    uint64_t h = FNV0;
    h = fnv1a(h, &d->n, sizeof d->n);
    h = fnv1a(h, &d->scale, sizeof d->scale);
    h = fnv1a(h, d->x1, sizeof(float) * (size_t)d->n * PATCH_T * PATCH_P);
    h = fnv1a(h, d->feat, sizeof(float) * (size_t)d->n * PATCH_T * PATCH_NFEAT);
    h = fnv1a(h, d->cond, sizeof(float) * (size_t)d->n * PATCH_NCOND);
    return h;
}

void train_free(train *t)
{
    if (!t) return;
    model_free(t->m);
    free(t->am); free(t->av); free(t->perm); free(t->bx1); free(t->bfeat); free(t->bcond);
    if (t->rng_init) gsl_rng_free(t->rng_init);
    if (t->rng_batch) gsl_rng_free(t->rng_batch);
    if (t->rng_noise) gsl_rng_free(t->rng_noise);
    free(t);
}

cs_status train_alloc(train **out, const model_cfg *cfg, const patch_set *data, const train_opts *o)
{
    *out = NULL;
    if (!data || data->n < 1) return cs_err(CS_EINPUT, "train: no training patches");
    if (!(data->scale > 0)) return cs_err(CS_EINPUT, "train: training patches are not standardised");
    if (cfg->T != PATCH_T || cfg->P != PATCH_P || cfg->nfeat != PATCH_NFEAT || cfg->ncond != PATCH_NCOND)
        return cs_err(CS_EINPUT,
                      "train: model config (T %d, P %d, nfeat %d, ncond %d) does not match patches (%d, %d, %d, %d)",
                      cfg->T, cfg->P, cfg->nfeat, cfg->ncond, PATCH_T, PATCH_P, PATCH_NFEAT, PATCH_NCOND);
    if (o->batch < 1 || o->steps < 1 || !(o->lr > 0))
        return cs_err(CS_EINPUT, "train: batch %d, steps %ld, lr %g must be positive", o->batch, o->steps, o->lr);
    if (!(o->warmup >= 0 && o->warmup < 1) || !(o->lr_final >= 0 && o->lr_final <= 1))
        return cs_err(CS_EINPUT, "train: warm-up fraction %g must be in [0,1) and final lr fraction %g in [0,1]",
                      o->warmup, o->lr_final);
    train *t = calloc(1, sizeof *t);
    if (!t) return cs_err(CS_ENOMEM, "train: out of memory");
    t->loss = NAN; /* no step taken yet (a run resumed at its last step): never a loss of 0 */
    t->o = *o;
    t->data = data;
    t->data_hash = data_fingerprint(data);
    t->B = o->batch < data->n ? o->batch : data->n;
    cs_status st = model_alloc(&t->m, cfg, t->B);
    if (st) { train_free(t); return st; }
    size_t np = t->m->nparams;
    t->am = calloc(np, sizeof(float));
    t->av = calloc(np, sizeof(float));
    t->perm = malloc(sizeof(int) * data->n);
    t->bx1 = malloc(sizeof(float) * t->B * PATCH_T * PATCH_P);
    t->bfeat = malloc(sizeof(float) * t->B * PATCH_T * PATCH_NFEAT);
    t->bcond = malloc(sizeof(float) * t->B * PATCH_NCOND);
    t->rng_init = gsl_rng_alloc(gsl_rng_mt19937);
    t->rng_batch = gsl_rng_alloc(gsl_rng_mt19937);
    t->rng_noise = gsl_rng_alloc(gsl_rng_mt19937);
    if (!t->am || !t->av || !t->perm || !t->bx1 || !t->bfeat || !t->bcond ||
        !t->rng_init || !t->rng_batch || !t->rng_noise) {
        train_free(t);
        return cs_err(CS_ENOMEM, "train: out of memory");
    }
    gsl_rng_set(t->rng_init, o->seed_init);
    gsl_rng_set(t->rng_batch, o->seed_batch);
    gsl_rng_set(t->rng_noise, o->seed_noise);
    model_init(t->m, t->rng_init);
    st = model_norm_fit(t->m, data->feat, data->n);
    if (st) { train_free(t); return st; }
    for (int i = 0; i < data->n; i++) t->perm[i] = i;
    t->pos = data->n; /* forces a shuffle (epoch 1) at the first step */
    *out = t;
    return CS_OK;
}

double train_lr(const train_opts *o, long s)
{
    double w = o->warmup * (double)o->steps;
    if (s <= w && w >= 1) return o->lr * (double)s / w;
    double f = (double)(s - w) / ((double)o->steps - w > 0 ? (double)o->steps - w : 1.0);
    if (f > 1) f = 1;
    return o->lr * (o->lr_final + (1 - o->lr_final) * 0.5 * (1 + cos(M_PI * f)));
}

cs_status train_step(train *t, double *loss)
{
    const patch_set *d = t->data;
    if (t->pos + t->B > d->n) {
        gsl_ran_shuffle(t->rng_batch, t->perm, d->n, sizeof(int));
        t->pos = 0;
        t->epoch++;
    }
    const size_t TP = PATCH_T * PATCH_P, TF = PATCH_T * PATCH_NFEAT;
    for (int b = 0; b < t->B; b++) {
        size_t k = t->perm[t->pos + b];
        memcpy(t->bx1 + b * TP, d->x1 + k * TP, sizeof(float) * TP);
        memcpy(t->bfeat + b * TF, d->feat + k * TF, sizeof(float) * TF);
        memcpy(t->bcond + b * PATCH_NCOND, d->cond + k * PATCH_NCOND, sizeof(float) * PATCH_NCOND);
    }
    t->pos += t->B;
    double l;
    cs_status st = model_fm_grad(t->m, t->rng_noise, t->B, t->bx1, t->bfeat, t->bcond, &l);
    if (st) return st;
    t->step++;
    adamw_update(t->m->params, t->m->grads, t->am, t->av, t->m->nparams, t->m->ndecay,
                 t->step, train_lr(&t->o, t->step), &t->o.hp);
    t->loss = l;
    if (loss) *loss = l;
    return CS_OK;
}

cs_status train_eval_loss(train *t, const patch_set *d, int nbatch, unsigned long seed, double *loss)
{
    gsl_rng *g = gsl_rng_alloc(gsl_rng_mt19937);
    if (!g) return cs_err(CS_ENOMEM, "train: out of memory");
    gsl_rng_set(g, seed);
    model *m = t->m;
    const size_t TP = PATCH_T * PATCH_P;
    double sum = 0;
    int nb = 0;
    cs_status st = CS_OK;
    for (int k = 0; k < nbatch && !st; k++) {
        int b0 = k * t->B;
        if (b0 >= d->n) break;
        int B = d->n - b0 < t->B ? d->n - b0 : t->B;
        model_fm_draw(g, B, (int)TP, d->x1 + (size_t)b0 * TP, m->fm_xt, m->fm_u, m->fm_t);
        st = model_forward(m, B, m->fm_xt, d->feat + (size_t)b0 * PATCH_T * PATCH_NFEAT,
                           d->cond + (size_t)b0 * PATCH_NCOND, m->fm_t, m->fm_v);
        if (!st) { sum += model_fm_loss(m->fm_v, m->fm_u, (size_t)B * TP, NULL); nb++; }
    }
    gsl_rng_free(g);
    if (st) return st;
    *loss = nb ? sum / nb : NAN;
    return CS_OK;
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

cs_status train_run(train *t, long until, const char *ckpt, long ckpt_every, FILE *progress)
{
    if (until > t->o.steps) until = t->o.steps;
    const long start = t->step, every = (t->o.steps / 50) > 0 ? t->o.steps / 50 : 1;
    const long per_epoch = t->data->n / t->B;
    double t0 = now_s(), ema = NAN;
    while (t->step < until) {
        double l;
        cs_status st = train_step(t, &l);
        if (st) return st;
        ema = isnan(ema) ? l : 0.95 * ema + 0.05 * l;
        if (ckpt && ckpt_every > 0 && t->step % ckpt_every == 0 && t->step < until) {
            st = train_save(t, ckpt);
            if (st) return st;
        }
        if (progress && (t->step % every == 0 || t->step == until)) {
            double el = now_s() - t0, eta = el / (double)(t->step - start) * (double)(until - t->step);
            fprintf(progress, "epoch %d/%ld  step %ld/%ld  loss %.5f (avg %.5f)  %.1f steps/s  ETA %02d:%02d\n",
                    t->epoch, (t->o.steps + per_epoch - 1) / per_epoch, t->step, t->o.steps, l, ema,
                    (double)(t->step - start) / el, (int)(eta / 60), (int)fmod(eta, 60));
            fflush(progress);
        }
    }
    return ckpt ? train_save(t, ckpt) : CS_OK;
}

/* ---- checkpoints ------------------------------------------------------------ */
typedef struct { unsigned char *p; size_t n, cap; int oom; } buf;

static void put(buf *b, const void *src, size_t n)
{
    if (b->oom) return;
    if (b->n + n > b->cap) {
        size_t nc = (b->cap ? b->cap * 2 : 4096);
        while (nc < b->n + n) nc *= 2;
        unsigned char *q = realloc(b->p, nc);
        if (!q) { b->oom = 1; return; }
        b->p = q;
        b->cap = nc;
    }
    memcpy(b->p + b->n, src, n);
    b->n += n;
}
#define PUTV(b, v) put((b), &(v), sizeof(v))

typedef struct {
    int32_t cfg[11]; /* T P nfeat ncond ntime C L H F joint pair */
    int32_t batch, epoch, pos, ndata;
    int32_t ingr; /* stdz | nuse << 8 (cfg_ingr): in what was the alignment padding, zero in the files written before
                     the readings */
    int64_t step, steps;
    uint64_t nparams, data_hash, rng_size, nnorm;
    double scale, lr, warmup, lr_final, b1, b2, eps, wd;
    uint64_t seeds[3];
} ckpt_head;

/* The ingredients beyond `pair` (model.h stdz, nuse) in one int32 of the
 * file headers, where both formats had a zero pad: zero for the plain and pair
 * readings, so their files are those written before the readings. */
static int32_t cfg_ingr(const model_cfg *c) { return (int32_t)(c->stdz | c->nuse << 8); }
static model_cfg cfg_from(const int32_t v[11], int32_t ingr)
{
    model_cfg c = {v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], v[9], v[10], ingr & 0xff, ingr >> 8};
    return c;
}
_Static_assert(offsetof(ckpt_head, step) == 64 && sizeof(ckpt_head) == 200,
               "checkpoint header layout of format version 2");

static void fill_head(const train *t, ckpt_head *h)
{
    memset(h, 0, sizeof *h);
    const model_cfg *c = &t->m->cfg;
    int32_t v[11] = {c->T, c->P, c->nfeat, c->ncond, c->ntime, c->C, c->L, c->H, c->F, c->joint, c->pair};
    memcpy(h->cfg, v, sizeof v);
    h->ingr = cfg_ingr(c);
    h->batch = t->B; h->epoch = t->epoch; h->pos = t->pos; h->ndata = t->data->n;
    h->step = t->step; h->steps = t->o.steps;
    h->nparams = t->m->nparams; h->data_hash = t->data_hash; h->nnorm = t->m->nnorm;
    h->rng_size = gsl_rng_size(t->rng_noise);
    h->scale = t->data->scale; h->lr = t->o.lr; h->warmup = t->o.warmup; h->lr_final = t->o.lr_final;
    h->b1 = t->o.hp.beta1; h->b2 = t->o.hp.beta2; h->eps = t->o.hp.eps; h->wd = t->o.hp.wd;
    h->seeds[0] = t->o.seed_init; h->seeds[1] = t->o.seed_batch; h->seeds[2] = t->o.seed_noise;
}

static size_t ckpt_body_size(const ckpt_head *h)
{
    return 8 + 4 + sizeof *h + 3 * h->rng_size + sizeof(int32_t) * (size_t)h->ndata
         + sizeof(float) * h->nnorm + 3 * sizeof(float) * h->nparams;
}

static cs_status write_sealed(buf *bb, const char *path);

cs_status train_save(const train *t, const char *path)
{
    ckpt_head h;
    fill_head(t, &h);
    buf b = {0};
    uint32_t ver = CKPT_VERSION;
    put(&b, CKPT_MAGIC, 8);
    PUTV(&b, ver);
    PUTV(&b, h);
    put(&b, gsl_rng_state(t->rng_init), h.rng_size);
    put(&b, gsl_rng_state(t->rng_batch), h.rng_size);
    put(&b, gsl_rng_state(t->rng_noise), h.rng_size);
    for (int i = 0; i < t->data->n; i++) { int32_t v = t->perm[i]; PUTV(&b, v); }
    put(&b, t->m->norm, sizeof(float) * h.nnorm);
    put(&b, t->m->params, sizeof(float) * h.nparams);
    put(&b, t->am, sizeof(float) * h.nparams);
    put(&b, t->av, sizeof(float) * h.nparams);
    return write_sealed(&b, path);
}

/* Append the FNV-1a checksum to b and write it atomically (afile: a unique
 * temporary name, fsync, rename), so two writers never share a temporary file;
 * frees b's bytes. */
static cs_status write_sealed(buf *bb, const char *path)
{
    buf b = *bb;
    uint64_t sum = b.oom ? 0 : fnv1a(FNV0, b.p, b.n);
    PUTV(&b, sum);
    if (b.oom) { free(b.p); return cs_err(CS_ENOMEM, "%s: out of memory writing checkpoint", path); }
    afile a;
    cs_status st = afile_open(&a, path);
    if (st) { free(b.p); return st; }
    if (fwrite(b.p, 1, b.n, a.f) != b.n) a.err = 1;
    free(b.p);
    return afile_commit(&a);
}

/* Read and verify a checkpoint: magic, version, sizes, checksum. On success
 * *data owns the bytes and *h is the header. */
static cs_status ckpt_read(const char *path, unsigned char **data, size_t *len, ckpt_head *h)
{
    *data = NULL;
    cs_status ist = paths_input_file(path); /* a directory is an input error, not "out of memory" */
    if (ist) return ist;
    FILE *f = fopen(path, "rb");
    if (!f) return cs_err(CS_EINPUT, "%s: cannot open checkpoint: %s", path, strerror(errno));
    if (fseek(f, 0, SEEK_END) != 0) { fclose(f); return cs_err(CS_EINPUT, "%s: cannot seek", path); }
    long n = ftell(f);
    rewind(f);
    if (n < 0) { fclose(f); return cs_err(CS_EINPUT, "%s: cannot size", path); }
    size_t minlen = 8 + 4 + sizeof *h + 8;
    if ((size_t)n < minlen) {
        fclose(f);
        return cs_err(CS_EINPUT, "%s: truncated checkpoint (%ld bytes, header needs %zu)", path, n, minlen);
    }
    unsigned char *p = malloc((size_t)n);
    if (!p) { fclose(f); return cs_err(CS_ENOMEM, "%s: out of memory", path); }
    size_t got = fread(p, 1, (size_t)n, f);
    fclose(f);
    if (got != (size_t)n) { free(p); return cs_err(CS_EINPUT, "%s: short read", path); }
    if (memcmp(p, CKPT_MAGIC, 8) != 0) {
        free(p);
        return cs_err(CS_EINPUT, "%s: not a crownshy checkpoint (bad magic)", path);
    }
    uint32_t ver;
    memcpy(&ver, p + 8, 4);
    if (ver != CKPT_VERSION) {
        free(p);
        if (ver < CKPT_VERSION)
            return cs_err(
                CS_EINPUT,
                "%s: checkpoint format version %u is no longer read (this build writes and reads "
                "version %u: pair-aware model configuration and feature z-scores); delete it to restart the run",
                path, ver, CKPT_VERSION);
        return cs_err(CS_EINPUT, "%s: checkpoint version %u, expected %u", path, ver, CKPT_VERSION);
    }
    memcpy(h, p + 12, sizeof *h);
    /* bound the declared sizes before using them in arithmetic */
    if (h->nparams > ((uint64_t)1 << 34) || h->nnorm > (1u << 20) || h->rng_size > (1u << 20) || h->ndata < 0 ||
        h->ndata > (1 << 28)) {
        free(p);
        return cs_err(CS_EINPUT, "%s: corrupt checkpoint header (implausible sizes)", path);
    }
    size_t want = ckpt_body_size(h) + 8;
    if ((size_t)n != want) {
        free(p);
        return cs_err(CS_EINPUT, "%s: %s checkpoint: %ld bytes, header declares %zu", path,
                      (size_t)n < want ? "truncated" : "oversized", n, want);
    }
    uint64_t sum;
    memcpy(&sum, p + n - 8, 8);
    if (fnv1a(FNV0, p, (size_t)n - 8) != sum) {
        free(p);
        return cs_err(CS_EINPUT, "%s: checkpoint checksum mismatch (corrupt or tampered)", path);
    }
    *data = p;
    *len = (size_t)n;
    return CS_OK;
}

cs_status train_load(train *t, const char *path)
{
    unsigned char *p;
    size_t len;
    ckpt_head h, mine;
    cs_status st = ckpt_read(path, &p, &len, &h);
    if (st) return st;
    fill_head(t, &mine);
    const char *what = NULL;
    if (memcmp(h.cfg, mine.cfg, sizeof h.cfg) || h.ingr != mine.ingr) what = "model configuration";
    else if (h.nparams != mine.nparams || h.nnorm != mine.nnorm) what = "parameter count";
    else if (h.batch != mine.batch || h.steps != mine.steps || h.lr != mine.lr || h.warmup != mine.warmup ||
             h.lr_final != mine.lr_final || h.b1 != mine.b1 || h.b2 != mine.b2 || h.eps != mine.eps || h.wd != mine.wd)
        what = "training options";
    else if (memcmp(h.seeds, mine.seeds, sizeof h.seeds)) what = "seeds";
    else if (h.ndata != mine.ndata || h.data_hash != mine.data_hash || h.scale != mine.scale) what = "training data";
    else if (h.rng_size != mine.rng_size) what = "RNG type";
    else if (h.step < 0 || h.step > h.steps || h.pos < 0 || h.pos > h.ndata || h.epoch < 0) what = "step counters";
    if (what) {
        free(p);
        return cs_err(CS_EINPUT, "%s: checkpoint belongs to a different run (%s differs)", path, what);
    }
    const unsigned char *q = p + 12 + sizeof h;
    memcpy(gsl_rng_state(t->rng_init), q, h.rng_size); q += h.rng_size;
    memcpy(gsl_rng_state(t->rng_batch), q, h.rng_size); q += h.rng_size;
    memcpy(gsl_rng_state(t->rng_noise), q, h.rng_size); q += h.rng_size;
    for (int i = 0; i < h.ndata; i++) {
        int32_t v;
        memcpy(&v, q, 4); q += 4;
        if (v < 0 || v >= h.ndata) { free(p); return cs_err(CS_EINPUT, "%s: corrupt permutation entry %d", path, i); }
        t->perm[i] = v;
    }
    memcpy(t->m->norm, q, sizeof(float) * h.nnorm); q += sizeof(float) * h.nnorm;
    size_t nb = sizeof(float) * h.nparams;
    memcpy(t->m->params, q, nb); q += nb;
    memcpy(t->am, q, nb); q += nb;
    memcpy(t->av, q, nb);
    t->step = h.step; t->epoch = h.epoch; t->pos = h.pos;
    free(p);
    return CS_OK;
}

/* ---- weights files (see train.h) ---------------------------------------------- */
#define WGTS_MAGIC "CSHYWGTS"
#define WGTS_VERSION 1u
typedef struct {
    int32_t cfg[11];
    int32_t ingr; /* cfg_ingr; the pad of the files written before the readings */
    uint64_t nparams, nnorm;
    double scale;
} wgts_head;
_Static_assert(sizeof(wgts_head) == 72, "weights header layout of format version 1");

cs_status train_save_weights(const train *t, const char *path)
{
    wgts_head h;
    memset(&h, 0, sizeof h);
    const model_cfg *c = &t->m->cfg;
    int32_t v[11] = {c->T, c->P, c->nfeat, c->ncond, c->ntime, c->C, c->L, c->H, c->F, c->joint, c->pair};
    memcpy(h.cfg, v, sizeof v);
    h.ingr = cfg_ingr(c);
    h.nparams = t->m->nparams; h.nnorm = t->m->nnorm; h.scale = t->data->scale;
    buf b = {0};
    uint32_t ver = WGTS_VERSION;
    put(&b, WGTS_MAGIC, 8);
    PUTV(&b, ver);
    PUTV(&b, h);
    put(&b, t->m->norm, sizeof(float) * h.nnorm);
    put(&b, t->m->params, sizeof(float) * h.nparams);
    return write_sealed(&b, path);
}

static cs_status slurp(const char *path, unsigned char **data, long *len)
{
    *data = NULL;
    FILE *f = fopen(path, "rb");
    if (!f) return cs_err(CS_EINPUT, "%s: cannot open: %s", path, strerror(errno));
    long n = -1;
    if (fseek(f, 0, SEEK_END) == 0) n = ftell(f);
    rewind(f);
    unsigned char *p = n >= 0 ? malloc((size_t)n + 1) : NULL;
    if (!p || fread(p, 1, (size_t)n, f) != (size_t)n) {
        free(p);
        fclose(f);
        return cs_err(CS_EINPUT, "%s: cannot read", path);
    }
    fclose(f);
    *data = p;
    *len = n;
    return CS_OK;
}

static cs_status weights_load(const char *path, model **out, int Bmax, double *scale)
{
    unsigned char *p = NULL;
    long n = 0;
    cs_status st = slurp(path, &p, &n);
    if (st) return st;
    wgts_head h;
    uint32_t ver = 0;
    const long hl = 8 + 4 + (long)sizeof h;
    if (n < hl + 8) { free(p); return cs_err(CS_EINPUT, "%s: truncated weights file (%ld bytes)", path, n); }
    memcpy(&ver, p + 8, 4);
    if (ver != WGTS_VERSION) {
        free(p);
        return cs_err(CS_EINPUT, "%s: weights format version %u, expected %u", path, ver, WGTS_VERSION);
    }
    memcpy(&h, p + 12, sizeof h);
    if (h.nparams > ((uint64_t)1 << 30) || h.nnorm > (1u << 20)) {
        free(p);
        return cs_err(CS_EINPUT, "%s: corrupt weights header (implausible sizes)", path);
    }
    long want = hl + (long)(sizeof(float) * (h.nnorm + h.nparams)) + 8;
    if (n != want) {
        free(p);
        return cs_err(CS_EINPUT, "%s: %s weights file: %ld bytes, header declares %ld", path,
                      n < want ? "truncated" : "oversized", n, want);
    }
    uint64_t sum;
    memcpy(&sum, p + n - 8, 8);
    if (fnv1a(FNV0, p, (size_t)n - 8) != sum) {
        free(p);
        return cs_err(CS_EINPUT, "%s: weights checksum mismatch (corrupt or tampered)", path);
    }
    model_cfg c = cfg_from(h.cfg, h.ingr);
    model *m;
    if ((st = model_alloc(&m, &c, Bmax))) {
        free(p);
        return cs_err(CS_EINPUT, "%s: weights model configuration unusable: %s", path, cs_errmsg());
    }
    if (m->nparams != h.nparams || m->nnorm != h.nnorm) {
        model_free(m);
        free(p);
        return cs_err(CS_EINPUT, "%s: parameter count mismatch", path);
    }
    memcpy(m->norm, p + hl, sizeof(float) * h.nnorm);
    memcpy(m->params, p + hl + sizeof(float) * h.nnorm, sizeof(float) * h.nparams);
    if (scale) *scale = h.scale;
    free(p);
    *out = m;
    return CS_OK;
}

cs_status train_load_model(const char *path, model **out, int Bmax, double *scale)
{
    unsigned char *p;
    size_t len;
    ckpt_head h;
    *out = NULL;
    {
        FILE *f = fopen(path, "rb");
        char mg[8] = {0};
        if (f) {
            size_t got = fread(mg, 1, 8, f);
            fclose(f);
            if (got == 8 && !memcmp(mg, WGTS_MAGIC, 8)) return weights_load(path, out, Bmax, scale);
        }
    }
    cs_status st = ckpt_read(path, &p, &len, &h);
    if (st) return st;
    model_cfg c = cfg_from(h.cfg, h.ingr);
    model *m;
    st = model_alloc(&m, &c, Bmax);
    if (st) { free(p); return cs_err(CS_EINPUT, "%s: checkpoint model configuration unusable: %s", path, cs_errmsg()); }
    if (m->nparams != h.nparams || m->nnorm != h.nnorm) {
        model_free(m);
        free(p);
        return cs_err(CS_EINPUT, "%s: parameter count mismatch", path);
    }
    const unsigned char *q = p + 12 + sizeof h + 3 * h.rng_size + sizeof(int32_t) * (size_t)h.ndata;
    memcpy(m->norm, q, sizeof(float) * h.nnorm);
    memcpy(m->params, q + sizeof(float) * h.nnorm, sizeof(float) * h.nparams);
    if (scale) *scale = h.scale;
    free(p);
    *out = m;
    return CS_OK;
}
