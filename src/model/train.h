/* train: the flow-matching trainer (paper §4.2, Eq. 2; design.md §8): batches of
 * patches in an epoch-wise random order, AdamW with linear warm-up and cosine
 * decay, atomic checkpoints that resume bit-identically, and progress lines
 * (the benchmark of design.md §10 times train_step: speed.h).
 *
 * Randomness: three explicitly seeded gsl_rng_mt19937 streams - init
 * (parameters), batch (epoch permutations), noise (t and x0 of Eq. 2) - never
 * seeded from the environment. The checkpoint holds parameters, both AdamW
 * moments, the step and epoch cursor, the current permutation and all three
 * RNG states, so a run killed and resumed ends with the same bytes as a run
 * that was never interrupted (one BLAS thread, same machine).
 *
 * Checkpoint file (format version 2): magic "CSHYCKPT", uint32 version, a
 * header (model configuration T P nfeat ncond ntime C L H F joint pair as
 * int32; batch, epoch, cursor, data size; step counts; parameter, z-score
 * and RNG state sizes; a fingerprint of the training data; scale, optimiser
 * options and seeds), the three RNG states, the permutation (int32), the
 * model's feature z-scores (nnorm floats, 0 for the plain reading), the
 * parameters and both AdamW moments (float), and a 64-bit FNV-1a checksum of
 * everything before it; native little-endian x86-64 layout. Version 1 files
 * (before the pair model) are refused with a message naming the version. Written to "<path>.tmp", fsync'd and
 * renamed. A truncated, tampered, foreign or mismatched file is rejected with
 * CS_EINPUT and a message naming the file and the problem. */
#ifndef TRAIN_H
#define TRAIN_H
#include "adamw.h"
#include "cs.h"
#include "model.h"
#include "patch.h"
#include <stdio.h>

typedef struct {
    int batch;             /* patches per step (capped at the data size) */
    long steps;            /* total optimiser steps */
    double lr;             /* peak learning rate */
    double warmup;         /* fraction of steps with linear warm-up */
    double lr_final;       /* final lr as a fraction of the peak (cosine) */
    adamw_hp hp;
    unsigned long seed_init, seed_batch, seed_noise;
} train_opts;

/* batch 64, steps 1000, lr 2e-3, warm-up 5 %, final 0.1, AdamW defaults, seeds 1, 2, 3. */
train_opts train_opts_default(void);

typedef struct train {
    model *m;
    float *am, *av; /* AdamW moments, same layout as m->params */
    train_opts o;
    const patch_set *data; /* not owned; must be standardised */
    unsigned long long data_hash;
    gsl_rng *rng_init, *rng_batch, *rng_noise;
    long step;  /* optimiser steps done */
    int epoch;  /* epochs started */
    int pos;    /* next index into perm */
    int B;      /* effective batch */
    int *perm;  /* [data->n] */
    float *bx1, *bfeat, *bcond;
    double loss; /* loss of the last step */
} train;

/* Build model and optimiser state; parameters from seed_init. */
cs_status train_alloc(train **out, const model_cfg *cfg, const patch_set *data, const train_opts *o);
void train_free(train *t);
/* Learning rate used at 1-based step s. */
double train_lr(const train_opts *o, long s);
/* One optimiser step (batch draw, Eq. 2 loss and gradient, AdamW). */
cs_status train_step(train *t, double *loss);
/* Steps until t->step == until. Every ckpt_every steps (0: never) and at the
 * end, an atomic checkpoint to ckpt (NULL: none). Progress lines to `progress`
 * (NULL: silent) about every 2 % with epoch, step, loss and ETA. */
cs_status train_run(train *t, long until, const char *ckpt, long ckpt_every, FILE *progress);

/* Mean Eq. 2 loss of the current parameters over the first nbatch batches of
 * `data` (in order), with its own noise stream seeded by `seed`; no update. */
cs_status train_eval_loss(train *t, const patch_set *data, int nbatch, unsigned long seed, double *loss);

cs_status train_save(const train *t, const char *path);
/* Restore state saved by train_save into t (same config, options and data). */
cs_status train_load(train *t, const char *path);
/* Weights file (format version 1; the frozen weights of E3/E4, README): magic
 * "CSHYWGTS", uint32 version, int32 T P nfeat ncond ntime C L H F joint pair
 * and an int32 pad, uint64 nparams and nnorm, double deviation scale, the
 * feature z-scores (nnorm floats), the parameters (float, flat buffer of
 * model.h) and a 64-bit FNV-1a checksum of everything before it; native
 * little-endian x86-64 layout, written atomically. */
cs_status train_save_weights(const train *t, const char *path);
/* Read the model (and its deviation scale) of a checkpoint or a weights file
 * (told apart by the magic) into a freshly allocated model with that config
 * (used by `crownshy sample`, comparison-run and main-redraw). */
cs_status train_load_model(const char *path, model **out, int Bmax, double *scale);

#endif
