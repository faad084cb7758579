/* verify: the reviewer's job (SPEC §9). Audit, recompute every claim from
 * frozen/ and compare with paper/numbers.tex, judge every gate, redraw every
 * figure with gnuplot, print a claim table and "N passed, N failed". */
#ifndef VERIFY_H
#define VERIFY_H
#include "cs.h"
#include "audit.h"

typedef struct { int quiet; int no_figures; } verify_opts;

/* Returns CS_OK when nothing failed, CS_EFAIL when any item failed,
 * another status on a broken installation (registry unreadable). */
cs_status verify_run(const verify_opts *o);
/* Evaluate every claim (res has c->n entries, caller frees). */
cs_status verify_eval_all(const claims *c, claim_result **res);
/* Is numbers.tex consistent with the recomputed claim (value and stated gate
 * verdict)? An honest gate failure is consistent. PENDING when not computable. */
verdict verify_consistent(const claim_row *row, const claim_result *res, const numbers_tex *nt, char *msg, size_t n);
/* verify_consistent, and FAIL when the claim's gate fails. */
verdict verify_claim(const claim_row *row, const claim_result *res, const numbers_tex *nt, char *msg, size_t n);
/* Redraw every figures/ *.gp whose data exist. */
void verify_figures(checklist *cl);
/* Print value, frozen file, function, gate and test of one macro. */
cs_status verify_trace(const char *macro);

#endif
