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

/* The preregistration commit pinned in audit/gates_prereg.sha256 (its
 * abbreviation into out, when pinned) and where it stands in this history:
 * an ancestor of HEAD, present but not an ancestor (a rewritten or grafted
 * history), absent (a shallow clone), no .git, or not pinned. git replace
 * refs are not followed while GIT_NO_REPLACE_OBJECTS is set (verify sets it). */
enum { PREREG_ANCESTOR = 0, PREREG_NOT_ANCESTOR, PREREG_ABSENT, PREREG_NO_GIT, PREREG_UNPINNED };
int audit_prereg_state(char *out, size_t n);
/* The preregistration commit (abbreviated), 0 when it is an ancestor of HEAD. */
int audit_prereg_commit(char *out, size_t n);

/* The last non-empty line cmd prints, into out; 0 when there is one and cmd exited 0. */
int audit_run_line(const char *cmd, char *out, size_t n);
#endif
