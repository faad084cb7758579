/* agree: the agreement of each measured claim with the reference paper,
 * judged against our own 95 % interval (design.md §6.1): inside (the
 * paper's value lies in our interval), reached (outside, but a run reading
 * or an unstated choice moves our interval onto it: attrib_reached),
 * unexplained (outside, and nothing measured reaches it), or no interval (no
 * replicate unit frozen for it). Writes the generated paper/intervals.tsv
 * (every interval, %.17g: what the claim tests recompute bit for bit) and
 * paper/summary.tex (the one-page reproduction summary), and prints the same
 * table on a terminal (`crownshy report`). The paper's value is known to its
 * printed precision: our interval is widened by half a unit in the paper's
 * last printed digit before it is compared (0.00049 printed for 2/4096 is
 * inside a point interval at 2/4096). */
#ifndef AGREE_H
#define AGREE_H
#include "attrib.h"
#include "claims.h"
#include "interval.h"
#include <stdio.h>

typedef enum { AGREE_NA = 0, AGREE_INSIDE, AGREE_REACHED, AGREE_UNEXPLAINED, AGREE_NOINTERVAL } agree_kind;
typedef struct { agree_kind kind; char by[240]; } agree_result;
typedef struct { size_t compared, inside, reached, unexplained, nointerval, measured, with_interval; } agree_counts;

/* Every claim's interval (has = 0 for rows without one). On an error of a
 * row the status is returned and *bad names the row; the array is complete. */
cs_status agree_intervals(const interval_table *t, const claims *c, const claim_result *res, claim_interval **out,
                          size_t *bad);
/* agree_intervals over PATHS_INTERVALS, computed once per (c, res) and kept
 * for the process (verify, numbers and the audit read the same results):
 * the array is owned here. */
cs_status agree_intervals_cached(const claims *c, const claim_result *res, const claim_interval **out);
/* The agreement of one claim (AGREE_NA: not a measured number with a reference). */
void agree_judge(const attrib_data *d, const claim_row *row, const claim_result *res, const claim_interval *ci,
                 agree_result *out);
const char *agree_name(agree_kind k);
void agree_count(const attrib_data *d, const claims *c, const claim_result *res, const claim_interval *ci,
                 agree_counts *k);
/* The summary line (plain text; tex != 0: LaTeX). */
void agree_line(const agree_counts *k, int tex, char *buf, size_t n);

/* paper/intervals.tsv: macro unit method n lo hi text (generated, atomic). */
cs_status agree_write_intervals(const char *path, const claims *c, const claim_interval *ci);
/* The claim test's check: ci against the row of path for the macro, bit for
 * bit. VERDICT_FAIL with msg naming the macro, file and line on a difference
 * or a missing row; VERDICT_PASS otherwise. */
verdict agree_check_interval(const char *path, const claim_row *row, const claim_interval *ci, char *msg, size_t n);

/* paper/comparison.tex: every claim, the reference paper's value, ours, our
 * interval, the gate verdict, whether the values agree, beyond 10 % what
 * reaches the paper's value (attrib_judge), and the agreement class. */
cs_status agree_write_comparison(const char *path, const claims *c, const claim_result *res, const attrib_data *at,
                                 const claim_interval *ci);
/* paper/summary.tex: the reproduction summary (generated, atomic). */
cs_status agree_write_summary(const char *path, const claims *c, const claim_result *res, const claim_interval *ci,
                              const attrib_data *d);
/* The same table on f (colour = 1: ANSI colours for the verdicts). */
void agree_print_report(FILE *f, const claims *c, const claim_result *res, const claim_interval *ci,
                        const attrib_data *d, int colour);

#endif
