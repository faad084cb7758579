/* audit_grids: the design grids of the frozen tables (design.md §9): each
 * table of audit/grids.tsv holds exactly the rows its design names, block by
 * block (the format is in audit_grids.c). */
#ifndef AUDIT_GRIDS_H
#define AUDIT_GRIDS_H
#include "checklist.h"
#include "claims.h"

/* Every table of audit/grids.tsv has exactly the rows of its design grid. */
void audit_grids(const claims *c, checklist *cl);

#endif
