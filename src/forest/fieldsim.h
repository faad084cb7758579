/* fieldsim: the simulated side of the field comparisons (design.md §7 E5, E6;
 * reference paper §5.3, §5.4). A stand is grown by the teacher
 * (exp_field_grow_append, in the experiments); for each interior tree (>= 2 d from the edge) the canonical estimator
 * gives the four cardinal gaps and the crown elongation. Trees are kept individually (fs_trees) so every summary in a
 * frozen table can be recomputed from the per-tree table beside it (X.tsv and X_trees.tsv) with the same code. A group
 * = (arm, level): arm coupled/uncoupled twin, level = the knob of the experiment (beta for the calibration, jitter a or
 * hard-core c for E6). */
#ifndef FIELDSIM_H
#define FIELDSIM_H
#include "cs.h"
#include "field.h"
#include "tsv.h"
#include <stddef.h>

typedef struct {
    size_t n, cap;
    int *coupled;
    double *level;
    unsigned *stand, *tree;
    double (*gap)[4];   /* E, N, W, S, m */
    double *elong;      /* all-axis elongation (design.md §5) */
    double *elong_card; /* cardinal elongation (the readings, design.md §7 E0) */
} fs_trees;

void fs_trees_init(fs_trees *t);
void fs_trees_free(fs_trees *t);

/* Append one tree: tags (coupled, level, stand, tree), cardinal gaps
 * (E, N, W, S, m) and crown elongation, all-axis and cardinal (both readings
 * from the same crowns). */
cs_status fs_trees_push(fs_trees *t, int coupled, double level, unsigned stand, unsigned tree,
                        const double gap[4], double elong, double elong_card);

typedef struct {
    field_summary f;      /* trees, tree-mean median, spread, anisotropy median (+ excluded) */
    double elong_median;  /* median crown elongation (all-axis) over the group's trees */
    double elong_card_median; /* the same, cardinal reading */
    size_t stands;        /* distinct stand indices present */
} fs_summary;

/* Summary of one group; CS_EINPUT when the group has no trees. */
cs_status fs_group(const fs_trees *t, int coupled, double level, fs_summary *out);

/* Per-tree table: columns arm level stand tree gap_e gap_n gap_w gap_s elong. */
#define FS_TREE_COLUMNS "arm\tlevel\tstand\ttree\tgap_e\tgap_n\tgap_w\tgap_s\telong\telong_card"
void fs_trees_write(tsv_writer *w, const fs_trees *t);
cs_status fs_trees_read(const char *path, fs_trees *out);

/* Summary table: one row per group. */
#define FS_SUMMARY_COLUMNS                                                                                             \
    "arm\tlevel\tbeta\tstands\tstands_failed\ttrees\ttree_mean_median\tspread\taniso_median\taniso_trees\taniso_"      \
    "excluded\telong_median\telong_card_median"
void fs_summary_write_row(tsv_writer *w, int coupled, double level, double beta, size_t stands_failed,
                          const fs_summary *s);

/* "dir/X.tsv" -> "dir/X_trees.tsv". */
void fs_trees_path(const char *summary_path, char *out, size_t n);
/* Read a summary table and its per-tree table, and check that every
 * summary row equals the group recomputed from the trees (exactly: same
 * code, same inputs). A tampered or inconsistent pair is CS_EINPUT naming
 * file, line and field. Rows with trees = 0 (unbuildable levels) are not
 * recomputed. On success *sum and *trees are owned by the caller. */
cs_status fs_load_checked(const char *summary_path, tsv **sum, fs_trees *trees);

/* First crossing of y = target along (x, y), x ascending: linear
 * interpolation between the bracketing grid points. When the target is not
 * bracketed, *bracketed = 0 and *xi is the grid end whose y is closest. */
cs_status fs_interp_target(const double *x, const double *y, size_t n, double target, double *xi, int *bracketed);
/* Round x to a multiple of step (step = 1/k for an integer k, e.g. 0.01):
 * round(x k)/k, so the result is the nearest double to the decimal value. */
double fs_round_step(double x, double step);
/* Text of a rank correlation as an exact fraction p/q (q <= 1000), "1", "-1",
 * or "%.3f" when no small denominator fits (ties). */
void fs_fraction_text(double v, char *buf, size_t n);

/* ---- calibrations (read back by the experiments and by the claims) ---- */
/* E5: beta_field from a calibration summary (checked against its trees):
 * the curve (beta, coupled tree_mean_median) interpolated to the field
 * target (gates/field.gate calibration_target_m) and rounded to the grid
 * step (dieback_grid). *line_lo gets the file line of the lower bracketing row. */
typedef struct { double target, interp, value, step; int bracketed, line_lo; size_t points; } fs_calibration;
cs_status fs_beta_field(const char *calibration_path, fs_calibration *out);
/* Jitter amplitude is stated in whole percent of the spacing (the paper's
 * JitterStarPct), so a* is rounded to 0.01. */
#define FS_JITTER_STEP 0.01
/* E6: a* from the jitter calibration table (columns level, aniso_median):
 * interpolated to gates/anisotropy.gate field_median, rounded to 0.01. */
cs_status fs_jitter_star(const char *path, fs_calibration *out);
#endif
