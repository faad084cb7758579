/* mainsum: the E3/E4 units that need no model (reference paper §4.3,
 * §5.1-§5.2; design.md §7 E3/E4): main-baselines, the baselines of an
 * evaluation volume (direction-blind level, split-half noise floor, the
 * teacher's own crowns under the probes), and main-summary, a reading's
 * per-run tables gathered into its main/runs.tsv and extrapolation/runs.tsv.
 * Entry points of the argv tables in src/cli/cli_main.c. */
#ifndef MAINSUM_H
#define MAINSUM_H
#include "cs.h"

typedef struct {
    const char *out, *scale, *samples; /* samples: NULL for none */
    const char *volume;                /* "16-stands" or "96-stands" (NULL: 16-stands; src/exp/mainrun.h) */
    const char *vary;                  /* sensitivity: NAME=VALUE (exp_common.h), NULL for the design */
    int stand_rows;                    /* 1: also <dir of out>/baselines_stands.tsv, the patches of each stand */
    int argc;
    char **argv;
} mainsum_baselines_args;
/* The direction-blind baseline, the noise floor and the teacher under the
 * probes. With stand_rows, written before the table: baselines_stands.tsv
 * beside it (spacing, stand, patches: how many consecutive patches of the
 * samples each evaluation stand gave, in order), the replicate units of a
 * stand bootstrap of the baselines (design.md §6.1). */
cs_status mainsum_baselines(const mainsum_baselines_args *a);

typedef struct {
    const char *dir; /* a reading's results root */
    int seeds;       /* seeds 1..seeds */
    int argc;
    char **argv;
} mainsum_summary_args;
/* main/runs.tsv and extrapolation/runs.tsv from the run tables. */
cs_status mainsum_summary(const mainsum_summary_args *a);

#endif
