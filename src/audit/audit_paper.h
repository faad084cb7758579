/* audit_paper: the write-up against frozen/ (design.md §9): generated
 * files equal a fresh generation; the hand-written .tex files (subfolders
 * too) use claim macros only. */
#ifndef AUDIT_PAPER_H
#define AUDIT_PAPER_H
#include "checklist.h"
#include "claims.h"
#include "paths.h"

/* Is path one of the generated paper files (numbers, constants, comparison, readings)? */
int paper_is_generated(const char *path);
/* The i-th generated paper file (NULL past the last). */
const char *paper_generated(size_t i);
/* A design constant the text prints through its macro (audit/design_numbers.tsv). */
typedef struct { char macro[64], value[32]; int line; } design_const;
/* Every row of audit/design_numbers.tsv checked at its source (a failing row
 * is a FAIL item of cl, left out); *out malloc'd; returns how many hold. */
size_t audit_design_consts(checklist *cl, design_const **out);
/* The design constant named name among v[0..n), NULL when none. */
const design_const *audit_design_find(const design_const *v, size_t n, const char *name);
/* paper/constants.tex from audit/design_numbers.tsv: one macro per design
 * constant the text prints (hide: the audit's render, each printing the
 * hidden word). Errors name the file, line and field. */
cs_status audit_write_constants(const char *path, int hide);
/* Write numbers.tex, comparison.tex, readings.tex (when
 * frozen/readings/summary.tsv exists; *readings bit 1) and sensitivity.tex
 * (when frozen/sensitivity/summary.tsv exists; bit 2) into dir, each summary
 * checked against its run tables first. Errors name file and field. */
cs_status paper_generate(const claims *c, const claim_result *res, const char *dir, int *readings);
/* Each generated file equals a fresh generation (only numbers.tex when
 * only_numbers), naming the first differing line and its claim. */
void audit_generated(const claims *c, const claim_result *res, checklist *cl, int only_numbers);
/* The claim a line of a generated file is about, into out (empty when none):
 * the first word of the line that is a claim's whole name, or a claim's name
 * followed by "Gate" (numbers.tex's verdict macro). */
void paper_line_claim(const claims *c, const char *line, char *out, size_t n);
/* Every non-generated .tex under paper/: claim macros registered, none
 * (re)defined, no measured number typed in any rounding, no exemption comment. */
void audit_paper_text(const claims *c, const claim_result *res, checklist *cl);
/* One hand-written file: FAIL items for unregistered, defined or hand-typed
 * claims (vals/who: the nv measured values and their macros) and exemption
 * comments; returns how many, adds claim-macro uses to *used. */
size_t paper_scan_file(const char *path, const claims *c, const double *vals, const char *const *who, size_t nv,
                       checklist *cl, size_t *used);

#endif
