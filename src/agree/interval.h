/* interval: the 95 % interval of every measured claim, from the frozen
 * replicates it rests on (design.md §6.1). audit/intervals.tsv (pinned)
 * states, per computing function, the independent replicate unit (seed,
 * stand, spacing, patch), the method and the replicates read, and the
 * bootstrap plan (seed, resamples, level) in its header; the code checks the
 * statement against what it computes. Methods:
 *   bootstrap  percentile bootstrap over the units (boot_percentile) of the
 *              claim's own statistic, recomputed from the units with the
 *              library code the claim uses; the statistic of the units as
 *              frozen must equal the claim's value bit for bit;
 *   range      a number resting on one unit (one stand, one patch): the
 *              2.5-97.5 % quantiles over frozen replicate units of the same
 *              family (boot_range); when the claim's own unit is among them,
 *              its row must equal the claim's value bit for bit;
 *   none       no replicate unit frozen for it: the interval is absent, with
 *              the reason, and counted as such.
 * Extension claims (a reading added after the first verdict) get theirs
 * the same way. Intervals are in the claim's display units (as claim_result.value). */
#ifndef INTERVAL_H
#define INTERVAL_H
#include "boot.h"
#include "claims.h"
#include "cs.h"

typedef struct claim_interval {
    int has;              /* 1: lo, hi computed */
    char unit[16], method[16];
    size_t n;             /* replicate units */
    double lo, hi;
    char text[128];       /* "[lo, hi]" in the claim's format, or "none" */
    char from[600];       /* the replicates read */
    char why[700];        /* has = 0: why there is none */
} claim_interval;

typedef struct {
    char function[64], unit[16], method[16], replicates[200];
    int line;
} interval_spec;

typedef struct { interval_spec *s; size_t n; boot_plan plan; char path[256]; } interval_table;

/* Load the statement table (seed, resamples and level from its header). */
cs_status interval_table_load(const char *path, interval_table *t);
void interval_table_free(interval_table *t);
const interval_spec *interval_table_find(const interval_table *t, const char *function);

/* The interval of one evaluated claim. Non-measured rows and rows that were
 * not computed get has = 0. CS_EINVARIANT when the replicates do not give
 * the claim's value or the table's statement differs from the code's; other
 * errors name file, line and field. */
cs_status interval_eval(const interval_table *t, const claim_row *row, const claim_result *res, claim_interval *out);

/* ---- used by the extractors (interval_src.c) ---- */
/* The statistic of a claim over units (rows) of m columns. */
typedef enum {
    IV_MEDIAN,
    IV_MIN,
    IV_MAX,
    IV_MEAN,
    IV_REL,
    IV_RATIO,
    IV_WILCOXON,
    IV_CALLBACK,
    IV_QUANTILE,
    IV_ZERO_PCT
} iv_kind;
typedef struct {
    iv_kind kind;
    size_t a,
        b; /* columns: MEDIAN..MEAN of a; REL 100 (med b - med a) / med b; RATIO med a / med b; WILCOXON p(b vs a) */
    boot_stat fn;     /* IV_CALLBACK: the statistic itself, ctx its data */
    const void *ctx;
    double q;         /* IV_QUANTILE: the level (stats_quantile of a); IV_ZERO_PCT: 100 x the share of a == 0 */
} iv_stat;
cs_status iv_stat_eval(const double *x, size_t n, size_t m, const void *ctx, double *out);

/* What an extractor hands back: units (bootstrap) or single-unit values (range). */
typedef struct {
    const char *unit, *method; /* "seed"/"stand"/"spacing"/"patch"; "bootstrap"/"range"/"none" */
    double *x;                 /* bootstrap: n x m; range: n values */
    size_t n, m;
    iv_stat stat;
    int own;                   /* range: index of the claim's own unit in x, -1 when not among them */
    int has_own_exact;         /* bootstrap: own_exact is the statistic of the frozen units in the claim's own
                                * summation order (stat sums per-unit partial sums: the same sums in another
                                * order); it must be the claim's value bit for bit, stat within 1e-12 of it */
    double own_exact;
    char from[600], why[700];
    void (*cleanup)(void *);   /* frees stat.ctx when set */
} iv_data;
typedef cs_status (*iv_extract)(const claim_row *row, const claim_result *res, const interval_spec *spec, iv_data *d);
/* The extractor for a computing function, or NULL (method none). */
iv_extract interval_extractor(const char *function);

#endif
