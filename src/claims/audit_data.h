/* audit_data: aggregates vs their per-run tables, lineage of per-run tables
 * to claims, and the git ledger of pinned files (design.md §9). */
#ifndef AUDIT_DATA_H
#define AUDIT_DATA_H
#include "checklist.h"
#include "claims.h"
#include "paths.h"
#include <stdio.h>

typedef struct {
    char aggregate[256], value[64], reduce[16], parts[256], part_value[64], filter[256];
    int line;
} aggr_spec;

/* Parse audit/aggregates.tsv (format in audit_data.c); CS_EINPUT naming
 * file, line and field on a malformed row. Caller frees *out. */
cs_status aggr_load(const char *path, aggr_spec **out, size_t *n);
/* Every aggregate cell equals the reduction of its per-run table (bit for
 * bit); FAIL items name the aggregate's line, the per-run file and the claims. */
void audit_aggregates(const claims *c, checklist *cl);
/* Comma-joined claims a frozen file feeds (directly or via an aggregate). */
void audit_feeds(const claims *c, const char *path, char *buf, size_t n);
/* Print which pinned files changed after the commit that added the gates. */
void audit_ledger(FILE *o);

#endif
