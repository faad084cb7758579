/* mainrun: the evaluation of one E3/E4 unit from a model (reference paper
 * §4.3-§5.2; design.md §7 E3/E4, §8): every evaluation spacing x probe of the
 * plan, the W1 of each and the clearance samples behind it, and the tables a
 * unit writes (run table, samples). main-run (train, then evaluate),
 * main-eval (evaluate frozen weights) and main-redraw (the samples only) all
 * come through here, so a re-evaluation gives a run's rows bit for bit.
 *
 * Evaluation volumes (mainrun_plan.volume; evalvol.h), named by their teacher
 * stands per evaluation spacing at full scale (smoke scale shrinks both):
 * 16-stands, the volume of the pair runs in
 * frozen/extension-pair-16-stands/main/ (16 teacher stands and 256 generated
 * patches per spacing; probes at every spacing, as many as that model had);
 * 96-stands, the volume of the generator readings (design.md
 * §8 "Readings of the generator"): more stands and patches per spacing for a
 * lower noise floor, the probes at the unseen spacings only (no claim reads
 * them at the extrapolation spacings), the same for every reading. Evaluation
 * stands and sampling seeds do not depend on the volume: the first 16 stands
 * of 96-stands are those of 16-stands, each spacing x probe draws from its own
 * seed. Every function returns cs_status and never exits. */
#ifndef MAINRUN_H
#define MAINRUN_H
#include "cs.h"
#include "evalvol.h"
#include "mainset.h"
#include "model.h"
#include "prov.h"
#include <stddef.h>

/* Stands per training spacing at full scale (chosen so that E3+E4
 * fit the 60 min budget on 2 cores; measured, README "Budgets"). */
#define MAINRUN_TRAIN_STANDS 12


typedef struct {
    const char *scale;     /* "full" or "smoke" */
    const char *volume;    /* evaluation volume: EVALVOL_SMALL or EVALVOL_LARGE (evalvol.h) */
    int train_stands;      /* stands per training spacing */
    int eval_stands;       /* teacher stands per eval spacing */
    int gen_patches;       /* generated patches per eval spacing */
    int epochs;            /* full: gates/main.gate epochs */
    int euler;             /* gates/main.gate euler_steps */
    int batch;
    double lr;
} mainrun_plan;

/* The plan for a scale ("full" or "smoke"); gate values read from gates/. */
cs_status mainrun_plan_get(const char *scale, mainrun_plan *p);

/* Set the evaluation stands and generated patches of p (scale set) for a
 * volume ("16-stands" or "96-stands"; CS_EUSAGE naming both otherwise). */
cs_status mainrun_plan_volume(mainrun_plan *p, const char *volume);

/* 1 when the plan evaluates at the small volume (16-stands). */
int mainrun_volume_small(const mainrun_plan *p);


/* One W1 of a run: spacing, probe, the generated clearances behind it, and
 * (on the generated row of a spacing) the teacher's. */
typedef struct {
    double d, w1;
    int unseen, ng, nt;
    mainset_probe probe;
    double *gen, *teach;
} mainrun_row;

#define MAINRUN_MAXROWS (MAINSET_NPROBE * 2 * MAINSET_MAXSP)

void mainrun_rows_free(mainrun_row *rows, size_t n);

/* Probes of a unit at an unseen (unseen = 1) or an extrapolation spacing:
 * at 16-stands as the pair runs in frozen/extension-pair-16-stands/main/
 * (pair model every probe on both arms; the plain model shuffled on the joint
 * arm, none on the independent one), at 96-stands every probe at the unseen spacings and none
 * at the extrapolation ones. */
int mainrun_nprobe(const mainrun_plan *pl, const model_cfg *cfg, int unseen);

/* Every evaluation spacing x probe of model m under plan pl (deviation scale
 * `scale`, model seed `seed`): rows[*nrows] (at most MAINRUN_MAXROWS), worst
 * overlap and estimator agreement; a progress line per row to stderr. */
cs_status mainrun_evaluate(model *m, int Bmax, const mainset_design *ds, const mainrun_plan *pl, double scale,
                           unsigned seed, const char *arm, mainrun_row *rows, size_t *nrows,
                           double *worst, double *maxdiff);
/* The same, for spacing only_d (NAN: every spacing) and probe only_probe (-1:
 * every probe) alone: the rows equal those rows of the whole evaluation bit
 * for bit (each spacing and probe draws from its own stream); the teacher
 * values ride on the first row of each spacing. */
/* The training patches of a unit, as a projection counts them: about 64
 * interior focal stems per training stand (the stand layout of mainset.h),
 * x pl->train_stands x the training spacings; the count itself comes from
 * building the stands, which a projection does not. */
long mainrun_train_patches(const mainset_design *ds, const mainrun_plan *pl);
/* The model FLOPs mainrun_evaluate spends on model m's configuration: every
 * evaluation spacing x its probes (mainrun_nprobe) x pl->euler forward passes
 * over pl->gen_patches in chunks of Bmax (speed_forward_flops); the most a
 * spacing with fewer patches can take. A projection's count (tier 2). */
double mainrun_eval_flops(const model_cfg *cfg, int Bmax, const mainset_design *ds, const mainrun_plan *pl);
cs_status mainrun_evaluate_slice(model *m, int Bmax, const mainset_design *ds, const mainrun_plan *pl, double scale,
                                 unsigned seed, const char *arm, double only_d, int only_probe, mainrun_row *rows,
                                 size_t *nrows, double *worst, double *maxdiff);

/* The samples behind every W1 of a run (README "Frozen samples and weights"). */
cs_status mainrun_samples_write(const char *path, prov *pv, unsigned seed, const char *arm,
                                const mainrun_row *rows, size_t n);

/* The run table: provenance, the `# key: value` lines meta[nmeta][2], the rows. */
cs_status mainrun_table_write(const char *path, prov *pv, unsigned seed, const char *arm,
                              const char *const (*meta)[2], int nmeta, const mainrun_row *rows, size_t n);

/* The provenance `seeds` text of a unit. */
const char *mainrun_seeds_text(char *buf, size_t n, unsigned seed);

#endif
