/* exp_main: the main experiment E3 and extrapolation E4 (reference paper
 * §4.3-§5.2; design.md §7 E3/E4, §8). One unit per (seed, arm): build the teacher
 * data, train the flow model (joint or independent arm), generate eval
 * patches at the unseen (4.0, 5.0, 6.0 m) and extrapolation (3.0, 7.5 m)
 * spacings, and measure W1 between generated and teacher focal nearest-
 * neighbour clearances; both arms are also probed with shuffled geometry (the
 * preregistered probe) and rotated geometry (added after the first verdict),
 * and each unit writes the clearance samples behind its W1 and its weights.
 * A baselines unit measures the direction-blind baseline and the split-half
 * noise floor; a summary unit gathers the runs into the frozen tables.
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
#include "model.h"
#include "patch.h"
#include <gsl/gsl_rng.h>

/* Stands per training spacing at full scale (design.md §8: chosen so that E3+E4
 * fit the 60 min budget on 2 cores; measured, README "Budgets"). */
#define EXP_MAIN_TRAIN_STANDS 12

typedef struct {
    const char *scale;     /* "full" or "smoke" */
    int train_stands;      /* stands per training spacing */
    int eval_stands;       /* teacher stands per eval spacing */
    int gen_patches;       /* generated patches per eval spacing */
    int epochs;            /* full: gates/main.gate epochs */
    int euler;             /* gates/main.gate euler_steps */
    int batch;
    double lr;
} exp_main_plan;

/* The plan for a scale ("full" or "smoke"); gate values read from gates/. */
cs_status exp_main_plan_get(const char *scale, exp_main_plan *p);

/* The entry points (argv tables: src/cli/cli_main.c). argc/argv are the
 * command line, quoted in the provenance. */
typedef struct {
    unsigned seed;           /* model seed, >= 1 */
    const char *arm;         /* "joint" or "indep" */
    const char *out;         /* the run table */
    const char *scale;       /* "full" or "smoke" */
    const char *ckpt;        /* checkpoint, resumed from when it exists (NULL: none) */
    const char *samples;     /* also the clearance samples behind every W1 (NULL: none) */
    const char *weights;     /* also the final weights (NULL: none) */
    long epochs;             /* 0: the plan's; else an exploration override */
    long train_stands;       /* 0: the plan's; else an exploration override */
    int pair;                /* 1: the pair-aware model (design.md §8), 0: the plain one */
    int argc;
    char **argv;
} exp_main_run_args;
/* One (seed, arm) unit: train (resuming), evaluate, write the run table. */
cs_status exp_main_run(const exp_main_run_args *a);

typedef struct {
    const char *weights, *arm, *out, *scale;
    unsigned seed;
    int argc;
    char **argv;
} exp_main_redraw_args;
/* A unit's samples drawn again from its weights alone (no training). */
cs_status exp_main_redraw(const exp_main_redraw_args *a);

typedef struct {
    const char *out, *scale, *samples; /* samples: NULL for none */
    int argc;
    char **argv;
} exp_main_baselines_args;
/* The direction-blind baseline, the noise floor and the teacher under the probes. */
cs_status exp_main_baselines(const exp_main_baselines_args *a);

typedef struct {
    const char *dir; /* results root */
    int seeds;       /* seeds 1..seeds */
    int argc;
    char **argv;
} exp_main_summary_args;
/* main/runs.tsv and extrapolation/runs.tsv from the run tables. */
cs_status exp_main_summary(const exp_main_summary_args *a);

#endif
