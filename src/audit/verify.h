/* verify: the reviewer's job (design.md §9). Audit, recompute every claim from
 * frozen/ and compare with paper/numbers.tex, judge every gate, redraw every
 * figure with gnuplot, print a claim table and "N passed, N failed". */
#ifndef VERIFY_H
#define VERIFY_H
#include "cs.h"
#include "audit.h"

/* strict: a failing preregistered gate (a finding) also fails verify. */
/* prereg: the gates' sha256 the reviewer brings (NULL: self-attested). */
/* spot_seed: the spot check's pick (0: from the clock); no_figures also skips the spot check. */
typedef struct { int quiet; int no_figures; int strict; const char *prereg; unsigned long spot_seed; } verify_opts;

/* design.md §9: CS_OK when every number, verdict, table, figure and
 * sentence follows from frozen/ and the pinned code (a failing gate is a
 * finding, "not reproduced"); CS_EFAIL on any inconsistency, or with strict
 * on any failing gate; another status on a broken installation. */
cs_status verify_run(const verify_opts *o);
/* build/ is writable (the fresh generation and the redraws go there):
 * CS_EIO naming it otherwise, an environment error. */
cs_status verify_preflight(void);
/* CS_EINPUT (each failing claim printed to stderr, prefixed "crownshy who")
 * when a claim cannot be computed from an input the user supplied
 * (FIELD_TABLE, CHM): a bad input, not an inconsistency. */
cs_status verify_external_inputs(const claims *c, const claim_result *res, const char *who);
/* Evaluate every claim (res has c->n entries, caller frees). */
cs_status verify_eval_all(const claims *c, claim_result **res);
/* Load the registry (PATHS_CLAIMS) and evaluate every claim; on success the
 * caller frees *res and claims_free(c). */
cs_status verify_load_eval(claims *c, claim_result **res);
/* Is numbers.tex consistent with the recomputed claim (value and stated gate
 * verdict)? An honest gate failure is consistent. PENDING when not computable. */
verdict verify_consistent(const claim_row *row, const claim_result *res, const numbers_tex *nt, char *msg, size_t n);
/* verify_consistent, and FAIL when the claim's gate fails. */
verdict verify_claim(const claim_row *row, const claim_result *res, const numbers_tex *nt, char *msg, size_t n);
/* Print value, frozen file, function, gate and test of one macro. */
cs_status verify_trace(const char *macro);

#endif
