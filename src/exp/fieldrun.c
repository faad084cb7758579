/* fieldrun: see fieldrun.h. */
#include "fieldrun.h"
#include "field.h"
#include "gate.h"
#include "paths.h"
#include "stand_grow.h"
#include <math.h>
#include <stdio.h>
#include <string.h>

cs_status fieldrun_run(fieldrun_job *j, fs_trees *acc, double *worst)
{
    double d = exp_field_d(&j->rd), L = exp_field_L(&j->rd);
    j->failed = 0;
    for (unsigned s = 0; s < j->nstands; s++) {
        stand *sd;
        cs_status st = exp_stand_alloc(&j->rd, &sd, j->kind, d, L, j->shape, j->seed_exp, s);
        if (st == CS_EINPUT && j->kind == stems_hardcore && strstr(cs_errmsg(), "unbuildable")) {
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
cs_status fieldrun_write(const char *out, prov *p, const fs_trees *acc, const fieldrun_job *jobs, size_t nj,
                          fieldrun_meta_fn meta, void *ctx)
{
    char tp[600];
    fs_trees_path(out, tp, sizeof tp);
    tsv_writer *w;
    cs_status st = tsv_writer_open(&w, tp);
    if (st) return st;
    if ((st = prov_write(w, p))) { tsv_writer_abort(w); return st; }
    tsv_writer_meta(w, "what",
                    "one row per interior tree (>= 2 d from the edge): cardinal gaps E N W S (m) and crown elongation, "
                    "all-axis (elong, design.md §5) and cardinal (elong_card, design.md §5), canonical estimator");
    tsv_writer_meta(w, "summary", "%s", out);
    fs_trees_write(w, acc);
    if ((st = tsv_writer_commit(w))) return st;
    if ((st = tsv_writer_open(&w, out))) return st;
    if ((st = prov_write(w, p))) { tsv_writer_abort(w); return st; }
    tsv_writer_meta(w, "trees_table", "%s", tp);
    if (nj)
        tsv_writer_meta(w, "layout", "%s: field stands d = %g m on L = %g m (design.md §7 E5%s)",
                        exp_layout_name(jobs[0].rd.layout), exp_field_d(&jobs[0].rd), exp_field_L(&jobs[0].rd),
                        jobs[0].rd.layout == EXP_LAYOUT_5M_ON_60M ? "; a reading, design.md §7 E0" : "");
    if (nj) exp_variant_meta(w, &jobs[0].rd);
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

cs_status fieldrun_canonical_jitter(double *a)
{
    return gate_read_value(PATHS_GATE("anisotropy"), "canonical_jitter", 0, a);
}

void fieldrun_meta_generic(tsv_writer *w, void *ctx)
{
    fieldrun_meta_ctx *m = ctx;
    tsv_writer_meta(w, "what", "%s", m->what);
    tsv_writer_meta(w, "beta_field", "%.17g", m->beta_field);
}

/* With FIELD_TABLE: print sim/field spread ratios (informational; the claims
 * recompute them from the frozen table and the same field table). */
void fieldrun_print_spread_ratios(const char *cmd, const fs_trees *acc, double level, int twins)
{
    const char *path = field_table_env();
    if (!path) {
        printf("%s: spread ratio PENDING: needs the raw field table (%s=path), not on this machine\n", cmd,
               FIELD_TABLE_ENV);
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
            printf("%s: %s spread %.4f m / field spread %.4f m = %.3f\n", cmd, arm ? "coupled" : "uncoupled",
                   s.f.spread, fsum.spread, s.f.spread / fsum.spread);
    }
}
