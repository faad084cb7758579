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
#include "unstated.h"
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
    memset(r, 0, sizeof *r);
    r->one_sided = 0;
    r->layout = EXP_LAYOUT_4M_ON_36M;
    if (teacher) {
        /* teacher-1|teacher-2, optionally -arc|-target: the name teacher_version() gives */
        size_t l = strlen(TEACHER_VERSION);
        const char *suffix = teacher + l;
        if (!strncmp(teacher, TEACHER_VERSION_ONE_SIDED, l)) r->one_sided = 1;
        else if (strncmp(teacher, TEACHER_VERSION, l)) suffix = NULL;
        if (suffix && !strcmp(suffix, "-arc")) r->dieback = TEACHER_DIEBACK_NEIGHBOURS;
        else if (suffix && !strcmp(suffix, "-target")) r->dieback = TEACHER_DIEBACK_TARGET;
        else if (!suffix || *suffix)
            return cs_err(CS_EINPUT, "--teacher: must be %s or %s, optionally with -arc or -target, not '%s'",
                          TEACHER_VERSION, TEACHER_VERSION_ONE_SIDED, teacher);
    }
    if (layout && !strcmp(layout, exp_layout_name(EXP_LAYOUT_5M_ON_60M))) r->layout = EXP_LAYOUT_5M_ON_60M;
    else if (layout && strcmp(layout, exp_layout_name(EXP_LAYOUT_4M_ON_36M)))
        return cs_err(CS_EINPUT, "--layout: must be %s or %s, not '%s'", exp_layout_name(EXP_LAYOUT_4M_ON_36M),
                      exp_layout_name(EXP_LAYOUT_5M_ON_60M), layout);
    return CS_OK;
}

/* One unstated choice set on v (unstated.h names; the design's values otherwise). */
static cs_status variant_set(exp_variant *v, const char *name, double x)
{
    if (!strcmp(name, "crown_R")) v->crowns.R_scale = x;
    else if (!strcmp(name, "crown_spread")) v->crowns.R_lnsd = x;
    else if (!strcmp(name, "height_sd")) v->crowns.h_sd = x;
    else if (!strcmp(name, "lobing")) v->crowns.a_max = x;
    else if (!strcmp(name, "growth_N")) {
        if (x != floor(x) || x < 4 || x > 4096)
            return cs_err(CS_EINPUT, "--vary growth_N: a whole number in [4, 4096], not %g", x);
        v->nres = (int)x;
    } else if (!strcmp(name, "start")) v->start_frac = x;
    else if (!strcmp(name, "fig_hardcore")) v->fig_c = x;
    else if (!strcmp(name, "field_d")) v->field_d = x;
    else if (!strcmp(name, "field_L")) v->field_L = x;
    else if (!strcmp(name, "dieback")) {
        if (x != 1.0 && x != 2.0 && x != 3.0)
            return cs_err(CS_EINPUT,
                          "--vary dieback: 1 (the contact arc), 2 (beta of the target length) or 3 (one-sided), not %g",
                          x);
        v->dieback = (int)x;
    } else return cs_err(CS_EINPUT, "--vary: no unstated choice '%s'", name);
    return CS_OK;
}

cs_status exp_reading_vary(const char *vary, exp_reading *r)
{
    if (!vary) return CS_OK;
    const char *eq = strchr(vary, '=');
    char name[32], *end;
    if (!eq || eq == vary || (size_t)(eq - vary) >= sizeof name)
        return cs_err(CS_EINPUT, "--vary: expected NAME=VALUE, not '%s'", vary);
    snprintf(name, sizeof name, "%.*s", (int)(eq - vary), vary);
    double x = strtod(eq + 1, &end);
    if (end == eq + 1 || *end || !isfinite(x) || x <= 0.0)
        return cs_err(CS_EINPUT, "--vary %s: value must be a positive number, not '%s'", name, eq + 1);
    const unstated_choice *c = unstated_find(name);
    if (!c) return cs_err(CS_EINPUT, "--vary: no unstated choice '%s' (unstated.h)", name);
    if (r->layout == EXP_LAYOUT_5M_ON_60M && c->scope == UNSTATED_FIELD)
        return cs_err(CS_EINPUT, "--vary %s: varies the 4m-on-36m field layout, not with --layout 5m-on-60m", name);
    exp_variant *v = &r->var;
    memset(v, 0, sizeof *v);
    snprintf(v->name, sizeof v->name, "%s", name);
    v->value = x;
    crown_dist_default(&v->crowns);
    v->nres = 48;
    v->start_frac = 0.05;
    v->fig_c = EXP_FIG_C;
    v->field_d = DESIGN_FIELD_SPACING_M;
    v->field_L = DESIGN_FIELD_L_M;
    cs_status st = variant_set(v, name, x);
    if (st) return st;
    /* 3: the one-sided reading (teacher-1: only the advancing crown dies back) */
    if (v->dieback == 3) r->one_sided = 1;
    else if (v->dieback) r->dieback = v->dieback;
    r->varied = 1;
    return CS_OK;
}

static void exp_teacher_params(const exp_reading *r, teacher_params *p) { EXP_TEACHER_PARAMS(r, p); }

cs_status exp_stand_alloc(const exp_reading *r, stand **out, const stems_type *kind, double d, double L, double shape,
                          const char *experiment, unsigned index)
{
    return stand_alloc_dist(out, kind, d, L, shape, experiment, index, r && r->varied ? &r->var.crowns : NULL);
}

double exp_fig_c(const exp_reading *r) { return r && r->varied ? r->var.fig_c : EXP_FIG_C; }
int exp_nres(const exp_reading *r) { return r && r->varied ? r->var.nres : 48; }

void exp_variant_meta(tsv_writer *w, const exp_reading *r)
{
    if (r && r->varied)
        tsv_writer_meta(w, "sensitivity", "%s = %.17g (design.md §7 E0; every other choice the design's)", r->var.name,
                        r->var.value);
}

void exp_prov_begin(prov *p, const char *experiment, const exp_reading *r, int argc, char **argv)
{
    prov_begin(p, experiment, argc, argv);
    teacher_params tp;
    exp_teacher_params(r, &tp);
    snprintf(p->teacher_version, sizeof p->teacher_version, "%s", teacher_version(&tp));
}

double exp_field_d(const exp_reading *r)
{
    if (r && r->varied) return r->var.field_d;
    return r && r->layout == EXP_LAYOUT_5M_ON_60M ? DESIGN_FIELD_SPACING_WIDE_M : DESIGN_FIELD_SPACING_M;
}
double exp_field_L(const exp_reading *r)
{
    if (r && r->varied) return r->var.field_L;
    return r && r->layout == EXP_LAYOUT_5M_ON_60M ? DESIGN_FIELD_L_WIDE_M : DESIGN_FIELD_L_M;
}
const char *exp_layout_name(exp_layout l) { return l == EXP_LAYOUT_5M_ON_60M ? "5m-on-60m" : "4m-on-36m"; }

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
            if (!isfinite(g[c]))
                st =
                    cs_err(CS_ENUMERIC, "exp_field: interior tree %zu of stand %u has no neighbour in cardinal cone %d",
                           i, index, c);
        if (!st) st = fs_trees_push(acc, coupled, level, index, (unsigned)i, g, est_elongation(r + i * CROWN_NSEC),
                                          est_elongation_cardinal(r + i * CROWN_NSEC));
    }
    free(r);
    return st;
}

