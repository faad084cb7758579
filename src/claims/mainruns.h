/* mainruns: the E3/E4 results of one generator reading gathered from its
 * per-run tables <dir>/run_sNN_{joint,indep}.tsv (design.md §8 "Readings of
 * the generator"; reference paper §5.1-§5.2). Each seed's error per arm and
 * probe is the mean of its W1 over the unseen spacings, summed in file order,
 * the reduction `crownshy main-summary` writes into main/runs.tsv, so a claim
 * computed here equals one computed from that summary bit for bit (tested).
 * The extrapolation W1 are the generated rows of split extrap, per spacing.
 * A reading whose units are not all frozen yet is reported as such: how many
 * seeds have both arms, and which units are missing (never a partial result).
 * Limits: at most MAINRUNS_MAXSEED seeds and MAINRUNS_MAXSP extrapolation
 * spacings. Returns cs_status; never exits. */
#ifndef MAINRUNS_H
#define MAINRUNS_H
#include "cs.h"
#include <stddef.h>

#define MAINRUNS_MAXSEED 64
#define MAINRUNS_MAXSP 4

typedef struct {
    int want;     /* seeds the design asks for */
    int complete; /* seeds 1..want with both arms frozen */
    int seed_ok[MAINRUNS_MAXSEED]; /* 1: that seed's two units are frozen */
    int nmissing; /* units missing among seeds 1..want x 2 arms */
    char missing[400]; /* their names (s02_joint s02_indep ...), shortened with "..." */
    /* [arm 0 joint, 1 indep][probe 0 generated, 1 shuffled, 2 rotated][seed - 1] */
    double err[2][3][MAINRUNS_MAXSEED];
    int has[2][3]; /* how many seeds carry that arm and probe */
    int nex;
    double exd[MAINRUNS_MAXSP];
    double ex[2][MAINRUNS_MAXSP][MAINRUNS_MAXSEED];
} mainruns;

/* The preregistered seeds of a gated reading (gates/main.gate's seeds); a
 * descriptive reading states its own in the registry (claim params seeds=). */
cs_status mainruns_gate_seeds(int *want);
/* Read every unit of seeds 1..want present under dir. m->complete == want
 * and m->nmissing == 0 when the set is whole; otherwise the values of the
 * present units are read but must not be reported as the reading's result. */
cs_status mainruns_load(const char *dir, int want, mainruns *m);
/* dir of a unit-set source: "<dir>/run_s*_*.tsv" -> "<dir>"; 0 when the
 * source is not a unit set. */
int mainruns_unit_set(const char *source, char *dir, size_t n);
/* One sentence for a pending claim: the reading under dir, how many of its
 * seeds are frozen and the missing units. */
void mainruns_pending_text(const mainruns *m, const char *dir, char *buf, size_t n);

#endif
