/* unstated: the sensitivity choices; see unstated.h. Values: the design's
 * value (design.md §2, §3, §4, §7 E5) with alternatives below and above it,
 * wide enough that a reader's other plausible reading falls inside. A choice
 * of scope "all" reruns every cheap teacher experiment (about 30 CPU-s per
 * unit at the sensitivity's stand counts), so it gets the wider pair only;
 * the figure and field choices are cheap and get two either side. */
#include "unstated.h"
#include <stdio.h>
#include <string.h>

static const unstated_choice CHOICES[] = {
    {"crown_R", "crown-radius scale R0 (m): R = R0 exp(s z)", 4.0, 2, {3.0, 5.0}, UNSTATED_ALL, 0},
    {"crown_spread", "crown-radius spread s: R = R0 exp(s z)", 0.15, 2, {0.05, 0.25}, UNSTATED_ALL, 0},
    {"height_sd", "height spread (m): h ~ N(25, sd^2) on [12, 38]", 4.0, 2, {2.0, 6.0}, UNSTATED_ALL, 0},
    {"lobing", "lobing range: a ~ U[0, a_max]", 0.2, 2, {0.10, 0.30}, UNSTATED_ALL, 0},
    {"growth_N", "growth resolution N (step = median R / N)", 48, 2, {24, 96}, UNSTATED_ALL, 0},
    {"start", "start radius, fraction of the target", 0.05, 2, {0.02, 0.10}, UNSTATED_ALL, 0},
    {"fig_hardcore", "hard-core level c of the figure stands (minimum distance c d)", 0.5, 4, {0.3, 0.4, 0.6, 0.7}, UNSTATED_FIGURE, 0},
    {"field_d", "field-stand spacing (m)", 4.0, 4, {3.0, 3.5, 4.5, 5.0}, UNSTATED_FIELD, 0},
    {"field_L", "field-stand footprint (m)", 36.0, 4, {28.0, 32.0, 44.0, 60.0}, UNSTATED_FIELD, 0},
    /* not an unstated number but the die-back readings (design.md §7 E0), run
     * here because a unit tolerates what a reading cannot build: 0 own sector
     * of both crowns in contact (Eq. 3, ours), 1 the contact arc s-1..s+1 too,
     * 2 beta of the target length, 3 one-sided (teacher-1: the advancing crown's
     * sector alone) */
    {"dieback", "die-back reading: 1 = the contact arc s-1..s+1 dies back too, 2 = beta of the target length (against Eq. 3), 3 = one-sided (only the advancing crown, teacher-1); ours 0 = the contacting sector of both crowns (Eq. 3)", 0, 3, {1, 2, 3}, UNSTATED_ALL, 1},
};
#define NCHOICES (sizeof CHOICES / sizeof CHOICES[0])

const unstated_choice *unstated_list(size_t *n) { *n = NCHOICES; return CHOICES; }

const unstated_choice *unstated_find(const char *name)
{
    for (size_t i = 0; name && i < NCHOICES; i++)
        if (!strcmp(CHOICES[i].name, name)) return &CHOICES[i];
    return NULL;
}

void unstated_dirname(const unstated_choice *c, double value, char *buf, size_t n)
{
    snprintf(buf, n, "%s_%g", c->name, value);
}

int unstated_touches(const unstated_choice *c, const char *relpath)
{
    if (c->scope == UNSTATED_ALL) return 1;
    if (c->scope == UNSTATED_FIGURE)
        return !strncmp(relpath, "mechanism/figure_", 17) || !strncmp(relpath, "pointcloud/", 11);
    /* field: the E5/E6 tables and E2 at beta_field, which the field calibration sets */
    return !strncmp(relpath, "field/", 6) || !strncmp(relpath, "anisotropy/", 11) ||
           (!strncmp(relpath, "irreducibility/", 15) && strstr(relpath, "_field.tsv"));
}
