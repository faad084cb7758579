/* exp_main: the main experiment E3 and extrapolation E4 (reference paper
 * §4.3-§5.2; design.md §7 E3/E4, §8). One unit per (reading, seed, arm): build
 * the teacher data, train the flow model (joint or independent arm, one of
 * the generator readings of model.h), generate eval patches at the unseen
 * (4.0, 5.0, 6.0 m) and extrapolation (3.0, 7.5 m) spacings, and measure W1
 * between generated and teacher focal nearest-neighbour clearances; both arms
 * are also probed with shuffled geometry (the preregistered probe) and rotated
 * geometry (added after the first verdict), and each unit writes the
 * clearance samples behind its W1 and its weights. main-train trains only,
 * main-eval evaluates weights without training (src/exp/mainrun.h: the
 * evaluation volumes), main-redraw draws a unit's samples again; the
 * baselines and the summary are in src/exp/mainsum.h.
 *
 * Data plan (ours; design.md §8 leaves it open): teacher at beta_train (from
 * gates/mechanism.gate) on the controlled lattice (jitter from
 * gates/anisotropy.gate canonical_jitter), L = 12 d; every interior stem of a
 * stand is a focal stem. Seeds: seed_derive("main-train"|"main-eval", d, k, ·)
 * for stands, seed_derive("main-model", 0, seed, "init"|"batch"|"noise"|
 * "sample"|"shuffle") for the model, so train and eval stands are disjoint
 * by construction and both arms of a seed share every seed. */
#ifndef EXP_MAIN_H
#define EXP_MAIN_H
#include "cs.h"

/* The entry points (argv tables: src/cli/cli_main.c). argc/argv are the
 * command line, quoted in the provenance. */
typedef struct {
    unsigned seed;           /* model seed, >= 1 */
    const char *arm;         /* "joint" or "indep" */
    const char *out;         /* the run table (main-run) or the training table (main-train) */
    const char *scale;       /* "full" or "smoke" */
    const char *ckpt;        /* checkpoint, resumed from when it exists (NULL: none) */
    const char *samples;     /* also the clearance samples behind every W1 (NULL: none) */
    const char *weights;     /* also the final weights (NULL: none; main-train: required) */
    const char *reading;     /* generator reading (model.h; NULL: from pair, else pair) */
    const char *volume;      /* evaluation volume "16-stands" or "96-stands" (mainrun.h; NULL: 16-stands) */
    const char *trained;     /* main-eval: the unit's training or run table */
    long epochs;             /* 0: the plan's; else an exploration override */
    long train_stands;       /* 0: the plan's; else an exploration override */
    long width;              /* 0: the reference width (model.h); else the width, MLP 4 x width */
    long blocks;             /* 0: the reference depth (model.h); else the number of blocks */
    double lr;               /* 0: the plan's peak learning rate; else the peak learning rate */
    int pair;                /* -1 unset; 1 the pair reading, 0 the plain one (short for reading) */
    double only_spacing;     /* main-redraw: 0 every spacing; else that spacing alone */
    const char *only_probe;  /* main-redraw: NULL every probe; else that probe alone (generated, shuffled, rotated) */
    long only_patches; /* main-redraw: 0 the plan's generated patches; else the first this many (a prefix of the whole)
                        */
    int argc;
    char **argv;
} exp_main_run_args;
/* What a unit costs, run nothing: the model FLOPs of its training (the
 * plan's epochs x steps over mainrun_train_patches patches, model_train_flops
 * each) and of its evaluation (mainrun_eval_flops), and this core's rates now
 * for a fresh model of the unit's configuration (speed_model_gflops): the
 * study's projected cost (make bench). */
typedef struct { double train_flops, eval_flops, train_gflops, sample_gflops; } exp_main_cost;
cs_status exp_main_run_cost(const exp_main_run_args *a, exp_main_cost *c);
/* What redrawing a unit costs, drawing nothing: the model FLOPs of its
 * evaluation (mainrun_eval_flops, at the weights' configuration and the
 * plan's volume) and this core's sampling rate for that model now
 * (speed_sample_gflops, GFLOP/s of thread CPU time): tier 2's projection. */
cs_status exp_main_redraw_cost(const exp_main_run_args *a, double *flops, double *gflops);
/* One (seed, arm) unit: train (resuming), evaluate, write the run table. */
cs_status exp_main_run(const exp_main_run_args *a);
/* Train only: the weights and a one-row training table. */
cs_status exp_main_train(const exp_main_run_args *a);
/* Evaluate frozen weights (a->weights, a->trained) without training. */
cs_status exp_main_eval(const exp_main_run_args *a);
/* A unit's samples drawn again from its weights alone (no training). */
cs_status exp_main_redraw(const exp_main_run_args *a);

#endif
