/* figdata: display data for the top-down canopy figures (design.md §12): each
 * crown's outline at 4 points per sector (crown_radius_at) plus the closing
 * point, FIGDATA_ROWS rows per tree, trees in ascending height so that taller
 * crowns are drawn last (on top, as seen from above). Millimetre precision:
 * display data, not results. */
#ifndef FIGDATA_H
#define FIGDATA_H
#include "cs.h"
#include "crown.h"
#include "tsv.h"
#include <stddef.h>

#define FIGDATA_PER_SECTOR 4
#define FIGDATA_ROWS (CROWN_NSEC * FIGDATA_PER_SECTOR + 1)

/* Writes the header row "tree x_m y_m h_m[ flag]" and the polygons of n crowns
 * (r: n x CROWN_NSEC) at stems (x, y) with heights h; flag (may be NULL) adds
 * a 0/1 column per tree (e.g. "overlaps a neighbour"), named flag_name. */
cs_status figdata_write_polygons(tsv_writer *w, size_t n, const double *x, const double *y, const double *h,
                                 const double *r, const int *flag, const char *flag_name);

#endif
