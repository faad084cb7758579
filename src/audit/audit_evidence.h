/* audit_evidence: what a number rests on, checked in tier 1 (design.md §9):
 * the files a table's provenance names (with their hashes), the
 * weights seals, every W1 from its samples, the gates against their
 * preregistered content and the superseded pins against the real history of
 * their files (each table's rows against its design grid: audit_grids.h). */
#ifndef AUDIT_EVIDENCE_H
#define AUDIT_EVIDENCE_H
#include "checklist.h"
#include "claims.h"
#include "paths.h"

/* Every "# key: NAME sha256 HEX" provenance line of a frozen table names a
 * file beside it that exists with that hash; every frozen weights file opens
 * (its checksum seal holds); every W1 of the E3/E4 run tables and baselines
 * equals the W1 recomputed from its samples. */
void audit_evidence(const claims *c, checklist *cl);
/* The gates equal their content at the commit that added them (.git present)
 * and the pinned copy of their hashes (audit/gates_prereg.sha256). */
void audit_gates_prereg(const claims *c, checklist *cl);
/* Every superseded pin is a real past value of its file (from git when present). */
void audit_superseded_real(checklist *cl);
/* 1 when the frozen table at path was made by a superseded reading (its
 * provenance names a pin of audit/pins_superseded.tsv instead of the current one). */
int audit_table_superseded(const char *path);
/* The gates against hashes from outside this tree: CITATION.cff must publish
 * their sha256 (an identifier "value: sha256:<hex>"), and brought (the
 * reviewer's PREREG, may be NULL) must equal it. line: the summary's
 * "preregistration: ..." (checked against the brought hash, or self-attested). */
void audit_prereg_anchor(checklist *cl, const char *brought, char *line, size_t n);

#endif
