/* audit_render: the write-up rendered by TeX with every generated value
 * hidden, its text read back (design.md §9). */
#ifndef AUDIT_RENDER_H
#define AUDIT_RENDER_H
#include "checklist.h"
#include "claims.h"

/* Render paper/main.tex in build/render/paper/ with the hidden generated
 * files; a PASS item, or a FAIL item per digit or verdict word the rendered
 * text holds (page and line named), or one when it does not render. */
void audit_render(const claims *c, const claim_result *res, checklist *cl);
/* The scan alone, on pdftotext output (pages split by form feeds); what names
 * the source in the items. Returns the number of FAIL items added. */
size_t render_scan_text(const char *text, const char *what, checklist *cl);
/* The Debian packages of the render (pdflatex, the packages the write-up
 * loads, pdftotext); the Makefile's DEB_PKGS holds them too. */
#define RENDER_DEBS "texlive-latex-base texlive-latex-recommended poppler-utils"
/* pdflatex and pdftotext on PATH. */
int render_tools_present(void);

#endif
