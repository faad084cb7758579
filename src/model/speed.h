/* speed: the model measurements of `make bench` (design.md §10), every rate
 * against the core's own fused multiply-add peak measured beside it.
 *
 * The machine is shared and its clock drifts, so no rate is judged against a
 * peak measured at another moment: each measurement (own product, OpenBLAS
 * sgemm, a training step, an Euler step of sampling) runs between two peak
 * loops (gemm_peak_gflops at the path's vector width) and is reported as a
 * fraction of their mean; the measurements rotate within a round and the
 * rounds repeat, so every quantity gets a median and a range over rounds.
 * Runs on the gemm path chosen with gemm_set_isa (the layer kernels follow,
 * gemm.h). Results never depend on the timing: this is a benchmark, not a
 * test. */
#ifndef SPEED_H
#define SPEED_H
#include "cs.h"
#include "model.h"

enum { SPEED_MAX_ROUNDS = 15 };

/* The goals `make bench` judges, each a fraction of the path's own FMA peak
 * measured beside the figure (never of another library's rate, whose kernel
 * choice on a given core is not ours): the own product on the products of a
 * training pass, a training step of either model, and a sampling step of the
 * pair model. */
#define SPEED_GOAL_PRODUCT 0.85
#define SPEED_GOAL_TRAIN 0.75
/* An Euler step of the pair model's sampling (either arm): forward only, so
 * no lower than training's goal, and the pass tier 2 spends most of its time in. */
#define SPEED_GOAL_SAMPLE 0.80

/* Training steps run before each timed run of consecutive steps on one
 * model, so a figure is the sustained rate of training, not the rate of a
 * step entered with another measurement's data in the caches. */
enum { SPEED_WARMUP_STEPS = 4 };

/* One quantity over the rounds: rate (GFLOP/s, or ms for times) and its
 * fraction of the neighbouring peak; median, minimum and maximum. */
typedef struct { double med, lo, hi; } speed_stat;
typedef struct { speed_stat rate, frac; } speed_item;

typedef enum {
    SPEED_PRODUCT = 0, /* gemm_fma on the products of one training pass */
    SPEED_SGEMM,       /* cblas_sgemm on the same products (yardstick) */
    SPEED_PLAIN,       /* plain model, joint arm: training step */
    SPEED_PAIR,        /* pair model, joint arm: training step */
    SPEED_PAIR_INDEP,  /* pair model, independent arm: training step */
    SPEED_PLAIN_SAMPLE, /* plain model, joint arm: one Euler step of a batch */
    SPEED_PAIR_SAMPLE,  /* pair model, joint arm: one Euler step */
    SPEED_PAIR_INDEP_SAMPLE, /* pair model, independent arm: one Euler step */
    SPEED_NITEMS
} speed_what;

typedef struct {
    int rounds, batch;
    speed_stat peak;              /* GFLOP/s at the path's widest vector */
    speed_stat peak256;           /* the same loop at 256 bits (AVX2 lanes) */
    speed_item item[SPEED_NITEMS]; /* rate in GFLOP/s (model-counted FLOPs) */
    speed_stat ms[SPEED_NITEMS];  /* ms per call (step, Euler step, product set) */
} speed_result;

/* Name of an item for the printed table ("own_product", "pair_train", ...). */
const char *speed_name(speed_what w);

/* Model FLOPs of one forward pass (one Euler step of sampling) at batch B:
 * the forward part of model_train_flops's count. */
double speed_forward_flops(const model_cfg *cfg, int B);

/* The sampling rate of model m on this core now: one untimed Euler step of a
 * B-patch batch (features drawn uniform in [-1, 1] from a fixed seed: the
 * work of a pass does not depend on the values), then `steps` timed ones, in
 * the thread's CPU time; *gflops = speed_forward_flops / CPU seconds per
 * step. A projection's yardstick (tier 2's projected time), never a test. */
cs_status speed_sample_gflops(model *m, int B, int steps, double *gflops);

/* This core's rates now for a fresh model of configuration cfg on toy
 * patches (patch_set_add_toy): training (one untimed step, then `steps`
 * timed, model_train_flops each) and sampling (speed_sample_gflops), GFLOP/s
 * of thread CPU time. A projection's yardstick (the study's cost). */
cs_status speed_model_gflops(const model_cfg *cfg, int B, int steps, double *train_gflops, double *sample_gflops);

/* `rounds` rounds (1..SPEED_MAX_ROUNDS) on the current gemm path at the
 * reference configuration with batch B (cfg's joint/pair are set per item);
 * `steps` consecutive training steps (after SPEED_WARMUP_STEPS untimed ones
 * on the same model) or Euler steps (after one untimed) per measurement. */
cs_status speed_run(const model_cfg *ref, int B, int rounds, int steps, speed_result *r);

#endif
