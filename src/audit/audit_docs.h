/* audit_docs: the documentation pages against frozen/ (design.md §9): README.md
 * and every *.md under audit/, frozen/, src/, tests/, paper/, figures/ and
 * gates/ (subfolders too; paper/CHANGELOG.md, which records history, aside).
 * A page states a measured number only through a generated region (the
 * markers of docs_render.h), equal to a fresh generation. Outside them a
 * decimal that rounds a measured value or the reference paper's (the rule of
 * the paper text, audit_paper.c) fails naming page and line; so do a comment
 * asking for an exemption and a relative link to a missing file. */
#ifndef AUDIT_DOCS_H
#define AUDIT_DOCS_H
#include "checklist.h"
#include "claims.h"
#include "paths.h"

/* The pages the audit reads, sorted (README.md first). */
cs_status docs_pages(paths_list *out);
/* One page: generated regions equal a fresh generation, no measured number
 * typed outside them, no exemption comment, every relative link resolves.
 * Adds FAIL items (page:line, and the claim) to cl; returns how many. */
size_t docs_check_page(const char *path, const claims *c, const claim_result *res, checklist *cl);
/* Every page: FAIL items, or one PASS item summing them up. */
void audit_docs(const claims *c, const claim_result *res, checklist *cl);
/* Rewrite the generated regions of every page whose rendering differs
 * (atomically); *changed counts the pages written. */
cs_status docs_refresh(const claims *c, const claim_result *res, size_t *changed);

#endif
