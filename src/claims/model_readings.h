/* model_readings: the generator readings table (design.md §8 "Readings of the
 * generator"; reference paper §4.2, §5.1-§5.2): one row per reading that has
 * run (paper, the reading the preregistered gates judge; pair, the extension
 * added after the first verdict; paper-fourier and plain, descriptive), each
 * recomputed from that reading's per-run tables under a results or frozen root:
 *   paper          <root>/paper-reading/{main,extrapolation}/
 *   pair           <root>/extension-pair/{main,extrapolation}/
 *   paper-fourier  <root>/model-readings/paper-fourier/{main,extrapolation}/
 *   plain          <root>/model-readings/plain/{main,extrapolation}/
 * Columns: seeds; parameters (the `# model:` line of the seed-1 joint run);
 * median over seeds of the joint and independent errors (mean W1 over the
 * unseen spacings); the direction-blind error of the paper reading's
 * baselines (<root>/paper-reading/main/baselines.tsv; the same evaluation volume for every reading); the relative
 * improvement and the exact Wilcoxon p of the paired seeds (main.gate); the
 * shuffled-geometry ratio of each arm and the rotation ratio of the joint arm
 * (median probe error / median error); how many seeds' joint arm passes the
 * preregistered shuffle threshold on its own (coupled seeds, main.gate
 * shuffle_ratio_min: a reading whose seeds split into two kinds of solution
 * shows it); the relative improvement at each
 * extrapolation spacing; the median training steps/s over the units that
 * recorded a training time (NaN when none did). No verdicts: the gates judge
 * the paper and pair readings through their claims. Returns cs_status. */
#ifndef MODEL_READINGS_H
#define MODEL_READINGS_H
#include "cs.h"
#include <stddef.h>

typedef struct {
    const char *reading, *role, *dir; /* dir relative to the root */
    int seeds, coupled;
    long params;
    double joint, indep, blind, rel, p, shuf_joint, shuf_indep, rot_joint, ex_lo, ex_hi, steps_per_s;
} model_readings_row;

/* Rows of every reading whose main/runs.tsv exists under root (rows[4]). */
cs_status model_readings_compute(const char *root, model_readings_row *rows, size_t *n);
/* The frozen table at path against rows computed afresh: the same readings in
 * the same order and every data cell equal bit for bit (NaN equal to NaN);
 * CS_EINPUT names the file, line and column of the first difference. */
cs_status model_readings_check(const char *path, const model_readings_row *rows, size_t n);
/* The table, with provenance, atomically. */
cs_status model_readings_write(const char *path, const char *root, const model_readings_row *rows, size_t n,
                               int argc, char **argv);

#endif
