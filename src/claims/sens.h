/* sens: the E0 sensitivity table (design.md §7 E0 "sensitivity"). For each
 * choice the reference paper leaves unstated (src/base/unstated.h) the cheap
 * teacher experiments were run with that choice at two values either side
 * of ours, everything else pinned (crownshy sensitivity-run, one unit per choice
 * and value, into <dir>/<choice>_<value>/), and once with the design's
 * values at the same stand counts (<dir>/centre/). This module computes one
 * row per (quantity, unit) with the registry's own computing function
 * (claims.h) on that unit's tables, beside the paper's value. A table a
 * choice cannot change is read from the centre run (unstated_touches). The
 * claim test recomputes the frozen summary from the frozen unit tables. */
#ifndef SENS_H
#define SENS_H
#include "claims.h"
#include "cs.h"
#include <stddef.h>

typedef struct {
    char quantity[64], choice[32], source[256];
    double x;                      /* the choice's value (the centre row: NaN) */
    double value, paper, rel_diff; /* rel_diff = (value - paper) / |paper| */
} sens_row;

/* Rows: per quantity, the centre row then every (choice, value) in the
 * order of unstated_list. */
size_t sens_count(void);
size_t sens_units_per_quantity(void);
cs_status sens_compute(const claims *c, const char *dir, sens_row *rows);
cs_status sens_write(const char *path, const char *dir, const sens_row *rows, size_t n);
/* Every value, paper value and relative difference of a frozen summary
 * against freshly computed rows, bit for bit; CS_EINPUT naming file, line, field. */
cs_status sens_check(const char *path, const sens_row *rows, size_t n);
/* paper/sensitivity.tex (generated): per quantity the paper's value, the
 * centre run, and per choice the span its values cover. */
cs_status sens_write_tex(const char *path, const sens_row *rows, size_t n);
/* Span of quantity q under choice ch over the centre and its values. 0 when absent. */
int sens_span(const sens_row *rows, size_t n, const char *q, const char *ch, double *lo, double *hi);

#endif
