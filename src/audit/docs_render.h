/* docs_render: a documentation page with its generated regions filled from
 * the claims (design.md §9). A page states a measured number only through a
 * generated region, which `crownshy numbers` fills and verify compares with a
 * fresh generation:
 *   <!--Macro-->value<!--/-->      one claim's numbers.tex text (MacroGate: its gate's
 *                                  verdict; MacroPaper: the reference paper's value)
 *   <!-- findings ... -->          (a line of its own) up to <!-- /findings -->:
 *                                  the gated claims, reproduced or not, per gate file */
#ifndef DOCS_RENDER_H
#define DOCS_RENDER_H
#include "claims.h"
#include "paths.h"

#define DOCS_FIND_BEGIN "<!-- findings"
#define DOCS_FIND_END "<!-- /findings -->"
#define DOCS_MARK_END "<!--/-->"

/* The inline marker at s ("<!--Name-->") of line: its name length and where
 * its value starts and ends; 0 when s is no marker (or lies in a code span). */
int docs_render_marker(const char *line, const char *s, size_t *nl, const char **v, const char **ve);
/* The page with every generated region regenerated, as a malloc'd string in
 * *out. Unknown macro in a marker: CS_EINPUT naming page and line. */
cs_status docs_render(const char *path, const claims *c, const claim_result *res, char **out);

#endif
