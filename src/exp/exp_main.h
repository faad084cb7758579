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

/* Stands per training spacing at full scale (issue 14: chosen so that E3+E4
 * fit the 60 min budget on 2 cores; measured, README "Budgets"). */
#define EXP_MAIN_TRAIN_STANDS 12

/* Evaluation volume v2 at full scale (mainrun.h; design.md §8 "Readings of
 * the generator"): chosen from the split-half noise floor and its cost,
 * measured (README "Budgets"). */
#define EXP_MAIN_V2_EVAL_STANDS 96
#define EXP_MAIN_V2_GEN_PATCHES 1536

typedef struct {
    const char *scale;     /* "full" or "smoke" */
    const char *volume;    /* evaluation volume: "v1" or "v2" (mainrun.h) */
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

/* Set the evaluation stands and generated patches of p (scale set) for a
 * volume ("v1" or "v2"; CS_EUSAGE otherwise). */
cs_status exp_main_plan_volume(exp_main_plan *p, const char *volume);

/* CLI entry points (return process exit codes; design.md §11). */
int exp_main_cmd_run(int argc, char **argv);
int exp_main_cmd_baselines(int argc, char **argv);
int exp_main_cmd_summary(int argc, char **argv);
int exp_main_cmd_redraw(int argc, char **argv);
int exp_main_cmd_train(int argc, char **argv);
int exp_main_cmd_eval(int argc, char **argv);

#endif
