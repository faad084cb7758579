/* field: the field reference (design.md §7 "Field reference data"; reference paper
 * §5.3, §5.4). Two inputs:
 *  - frozen/field/reference.tsv: the published figures the reference paper
 *    states for Markham & Fernandez Otarola 2020 (23 trees, 92 measurements,
 *    medians and bands). Not measured here; one row per quantity.
 *  - the raw per-tree table, only when a user supplies it (FIELD_TABLE=path):
 *    TSV with columns tree, direction, clearance_m; direction is E/N/W/S or
 *    east/north/west/south (any case); every tree has each of the 4
 *    directions exactly once. It is not on this machine (Dryad
 *    doi:10.5061/dryad.34tmpg4hk is unreachable here), so everything that
 *    needs it is PENDING without it.
 * Summaries use the canonical estimator's functions (est_tree_mean,
 * est_anisotropy, est_spread, est_median) for field and simulated trees alike,
 * so both sides of every comparison go through the same instrument. */
#ifndef FIELD_H
#define FIELD_H
#include "cs.h"
#include <stddef.h>

/* A clearance beyond this (metres) is a data error, not a measurement: the
 * loader names file, line and field instead of letting 1e308 overflow later. */
#define FIELD_CLEARANCE_MAX_M 1000.0
#define FIELD_TABLE_ENV "FIELD_TABLE"
#define FIELD_REFERENCE_PATH "frozen/field/reference.tsv"

typedef struct {
    size_t n;          /* trees, in order of first appearance */
    char (*id)[64];    /* tree identifiers as written */
    double (*gap)[4];  /* cardinal clearance, m, order EST_E, EST_N, EST_W, EST_S */
    char path[512];
} field_table;

/* Direction word -> EST_E/N/W/S, or -1. Accepts E N W S east north west south, any case. */
int field_direction(const char *s);
/* Load and validate a raw field table. CS_EINPUT naming file, line and field on:
 * missing column, unknown direction, non-numeric or non-finite clearance,
 * a direction given twice for one tree, a tree missing a direction, no rows. */
cs_status field_table_load(const char *path, field_table *out);
void field_table_free(field_table *ft);
/* The path in $FIELD_TABLE, or NULL when unset or empty. */
const char *field_table_env(void);

typedef struct {
    size_t trees, measurements;
    double tree_mean_median;  /* median over trees of the mean of the 4 cardinal gaps, m */
    double spread;            /* IQR of all cardinal gaps (est_spread), m */
    double aniso_median;      /* median widest/narrowest over trees with all gaps > 0 (NaN if none) */
    size_t aniso_trees, aniso_excluded;
} field_summary;
/* Summary of n trees' cardinal gaps (field or simulated: same code). n >= 1. */
cs_status field_summarize(const double (*gap)[4], size_t n, field_summary *out);

/* Value of `quantity` in a reference table (columns quantity, value, ...);
 * *line (may be NULL) gets its file line. CS_EINPUT naming file/line/field. */
cs_status field_reference_get(const char *path, const char *quantity, double *v, int *line);

#endif
