/* figcheck: what a figure shows, checked apart from how it is rendered
 * (design.md §9 "Figures"). Every figure script is also run under gnuplot's
 * `set table`, which writes the data of every plot instead of drawing it; the
 * SHA-256 of that table (comment and blank lines left out) is pinned per
 * figure in figures/plotted.sha256 and compared bit for bit on any machine.
 * The raster (PNG) depends besides on the renderer: gnuplot, cairo, pango,
 * freetype, fontconfig, libpng and zlib, and the font file the scripts name
 * ("DejaVu Sans", Debian fonts-dejavu-core). Their versions, the font file's
 * hash and fontconfig's match for it are pinned in figures/renderer.tsv; the
 * raster is compared only where they are the same, and a machine where they
 * differ is told so by name, never called inconsistent. Limits: the table
 * holds what gnuplot plots at its own precision (%g, six digits); colours,
 * labels and layout are in the raster only. */
#ifndef FIGCHECK_H
#define FIGCHECK_H
#include "checklist.h"
#include "claims.h"
#include "cs.h"
#include <stddef.h>

/* The font every figure script names (set in each `font "..."`). */
#define FIGCHECK_FONT "DejaVu Sans"

/* The renderer here, as "key\tvalue\n" lines (see above). */
cs_status figcheck_renderer(char *buf, size_t n);
/* Compare the renderer text `now` with the pinned file: *same = 1 when every
 * line agrees; else diff names each key that differs ("key: pinned A, here B").
 * A missing pinned file is *same = 0 with that said in diff. */
cs_status figcheck_renderer_compare(const char *pinned_path, const char *now, int *same, char *diff, size_t n);
/* The SHA-256 of a `set table` output without its comment and blank lines. */
cs_status figcheck_table_sha(const char *tabfile, char hex[65]);
/* The pinned hash of figure stem from a plotted.sha256 file ("<hex>  <stem>"
 * lines): *found = 0 when the file has no line for it. */
cs_status figcheck_pinned_sha(const char *list, const char *stem, char hex[65], int *found);
/* The shell command that writes script's plotted data into tabfile (drawing
 * nothing wanted: the terminal output goes into scratch). */
void figcheck_table_cmd(const char *script, const char *scratch, const char *tabfile, const char *log, char *cmd,
                        size_t n);
/* Write the pinned files atomically: the renderer text, and one line per
 * figure from stems[i], hexes[i] (nfig entries). */
cs_status figcheck_write(const char *renderer_path, const char *renderer, const char *plotted_path,
                         const char *const *stems, const char (*hexes)[65], size_t nfig);
/* Redraw every figure into build/figures.<pid>/ and compare it (install = 0:
 * the data it plots with figures/plotted.sha256, the PNG with the committed
 * one under the pinned renderer), or install the redraws into figures/ and
 * write both pinned files (install = 1, only when every script succeeded).
 * c (may be NULL) names the claims a figure feeds. */
void figcheck_verify(checklist *cl, int install, const claims *c);
/* Start every figure's redraw and table in the background (two gnuplot at a
 * time); the next figcheck_verify waits for them and compares. */
void figcheck_launch(void);
/* Wait for the launched redraws (a verify that stops early). */
void figcheck_wait(void);
#endif
