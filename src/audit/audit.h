/* audit: the traceability checks (design.md §9): source pins (estimator hash,
 * teacher version and hash, gate hashes), frozen-file hashes, frozen
 * provenance vs pins, registry completeness (every paper macro has a row,
 * every row a test and a function, no orphan function), numbers.tex equal
 * to a fresh generation, and no measured number typed into the paper text.
 * Each check is one item with a verdict and a message naming file and claim. */
#ifndef AUDIT_H
#define AUDIT_H
#include "cs.h"
#include "gate.h"
#include "claims.h"
#include "paths.h"

#include "checklist.h"

/* Run every audit check; `res` are the evaluated claims (same order as c). */
cs_status audit_run(const claims *c, const claim_result *res, checklist *out);
/* Rewrite audit/frozen.sha256 from the files under frozen/ (make freeze). */
cs_status audit_hash_frozen(void);

#endif
