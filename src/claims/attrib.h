/* attrib: is a difference from the reference paper explained? (design.md §9
 * "Agreement"). For each measured number beyond 10 % of the paper's value:
 * attributed when a run reading (frozen/readings/summary.tsv) lands within
 * 10 % of the paper's value, or an unstated choice's sensitivity values
 * (frozen/sensitivity/summary.tsv) land within 10 % of it or bracket it
 * (the paper's value lies between two of the centre run and the choice's
 * values; not for a categorical choice, the die-back rules); unexplained otherwise, and untested when no reading or choice
 * was measured for it. Reads the frozen summaries as they are; that they
 * equal their run tables is checked where the paper files are generated
 * (audit_paper.c) and by their claim tests. */
#ifndef ATTRIB_H
#define ATTRIB_H
#include "claims.h"
#include "cs.h"
#include <stddef.h>

typedef enum { ATTRIB_NA = 0, ATTRIB_WITHIN, ATTRIB_EXPLAINED, ATTRIB_UNEXPLAINED, ATTRIB_UNTESTED } attrib_kind;

typedef struct { char quantity[64], unit[40]; double x, value; int sens; } attrib_value;
typedef struct { attrib_value *v; size_t n; int have_readings, have_sens; } attrib_data;
typedef struct { attrib_kind kind; char by[240]; } attrib_result;

/* Load both summaries (either may be absent: then it contributes nothing). */
cs_status attrib_load(const char *readings_summary, const char *sens_summary, attrib_data *d);
void attrib_free(attrib_data *d);
/* The verdict of one claim (ATTRIB_NA: not a measured number with a reference). */
void attrib_judge(const attrib_data *d, const claim_row *row, const claim_result *res, attrib_result *out);
/* Against our interval [lo, hi] (design.md §6.1): does a reading or an
 * unstated choice move our interval onto the paper's value p? A run reading
 * of value x does when [lo, hi] + (x - v) holds p (v: our value); a choice's
 * sensitivity value x does when [lo, hi] + (x - c) holds p (c: the centre
 * unit, v without one), or, for a non-categorical choice, when p lies
 * between v and v + (x - c). 1 when reached, `by` naming what reaches it
 * ("reading R", or the choice); 0 otherwise (*tested = 0 when nothing was
 * measured for the claim). */
int attrib_reached(const attrib_data *d, const claim_row *row, const claim_result *res, double lo, double hi,
                   char *by, size_t n, int *tested);
typedef struct { size_t measured, in10, in25, attributed, unexplained, untested; } attrib_counts;
void attrib_count(const attrib_data *d, const claims *c, const claim_result *res, attrib_counts *k);
/* The one summary line (plain text; tex != 0: LaTeX percent signs). */
void attrib_line(const attrib_counts *k, int tex, char *buf, size_t n);
#endif
