/* unstated: the choices the reference paper leaves unstated, and the values
 * the sensitivity runs try for each (design.md §7 E0 "sensitivity"). One
 * choice is changed at a time, everything else pinned: two values either
 * side of ours (two either side where a unit is cheap: the figure and field
 * choices; one either side, the wider pair, where a unit reruns every teacher
 * experiment). The experiments map a choice onto the parameter it sets
 * (exp_common.h, exp_variant); the claims read the same list to build the
 * sensitivity table, so both stages agree on names, values and scope.
 * A choice's scope says which experiment tables it can change; every other
 * table of a variant is the centre run's (identical by construction). */
#ifndef UNSTATED_H
#define UNSTATED_H
#include <stddef.h>

typedef enum {
    UNSTATED_ALL = 0,   /* crown draws and the growth rule: every table */
    UNSTATED_FIGURE,    /* the hard-core figure stands: E1 figure stand, E8 */
    UNSTATED_FIELD      /* the E5/E6 field stands, and E2 at beta_field */
} unstated_scope;

#define UNSTATED_MAXVALUES 4

typedef struct {
    const char *name;   /* e.g. "crown_R" (a directory-safe token) */
    const char *what;   /* what it sets, with its unit */
    double ours;        /* the design's value */
    int nvalues;        /* 2 (one either side) or 4 (two either side) */
    double values[UNSTATED_MAXVALUES]; /* ascending: half below ours, half above (the die-back readings: all above) */
    unstated_scope scope;
    int categorical;    /* 1: the values name rules, not points on a scale (no value lies between two) */
} unstated_choice;

const unstated_choice *unstated_list(size_t *n);
/* NULL when no choice has that name. */
const unstated_choice *unstated_find(const char *name);
/* The folder of a variant under the sensitivity root: "<name>_<value %g>";
 * the centre run (ours at the same reduced stand counts) is UNSTATED_CENTRE. */
#define UNSTATED_CENTRE "centre"
void unstated_dirname(const unstated_choice *c, double value, char *buf, size_t n);
/* 1 when a variant of choice c can change the table at relpath (relative to a
 * run folder, e.g. "field/heldout.tsv"); 0: the table is the centre's. */
int unstated_touches(const unstated_choice *c, const char *relpath);

#endif
