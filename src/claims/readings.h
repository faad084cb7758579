/* readings: the E0 readings table (design.md §7 E0). Where the
 * reference paper's text allows more than one reading, the cheap experiments
 * are run under each reading (the same experiment units, switched by
 * --teacher and --layout, never copied files) into <dir>/<run>/..., and this
 * module computes one row per (quantity, reading) with the registry's own
 * computing function (claims.h) on that run's tables, beside the paper's
 * value (audit/claims.tsv reference column).
 *
 * Runs (directories under <dir>), named by die-back rule and footprint side:
 * one-sided-60m, mutual-60m, one-sided-36m, mutual-36m, arc-36m (one-sided:
 * teacher-1; mutual: teacher-2; arc: teacher-2 with the contact arc dying
 * back too, -arc; 60m: layout 5m-on-60m, 36m: layout 4m-on-36m; the die-back
 * by beta of the target length cannot be calibrated on the field grid, so it
 * runs as a sensitivity unit, sens.h).
 * Readings (rows): a run plus two choices that need no rerun,
 * read from the same tables: the elongation (cardinal, or all
 * axes, paper §5.3 "the ratio of the longest to shortest crown axis") and
 * the stand the Mech* numbers are measured on (the lattice ablation,
 * the lattice, or the figure stand, paper: "measured on the stand shown").
 * A reading is named by its run, led by "cardinal-" for the cardinal
 * elongation and the lattice (no name is the start of another, so "reading
 * NAME" in an attribution names one reading). The claim test recomputes the
 * frozen summary from the frozen run tables. */
#ifndef READINGS_H
#define READINGS_H
#include "claims.h"
#include "cs.h"
#include <stddef.h>

typedef struct {
    const char *name;      /* e.g. "mutual-36m" */
    const char *run;       /* directory under <dir> */
    int elong_all_axes;    /* 1: all-axis elongation; 0: cardinal */
    int figure_stand;      /* 1: Mech* on mechanism/figure_stats.tsv; 0: mechanism/ablation.tsv */
    const char *what;
} readings_def;

typedef struct {
    char quantity[64], reading[32], source[512];
    double value, paper, rel_diff; /* rel_diff = (value - paper) / |paper| (NaN when paper is 0 or absent) */
} readings_row;

/* The readings and the quantities, in table order. */
const readings_def *readings_list(size_t *n);

/* Compute every row from <dir>/<run>/... with the claims of registry c.
 * rows must hold readings_count() entries. */
size_t readings_count(void);
cs_status readings_compute(const claims *c, const char *dir, readings_row *rows);
/* Write the summary table (provenance block from prov is the caller's: the
 * header lines given are written first). */
cs_status readings_write(const char *path, const char *dir, const readings_row *rows, size_t n);
/* Check a frozen summary against freshly computed rows: every value, paper
 * value and relative difference bit for bit; CS_EINPUT naming file, line, field. */
cs_status readings_check(const char *path, const readings_row *rows, size_t n);
/* paper/readings.tex (generated; see readings.c). */
cs_status readings_write_tex(const char *path, const readings_row *rows, size_t n);
/* "N of M within 10 % / 25 %" counts over the rows of one reading. */
void readings_within(const readings_row *rows, size_t n, const char *reading, size_t *m, size_t *in10, size_t *in25);

#endif
