/* exp_common: what the experiments' units share (design.md §7, §9): the output
 * path and atomic commit of a unit's table, the metadata lines every unit
 * writes, pooled interior-tree clearances and cover, the crown and outline
 * tables of the canopy figures (design.md §12), and the field stands, options and
 * tables of E5 (exp_field.c, reference paper §5.3) and E6 (exp_aniso.c,
 * §5.4). Limits: no command lives here and no experiment's choices (seeds,
 * levels, stand counts) are made here; each experiment's file records its own. */
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

/* Growable double array. */
cs_status exp_dvec_push(exp_dvec *a, double x)
{
    if (a->n == a->cap) {
        size_t c = a->cap ? 2 * a->cap : 256;
        double *nv = realloc(a->v, c * sizeof *nv);
        if (!nv) return cs_err(CS_ENOMEM, "experiments: out of memory");
        a->v = nv;
        a->cap = c;
    }
    a->v[a->n++] = x;
    return CS_OK;
}

/* k = 1..3 NN clearances of the interior trees, appended to g[0..2]; interior cover. */
cs_status exp_stand_metrics(const stand *sd, const double *r, exp_dvec g[3], double *cover, size_t *ntrees)
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
            if (!st) st = exp_dvec_push(&g[k - 1], v);
        }
    }
    if (ntrees) *ntrees += m;
    if (st || !cover) return st;
    double lo = 2.0 * s->d, hi = s->L - 2.0 * s->d;
    return est_cover(s->x, s->y, r, s->n, lo, lo, hi, hi, cover);
}

cs_status exp_open_out(const exp_opts *o, const char *experiment, const char *file, tsv_writer **w,
                          char *path, size_t pathsz)
{
    snprintf(path, pathsz, "%s/%s/%s", o->out, experiment, file);
    return tsv_writer_open(w, path);
}

cs_status exp_finish(tsv_writer *w, prov *pv, const char *path)
{
    cs_status st = tsv_writer_commit(w);
    if (!st) fprintf(stderr, "wrote %s (%.1f s)\n", path, prov_now() - pv->t0);
    return st;
}

/* Metadata lines shared by all units (after the provenance block). */
void exp_common_meta(tsv_writer *w, const exp_opts *o)
{
    tsv_writer_meta(w, "stands_per_cell", "%d", o->stands);
    tsv_writer_meta(w, "teacher_resolution", "N = 48 unless a column says otherwise; gamma = 1");
}

/* Crowns of one panel: one row per tree: panel, tree, x, y, h, interior, r0..r23. */
void exp_write_crowns(tsv_writer *w, const char *panel, double d, const stand *sd, const double *r)
{
    for (size_t i = 0; i < sd->s->n; i++) {
        tsv_writer_str(w, panel);
        tsv_writer_dbl(w, d);
        tsv_writer_long(w, (long)i);
        tsv_writer_dbl(w, sd->s->x[i]);
        tsv_writer_dbl(w, sd->s->y[i]);
        tsv_writer_dbl(w, sd->h[i]);
        tsv_writer_long(w, stems_interior(sd->s, i));
        for (int s = 0; s < NS; s++) tsv_writer_dbl(w, r[i * NS + s]);
        tsv_writer_endrow(w);
    }
}

void exp_crown_columns(tsv_writer *w)
{
    char cols[1024];
    int off = snprintf(cols, sizeof cols, "panel\tspacing_m\ttree\tx_m\ty_m\th_m\tinterior");
    for (int s = 0; s < NS; s++) off += snprintf(cols + off, sizeof cols - (size_t)off, "\tr%d", s);
    tsv_writer_columns(w, cols);
}

cs_status exp_write_polygons(const exp_opts *o, prov *pv, const char *experiment, const char *panel, double d,
                                const stand *sd, const double *r, double k1)
{
    char file[128], path[512];
    snprintf(file, sizeof file, "figure_poly_%s_%.1f.tsv", panel, d);
    tsv_writer *w = NULL;
    cs_status st = exp_open_out(o, experiment, file, &w, path, sizeof path);
    if (st) return st;
    st = prov_write(w, pv);
    if (st) { tsv_writer_abort(w); return st; }
    size_t n = sd->s->n;
    tsv_writer_meta(w, "panel", "%s, spacing %.2f m, footprint %.0f m, %zu trees, %d rows per tree", panel, d, sd->s->L, n, FIGDATA_ROWS);
    tsv_writer_meta(w, "k1_median_m", "%.3f", k1);
    st = figdata_write_polygons(w, n, sd->s->x, sd->s->y, sd->h, r, NULL, NULL);
    if (st) { tsv_writer_abort(w); return st; }
    return tsv_writer_commit(w);
}

/* Median k1 clearance of the interior trees of one stand. */
double exp_stand_k1(const stand *sd, const double *r)
{
    exp_dvec g[3] = {{0}, {0}, {0}};
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

/* ------------------------------------------------ E5/E6 field stands ---- */

cs_status exp_field_run_job(exp_field_job *j, fs_trees *acc, double *worst)
{
    double d = exp_field_d(j->rd.layout), L = exp_field_L(j->rd.layout);
    j->failed = 0;
    for (unsigned s = 0; s < j->nstands; s++) {
        stand *sd;
        cs_status st = stand_alloc(&sd, j->kind, d, L, j->shape, j->seed_exp, s);
        if (st == CS_EINPUT && j->kind == STAND_HARDCORE && strstr(cs_errmsg(), "unbuildable")) {
            /* A level the stem process cannot reach is a finding, not a crash. */
            j->failed++;
            continue;
        }
        if (st) return st;
        st = exp_field_grow_append(sd, &j->rd, j->beta, 1, j->level, s, acc, worst);
        if (!st && j->twins) st = exp_field_grow_append(sd, &j->rd, j->beta, 0, j->level, s, acc, NULL);
        stand_free(sd);
        if (st) return st;
    }
    return CS_OK;
}

/* Write X_trees.tsv then X.tsv (one summary row per job and arm). */
cs_status exp_field_write(const char *out, prov *p, const fs_trees *acc, const exp_field_job *jobs, size_t nj,
                          exp_field_meta_fn meta, void *ctx)
{
    char tp[600];
    fs_trees_path(out, tp, sizeof tp);
    tsv_writer *w;
    cs_status st = tsv_writer_open(&w, tp);
    if (st) return st;
    if ((st = prov_write(w, p))) { tsv_writer_abort(w); return st; }
    tsv_writer_meta(w, "what", "one row per interior tree (>= 2 d from the edge): cardinal gaps E N W S (m) and crown elongation, all-axis (elong, design.md §5) and cardinal (elong_card, design.md §5), canonical estimator");
    tsv_writer_meta(w, "summary", "%s", out);
    fs_trees_write(w, acc);
    if ((st = tsv_writer_commit(w))) return st;
    if ((st = tsv_writer_open(&w, out))) return st;
    if ((st = prov_write(w, p))) { tsv_writer_abort(w); return st; }
    tsv_writer_meta(w, "trees_table", "%s", tp);
    if (nj) tsv_writer_meta(w, "layout", "%s: field stands d = %g m on L = %g m (design.md §7 E5%s)", exp_layout_name(jobs[0].rd.layout),
                            exp_field_d(jobs[0].rd.layout), exp_field_L(jobs[0].rd.layout),
                            jobs[0].rd.layout == EXP_LAYOUT_R1 ? ", the first round's layout" : "");
    if (meta) meta(w, ctx);
    tsv_writer_columns(w, FS_SUMMARY_COLUMNS);
    for (size_t k = 0; k < nj && !st; k++)
        for (int arm = 1; arm >= (jobs[k].twins ? 0 : 1) && !st; arm--) {
            fs_summary s;
            memset(&s, 0, sizeof s);
            size_t have = 0;
            for (size_t i = 0; i < acc->n; i++) have += acc->coupled[i] == arm && acc->level[i] == jobs[k].level;
            if (have) st = fs_group(acc, arm, jobs[k].level, &s);
            if (!st) fs_summary_write_row(w, arm, jobs[k].level, jobs[k].beta, jobs[k].failed, &s);
        }
    if (st) { tsv_writer_abort(w); return st; }
    return tsv_writer_commit(w);
}

cs_status exp_canonical_jitter(double *a)
{
    return gate_read_value(PATHS_GATE("anisotropy"), "canonical_jitter", 0, a);
}

void exp_meta_generic(tsv_writer *w, void *ctx)
{
    exp_meta_ctx *m = ctx;
    tsv_writer_meta(w, "what", "%s", m->what);
    tsv_writer_meta(w, "beta_field", "%.17g", m->beta_field);
}

/* With FIELD_TABLE: print sim/field spread ratios (informational; the claims
 * recompute them from the frozen table and the same field table). */
void exp_print_spread_ratios(const char *cmd, const fs_trees *acc, double level, int twins)
{
    const char *path = field_table_env();
    if (!path) {
        printf("%s: spread ratio PENDING: needs the raw field table (%s=path), not on this machine\n", cmd, FIELD_TABLE_ENV);
        return;
    }
    field_table ft;
    field_summary fsum;
    if (field_table_load(path, &ft) || field_summarize((const double (*)[4])ft.gap, ft.n, &fsum)) {
        printf("%s: spread ratio not computed: %s\n", cmd, cs_errmsg());
        field_table_free(&ft);
        return;
    }
    field_table_free(&ft);
    for (int arm = 1; arm >= (twins ? 0 : 1); arm--) {
        fs_summary s;
        if (!fs_group(acc, arm, level, &s))
            printf("%s: %s spread %.4f m / field spread %.4f m = %.3f\n", cmd, arm ? "coupled" : "uncoupled", s.f.spread, fsum.spread, s.f.spread / fsum.spread);
    }
}
