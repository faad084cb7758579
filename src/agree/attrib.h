/* attrib: is a difference from the reference paper explained? (design.md §9
 * "Agreement"). For each measured number beyond 10 % of the paper's value:
 * attributed when a run reading (frozen/readings/summary.tsv) lands within
 * 10 % of the paper's value, or an unstated choice's sensitivity values
 * (frozen/sensitivity/summary.tsv) land within 10 % of it or bracket it
 * (the paper's value lies between two of the centre run and the choice's
 * values; not for a categorical choice, the die-back rules); unexplained otherwise, and untested when no reading or
 * choice was measured for it. Reads the frozen summaries as they are; that they equal their run tables is checked where
 * the paper files are generated (audit_paper.c) and by their claim tests. */
#ifndef ATTRIB_H
#define ATTRIB_H
#include "claims.h"
#include "cs.h"
#include <stddef.h>

typedef enum { ATTRIB_NA = 0, ATTRIB_WITHIN, ATTRIB_EXPLAINED, ATTRIB_UNEXPLAINED, ATTRIB_UNTESTED } attrib_kind;

/* sens: 0 a run reading (the whole shift), 1 a value x of an unstated
 * choice of the simulation (a fraction of the shift from the centre run), 2 a
 * training choice of the generator (a fraction of the shift from ours) */
typedef struct { char quantity[64], unit[40]; double x, value; int sens; } attrib_value;
struct claim_interval; /* interval.h */

typedef struct {
    attrib_value *v;
    size_t n;
    int have_readings, have_sens, have_gensens;
    /* every claim, its result and interval (attrib_bind): what "reached" must keep in agreement */
    const claims *c;
    const claim_result *res;
    const struct claim_interval *ci;
} attrib_data;
typedef struct { attrib_kind kind; char by[240]; } attrib_result;

/* Load both summaries (either may be absent: then it contributes nothing). */
cs_status attrib_load(const char *readings_summary, const char *sens_summary, attrib_data *d);
void attrib_free(attrib_data *d);
/* The verdict of one claim (ATTRIB_NA: not a measured number with a reference). */
void attrib_judge(const attrib_data *d, const claim_row *row, const claim_result *res, attrib_result *out);
/* Half a unit in the last digit a printed reference value shows (0.00049:
 * 5e-6): the paper's value is known to that precision only. */
double attrib_half_unit(const char *ref);
/* Bind every claim's result and interval to d (the arrays outlive d's use):
 * attrib_reached then keeps the rest of a claim's experiment in agreement.
 * The generator's training choices join the alternatives here: a computed
 * claim whose source is a choice's unit set (<root>/generator-sensitivity/
 * <choice>/<rest>) and whose params name (of=) a claim computed by the same
 * function on <root>/paper-reading/<rest> is that claim's value under the
 * choice (design.md §8.2). */
void attrib_bind(attrib_data *d, const claims *c, const claim_result *res, const struct claim_interval *ci);
/* Against our interval [lo, hi] (design.md §6.1): does one reading or one
 * value of an unstated choice move our interval onto the paper's value p,
 * while every other number of the same experiment that agrees today stays
 * in agreement? An alternative moves each number by its own shift s (its
 * value there minus ours, or minus the centre run's for a choice): a run
 * reading, or a categorical choice (the die-back rules), by the whole s; a
 * numeric choice by a fraction t of s, t in [0, 1], the same t for every
 * number of the experiment (the choice set between ours and the value run,
 * read linearly). Reached when some t puts p inside [lo, hi] + t s, keeps
 * each other agreeing number's paper value inside its own interval moved by
 * t times its shift, and moves no other number further from its paper value
 * than it is today (numbers the alternative did not measure, or could not
 * compute, are not constrained). 1 when reached, `by` naming each alternative that reaches it
 * ("reading R" or "choice x"); 0 otherwise, `by` naming what reaches it only
 * by moving another number out (*tested = 0 when nothing was measured for
 * the claim). Without attrib_bind nothing else is constrained. */
int attrib_reached(const attrib_data *d, const claim_row *row, const claim_result *res, double lo, double hi,
                   char *by, size_t n, int *tested);
typedef struct { size_t measured, in10, in25, attributed, unexplained, untested; } attrib_counts;
void attrib_count(const attrib_data *d, const claims *c, const claim_result *res, attrib_counts *k);
/* The one summary line (plain text; tex != 0: LaTeX percent signs). */
void attrib_line(const attrib_counts *k, int tex, char *buf, size_t n);
#endif
