/* exp_common: what every experiment shares (design.md §7): the readings (the
 * teacher rule and the field layout a unit runs under, and the provenance
 * that names them), growing a field stand under a reading, and pooled
 * interior-tree clearances and cover. Writing a unit's tables is unit_out.c,
 * the E5/E6 field stands fieldrun.c. Limits: no command lives here and no
 * experiment's choices (seeds, levels, stand counts) are made here. */
#include "exp_common.h"
#include "estimator.h"
#include "figdata.h"
#include "design.h"
#include "field.h"
#include "gate.h"
#include "paths.h"
#include "stand_grow.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define NS CROWN_NSEC


/* k = 1..3 NN clearances of the interior trees, appended to g[0..2]; interior cover. */
cs_status exp_stand_metrics(const stand *sd, const double *r, dvec g[3], double *cover, size_t *ntrees)
{
    const stems *s = sd->s;
    cs_status st = CS_OK;
    size_t m = 0;
    for (size_t i = 0; i < s->n && !st; i++) {
        if (!stems_interior(s, i)) continue;
        m++;
        for (int k = 1; k <= 3 && !st; k++) {
            double v;
            st = est_knn_clearance(s->x, s->y, r, s->n, i, k, &v);
            if (!st) st = dvec_push(&g[k - 1], v);
        }
    }
    if (ntrees) *ntrees += m;
    if (st || !cover) return st;
    double lo = 2.0 * s->d, hi = s->L - 2.0 * s->d;
    return est_cover(s->x, s->y, r, s->n, lo, lo, hi, hi, cover);
}


/* Median k1 clearance of the interior trees of one stand. */
double exp_stand_k1(const stand *sd, const double *r)
{
    dvec g[3] = {{0}, {0}, {0}};
    double med = NAN;
    if (!exp_stand_metrics(sd, r, g, NULL, NULL)) est_median(g[0].v, g[0].n, &med);
    for (int k = 0; k < 3; k++) free(g[k].v);
    return med;
}


cs_status exp_reading_parse(const char *teacher, const char *layout, exp_reading *r)
{
    r->one_sided = 0;
    r->layout = EXP_LAYOUT_R2;
    if (teacher && !strcmp(teacher, TEACHER_VERSION_ONE_SIDED)) r->one_sided = 1;
    else if (teacher && strcmp(teacher, TEACHER_VERSION))
        return cs_err(CS_EINPUT, "--teacher: must be %s or %s, not '%s'", TEACHER_VERSION, TEACHER_VERSION_ONE_SIDED, teacher);
    if (layout && !strcmp(layout, "r1")) r->layout = EXP_LAYOUT_R1;
    else if (layout && strcmp(layout, "r2")) return cs_err(CS_EINPUT, "--layout: must be r1 or r2, not '%s'", layout);
    return CS_OK;
}

static void exp_teacher_params(const exp_reading *r, teacher_params *p)
{
    teacher_params_default(p);
    p->one_sided = r ? r->one_sided : 0;
}

void exp_prov_begin(prov *p, const char *experiment, const exp_reading *r, int argc, char **argv)
{
    prov_begin(p, experiment, argc, argv);
    teacher_params tp;
    exp_teacher_params(r, &tp);
    snprintf(p->teacher_version, sizeof p->teacher_version, "%s", teacher_version(&tp));
}

double exp_field_d(exp_layout l) { return l == EXP_LAYOUT_R1 ? DESIGN_FIELD_SPACING_R1_M : DESIGN_FIELD_SPACING_M; }
double exp_field_L(exp_layout l) { return l == EXP_LAYOUT_R1 ? DESIGN_FIELD_L_R1_M : DESIGN_FIELD_L_M; }
const char *exp_layout_name(exp_layout l) { return l == EXP_LAYOUT_R1 ? "r1" : "r2"; }

cs_status exp_field_grow_append(const stand *sd, const exp_reading *rd, double beta, int coupled, double level,
                                unsigned index, fs_trees *acc, double *worst)
{
    stand_arrays v;
    stand_view(sd, &v);
    teacher_params p;
    exp_teacher_params(rd, &p);
    p.beta = beta;
    p.coupled = coupled;
    double *r = malloc((v.n ? v.n : 1) * CROWN_NSEC * sizeof *r);
    if (!r) return cs_err(CS_ENOMEM, "exp_field: out of memory");
    cs_status st = stand_grow(sd, &p, NULL, r, NULL, worst);
    for (size_t i = 0; i < v.n && !st; i++) {
        if (!stems_interior(sd->s, i)) continue;
        double g[4];
        est_cardinal_gaps(v.x, v.y, r, v.n, i, g);
        for (int c = 0; c < 4; c++)
            if (!isfinite(g[c])) st = cs_err(CS_ENUMERIC, "exp_field: interior tree %zu of stand %u has no neighbour in cardinal cone %d", i, index, c);
        if (!st) st = fs_trees_push(acc, coupled, level, index, (unsigned)i, g, est_elongation(r + i * CROWN_NSEC),
                                          est_elongation_cardinal(r + i * CROWN_NSEC));
    }
    free(r);
    return st;
}

