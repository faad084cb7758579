/* exp_field: E5 field validation and E6 anisotropy attribution (SPEC §7;
 * reference paper §5.3, §5.4).
 *
 * Field stands: the controlled lattice at d = 5.0 m (DESIGN_FIELD_SPACING_M),
 * L = 12 d, canonical jitter (anisotropy.gate canonical_jitter); teacher at
 * N = 48, gamma = 1. Seeds: seed_derive(<seed experiment>, 5.0, stand,
 * "stems"/"crowns") with one seed-experiment string per role, so that
 * calibration, held-out and sweep stands are disjoint by construction:
 *   field/calibration   stands 0..calibration_seeds-1, the same stands at every beta
 *   field/heldout       E5 held-out (coupled and uncoupled twin share the stand)
 *   anisotropy/lattice  E6 lattice statistic at beta_field
 *   anisotropy/hardcore hard-core family, same indices at every c
 *   anisotropy/jitter   jitter family (a* calibration), same indices at every a
 *   anisotropy/heldout  held-out stands at a*
 * Re-using the same indices across the levels of one sweep (common random
 * numbers) makes the sweep curves smooth in the knob without favouring any
 * level. Outputs: X.tsv (one row per arm and level) and X_trees.tsv (one row
 * per interior tree), both with the provenance block; the summary is written
 * last, so a killed run leaves no target make would count as done.
 * Limits: d and L are fixed by the design; stand counts are options (the
 * defaults are the full-run choices recorded in each file's provenance). */
#include "exp_field.h"
#include "exp_common.h"
#include "design.h"
#include "fieldsim.h"
#include "gate.h"
#include "opts.h"
#include "paths.h"
#include "prov.h"
#include "stats.h"
#include "estimator.h"
#include "crown.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define FS_L_FACTOR 12.0  /* L = 12 d (SPEC §2) */

/* The options of the E5/E6 commands; each command's table lists the ones it takes. */
typedef struct {
    const char *out, *calibration, *sweep, *jitter_calibration;
    long stands_opt;  /* --stands, parsed */
    unsigned stands;  /* the same, set by fs_parse */
} fs_opts;

#define FS_OPT_OUT(o) {"out", OPT_STR, &(o).out, 0, 0, "output table (required)"}
#define FS_OPT_CAL(o) {"calibration", OPT_STR, &(o).calibration, 0, 0, "E5 calibration table DIR/calibration.tsv, gives beta_field (required)"}
#define FS_OPT_STANDS(o, help) {"stands", OPT_LONG, &(o).stands_opt, 1, 10000, help}

static int fs_die(const char *cmd, cs_status st)
{
    fprintf(stderr, "crownshy %s: %s\n", cmd, cs_errmsg()[0] ? cs_errmsg() : cs_status_name(st));
    return cs_exit_code(st);
}

/* opts_parse with the table of c (no positional arguments), then --out is
 * required when the table has it. An opts result: OPTS_OK, OPTS_HELP, OPTS_USAGE. */
static int fs_parse(const opts_cmd *c, int argc, char **argv, fs_opts *o)
{
    int r = opts_parse(c, argc, argv, NULL, NULL);
    if (r) return r;
    o->stands = (unsigned)o->stands_opt;
    for (size_t i = 0; i < c->nopts; i++)
        if (c->opts[i].dst == &o->out && !o->out) { opts_usage_error(c->cmd, "--out PATH is required"); return OPTS_USAGE; }
    return OPTS_OK;
}

/* One group of stands: `nstands` stands of one stem process at one level. */
typedef struct {
    const char *seed_exp;
    stand_kind kind;
    double shape, level, beta;
    unsigned nstands;
    int twins;          /* also grow the uncoupled twin of each stand */
    size_t failed;      /* out: stands that could not be built (hard-core "unbuildable") */
} fs_job;

static cs_status fs_run_job(fs_job *j, fs_trees *acc, double *worst)
{
    double d = DESIGN_FIELD_SPACING_M, L = FS_L_FACTOR * d;
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
        st = exp_field_grow_append(sd, j->beta, 1, j->level, s, acc, worst);
        if (!st && j->twins) st = exp_field_grow_append(sd, j->beta, 0, j->level, s, acc, NULL);
        stand_free(sd);
        if (st) return st;
    }
    return CS_OK;
}

typedef void (*fs_meta_fn)(tsv_writer *w, void *ctx);

/* Write X_trees.tsv then X.tsv (one summary row per job and arm). */
static cs_status fs_write(const char *out, prov *p, const fs_trees *acc, const fs_job *jobs, size_t nj,
                          fs_meta_fn meta, void *ctx)
{
    char tp[600];
    fs_trees_path(out, tp, sizeof tp);
    tsv_writer *w;
    cs_status st = tsv_writer_open(&w, tp);
    if (st) return st;
    if ((st = prov_write(w, p))) { tsv_writer_abort(w); return st; }
    tsv_writer_meta(w, "what", "one row per interior tree (>= 2 d from the edge): cardinal gaps E N W S (m) and crown elongation, canonical estimator");
    tsv_writer_meta(w, "summary", "%s", out);
    fs_trees_write(w, acc);
    if ((st = tsv_writer_commit(w))) return st;
    if ((st = tsv_writer_open(&w, out))) return st;
    if ((st = prov_write(w, p))) { tsv_writer_abort(w); return st; }
    tsv_writer_meta(w, "trees_table", "%s", tp);
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

static cs_status fs_canonical_jitter(double *a)
{
    return gate_read_value(PATHS_GATE("anisotropy"), "canonical_jitter", 0, a);
}

/* ---------------------------------------------------------------- E5 ---- */

int cmd_field_summary(int argc, char **argv)
{
    const opts_cmd oc = {"field-summary", "[TABLE.tsv]",
                         "Summarise a raw field table (default: $FIELD_TABLE): trees, measurements, tree-mean\n"
                         "median clearance, spread (IQR of all cardinal gaps), anisotropy median (+ excluded),\n"
                         "with the canonical estimator's functions, next to the published figures of\n"
                         "frozen/field/reference.tsv. Columns: tree, direction (E/N/W/S or east/north/west/south),\n"
                         "clearance_m; each tree needs each direction exactly once. Exit 3 on a bad table.",
                         NULL, 0, 0, 1};
    char *pos[argc > 0 ? argc : 1];
    int npos = 0, rc = opts_parse(&oc, argc, argv, pos, &npos);
    if (rc) return opts_exit_code(rc);
    const char *path = npos ? pos[0] : field_table_env();
    if (!path) {
        fprintf(stderr, "crownshy field-summary: no table given and %s is not set; the raw field table "
                        "(Dryad doi:10.5061/dryad.34tmpg4hk) is not on this machine\n", FIELD_TABLE_ENV);
        return 3;
    }
    field_table ft;
    cs_status st = field_table_load(path, &ft);
    if (st) return fs_die("field-summary", st);
    field_summary s;
    st = field_summarize((const double (*)[4])ft.gap, ft.n, &s);
    field_table_free(&ft);
    if (st) return fs_die("field-summary", st);
    double ref;
    printf("table\t%s\n", path);
    printf("trees\t%zu", s.trees);
    if (!field_reference_get(FIELD_REFERENCE_PATH, "trees", &ref, NULL)) printf("\t(published %g)", ref);
    printf("\nmeasurements\t%zu", s.measurements);
    if (!field_reference_get(FIELD_REFERENCE_PATH, "measurements", &ref, NULL)) printf("\t(published %g)", ref);
    printf("\ntree_mean_median_m\t%.17g", s.tree_mean_median);
    if (!field_reference_get(FIELD_REFERENCE_PATH, "tree_mean_median_m", &ref, NULL)) printf("\t(published %g)", ref);
    printf("\nspread_iqr_m\t%.17g\naniso_median\t%.17g", s.spread, s.aniso_median);
    if (!field_reference_get(FIELD_REFERENCE_PATH, "aniso_median", &ref, NULL)) printf("\t(published %g)", ref);
    printf("\naniso_trees\t%zu\naniso_excluded\t%zu\n", s.aniso_trees, s.aniso_excluded);
    return 0;
}

static void meta_calibration(tsv_writer *w, void *ctx)
{
    (void)ctx;
    tsv_writer_meta(w, "what", "E5 calibration: median over interior trees (pooled over the calibration stands) of the tree-mean cardinal clearance, per die-back beta; lattice d = 5 m, L = 60 m");
    tsv_writer_meta(w, "rule", "beta_field = linear interpolation of the curve to gates/field.gate calibration_target_m, rounded to the grid step (fs_beta_field)");
}

int cmd_field_calibrate(int argc, char **argv)
{
    fs_opts o = {0};
    const opt_spec spec[] = {FS_OPT_OUT(o)};
    const opts_cmd oc = {"field-calibrate", "--out DIR/calibration.tsv",
                         "E5 calibration (SPEC §7): grow the calibration stands (gates/field.gate calibration_seeds)\n"
                         "at every beta of dieback_grid, record the median tree-mean clearance per beta, and print\n"
                         "beta_field (interpolated to calibration_target_m, rounded to the grid). Also writes\n"
                         "DIR/calibration_trees.tsv.",
                         spec, sizeof spec / sizeof *spec, 0, 0};
    int rc = fs_parse(&oc, argc, argv, &o);
    if (rc) return opts_exit_code(rc);
    prov p;
    prov_begin(&p, "field", argc, argv);
    double lo, hi, step, seeds, a;
    cs_status st = gate_read_value(PATHS_GATE("field"), "dieback_grid", 0, &lo);
    if (!st) st = gate_read_value(PATHS_GATE("field"), "dieback_grid", 1, &hi);
    if (!st) st = gate_read_value(PATHS_GATE("field"), "dieback_grid", 2, &step);
    if (!st) st = gate_read_value(PATHS_GATE("field"), "calibration_seeds", 0, &seeds);
    if (!st) st = fs_canonical_jitter(&a);
    if (st) return fs_die("field-calibrate", st);
    size_t nb = (size_t)lround((hi - lo) / step) + 1;
    fs_job *jobs = calloc(nb, sizeof *jobs);
    fs_trees acc;
    fs_trees_init(&acc);
    double worst = 0;
    for (size_t k = 0; k < nb && !st; k++) {
        double beta = fs_round_step(lo + (double)k * step, step);
        jobs[k] = (fs_job){"field/calibration", STAND_LATTICE, a, beta, beta, (unsigned)seeds, 0, 0};
        st = fs_run_job(&jobs[k], &acc, &worst);
        if (!st && (k % 7 == 0 || k + 1 == nb)) fprintf(stderr, "field-calibrate: beta %.2f done (%zu/%zu)\n", beta, k + 1, nb);
    }
    snprintf(p.seeds, sizeof p.seeds, "seed_derive(\"field/calibration\", 5.0, s, stems|crowns), s = 0..%u at every beta", (unsigned)seeds - 1);
    p.worst_overlap_m = worst;
    if (!st) st = fs_write(o.out, &p, &acc, jobs, nb, meta_calibration, NULL);
    fs_trees_free(&acc);
    free(jobs);
    if (st) return fs_die("field-calibrate", st);
    fs_calibration c;
    if ((st = fs_beta_field(o.out, &c))) return fs_die("field-calibrate", st);
    printf("field-calibrate: target %.3f m, beta interpolated %.6f, beta_field %.2f%s\n", c.target, c.interp, c.value,
           c.bracketed ? "" : " (TARGET NOT BRACKETED by the grid: nearest end)");
    return 0;
}

int cmd_field_beta(int argc, char **argv)
{
    const opts_cmd oc = {"field-beta", "DIR/calibration.tsv",
                         "Print beta_field (%.17g) recomputed from an E5 calibration table (used by the make units\n"
                         "that rerun E2 at the field operating point).",
                         NULL, 0, 1, 1};
    char *pos[argc > 0 ? argc : 1];
    int rc = opts_parse(&oc, argc, argv, pos, NULL);
    if (rc) return opts_exit_code(rc);
    fs_calibration c;
    cs_status st = fs_beta_field(pos[0], &c);
    if (st) return fs_die("field-beta", st);
    printf("%.17g\n", c.value);
    return 0;
}

/* beta_field from --calibration, or a usage/input error code. */
static int need_beta(const char *cmd, const fs_opts *o, fs_calibration *c)
{
    if (!o->calibration) { opts_usage_error(cmd, "--calibration DIR/calibration.tsv is required (beta_field)"); return 2; }
    cs_status st = fs_beta_field(o->calibration, c);
    if (st) return fs_die(cmd, st);
    return 0;
}

typedef struct { double beta_field, a; const char *what; } meta_ctx;

static void meta_generic(tsv_writer *w, void *ctx)
{
    meta_ctx *m = ctx;
    tsv_writer_meta(w, "what", "%s", m->what);
    tsv_writer_meta(w, "beta_field", "%.17g", m->beta_field);
}

/* With FIELD_TABLE: print sim/field spread ratios (informational; the claims
 * recompute them from the frozen table and the same field table). */
static void print_spread_ratios(const char *cmd, const fs_trees *acc, double level, int twins)
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

int cmd_field_heldout(int argc, char **argv)
{
    fs_opts o = {.stands_opt = 28};
    const opt_spec spec[] = {FS_OPT_CAL(o), FS_OPT_OUT(o), FS_OPT_STANDS(o, "stands (default 28)")};
    const opts_cmd oc = {"field-heldout", "--calibration DIR/calibration.tsv --out DIR/heldout.tsv [--stands N]",
                         "E5 held-out (SPEC §7): N stands (default 28) on seeds disjoint from the calibration, grown at\n"
                         "beta_field coupled and as the uncoupled twin: tree-mean median, spread, elongation, anisotropy.\n"
                         "The spread ratios need the raw field table (FIELD_TABLE=path); without it they are pending.",
                         spec, sizeof spec / sizeof *spec, 0, 0};
    int rc = fs_parse(&oc, argc, argv, &o);
    if (rc) return opts_exit_code(rc);
    fs_calibration c;
    if ((rc = need_beta("field-heldout", &o, &c))) return rc;
    prov p;
    prov_begin(&p, "field", argc, argv);
    double a;
    cs_status st = fs_canonical_jitter(&a);
    if (st) return fs_die("field-heldout", st);
    fs_job j = {"field/heldout", STAND_LATTICE, a, c.value, c.value, o.stands, 1, 0};
    fs_trees acc;
    fs_trees_init(&acc);
    double worst = 0;
    st = fs_run_job(&j, &acc, &worst);
    snprintf(p.seeds, sizeof p.seeds, "seed_derive(\"field/heldout\", 5.0, s, stems|crowns), s = 0..%u; uncoupled twin = same stand", o.stands - 1);
    p.worst_overlap_m = worst;
    meta_ctx m = {c.value, a, "E5 held-out: controlled lattice d = 5 m, L = 60 m, canonical jitter, teacher at beta_field; coupled stands and their uncoupled twins (same stems and crown draws)"};
    if (!st) st = fs_write(o.out, &p, &acc, &j, 1, meta_generic, &m);
    if (!st) {
        fs_summary s;
        if (!fs_group(&acc, 1, c.value, &s))
            printf("field-heldout: beta_field %.2f, %zu stands, %zu trees: tree-mean median %.4f m, elongation median %.4f, spread %.4f m\n",
                   c.value, s.stands, s.f.trees, s.f.tree_mean_median, s.elong_median, s.f.spread);
        print_spread_ratios("field-heldout", &acc, c.value, 1);
    }
    fs_trees_free(&acc);
    return st ? fs_die("field-heldout", st) : 0;
}

/* ---------------------------------------------------------------- E6 ---- */

int cmd_aniso_lattice(int argc, char **argv)
{
    fs_opts o = {.stands_opt = 28};
    const opt_spec spec[] = {FS_OPT_CAL(o), FS_OPT_OUT(o), FS_OPT_STANDS(o, "stands (default 28)")};
    const opts_cmd oc = {"aniso-lattice", "--calibration DIR/calibration.tsv --out DIR/lattice.tsv [--stands N]",
                         "E6 (SPEC §7): anisotropy on the controlled lattice (d = 5 m, canonical jitter) at beta_field,\n"
                         "N stands (default 28).",
                         spec, sizeof spec / sizeof *spec, 0, 0};
    int rc = fs_parse(&oc, argc, argv, &o);
    if (rc) return opts_exit_code(rc);
    fs_calibration c;
    if ((rc = need_beta("aniso-lattice", &o, &c))) return rc;
    prov p;
    prov_begin(&p, "anisotropy", argc, argv);
    double a;
    cs_status st = fs_canonical_jitter(&a);
    if (st) return fs_die("aniso-lattice", st);
    fs_job j = {"anisotropy/lattice", STAND_LATTICE, a, a, c.value, o.stands, 0, 0};
    fs_trees acc;
    fs_trees_init(&acc);
    double worst = 0;
    st = fs_run_job(&j, &acc, &worst);
    snprintf(p.seeds, sizeof p.seeds, "seed_derive(\"anisotropy/lattice\", 5.0, s, stems|crowns), s = 0..%u", o.stands - 1);
    p.worst_overlap_m = worst;
    meta_ctx m = {c.value, a, "E6 lattice: controlled lattice d = 5 m, L = 60 m, canonical jitter (level = a), teacher at beta_field"};
    if (!st) st = fs_write(o.out, &p, &acc, &j, 1, meta_generic, &m);
    if (!st) {
        fs_summary s;
        if (!fs_group(&acc, 1, a, &s))
            printf("aniso-lattice: anisotropy median %.4f over %zu trees (%zu excluded) in %zu stands\n", s.f.aniso_median, s.f.aniso_trees, s.f.aniso_excluded, s.stands);
    }
    fs_trees_free(&acc);
    return st ? fs_die("aniso-lattice", st) : 0;
}

/* A family sweep: one job per level of `key` in anisotropy.gate. */
static int aniso_family(const char *cmd, const char *synopsis, const char *about, int argc, char **argv,
                        stand_kind kind, const char *key, const char *seed_exp, const char *what)
{
    fs_opts o = {.stands_opt = 12};
    const opt_spec spec[] = {FS_OPT_CAL(o), FS_OPT_OUT(o), FS_OPT_STANDS(o, "stands per level (default 12)")};
    const opts_cmd oc = {cmd, synopsis, about, spec, sizeof spec / sizeof *spec, 0, 0};
    int rc = fs_parse(&oc, argc, argv, &o);
    if (rc) return opts_exit_code(rc);
    fs_calibration c;
    if ((rc = need_beta(cmd, &o, &c))) return rc;
    prov p;
    prov_begin(&p, "anisotropy", argc, argv);
    double lv[32];
    size_t nl;
    cs_status st = gate_read_values(PATHS_GATE("anisotropy"), key, lv, 32, &nl);
    if (st) return fs_die(cmd, st);
    fs_job jobs[32];
    fs_trees acc;
    fs_trees_init(&acc);
    double worst = 0;
    for (size_t k = 0; k < nl && !st; k++) {
        jobs[k] = (fs_job){seed_exp, kind, lv[k], lv[k], c.value, o.stands, 0, 0};
        st = fs_run_job(&jobs[k], &acc, &worst);
        if (!st) {
            fs_summary s;
            if (jobs[k].failed == o.stands) fprintf(stderr, "%s: level %.2f UNBUILDABLE (%zu of %u stands failed)\n", cmd, lv[k], jobs[k].failed, o.stands);
            else if (!fs_group(&acc, 1, lv[k], &s))
                fprintf(stderr, "%s: level %.2f: anisotropy median %.4f (%zu trees, %zu excluded; %zu stands failed)\n", cmd, lv[k], s.f.aniso_median, s.f.aniso_trees, s.f.aniso_excluded, jobs[k].failed);
        }
    }
    snprintf(p.seeds, sizeof p.seeds, "seed_derive(\"%s\", 5.0, s, stems|crowns), s = 0..%u at every level", seed_exp, o.stands - 1);
    p.worst_overlap_m = worst;
    meta_ctx m = {c.value, 0, what};
    if (!st) st = fs_write(o.out, &p, &acc, jobs, nl, meta_generic, &m);
    fs_trees_free(&acc);
    return st ? fs_die(cmd, st) : 0;
}

int cmd_aniso_hardcore(int argc, char **argv)
{
    return aniso_family("aniso-hardcore", "--calibration DIR/calibration.tsv --out DIR/hardcore.tsv [--stands N]",
                        "E6 hard-core family (SPEC §7): stems by random sequential addition with minimum distance c d,\n"
                        "c in anisotropy.gate hardcore_levels, N stands per level (default 12), teacher at beta_field.\n"
                        "A level whose stands cannot be built is recorded (stands_failed, trees 0), not a crash.",
                        argc, argv, STAND_HARDCORE, "hardcore_levels", "anisotropy/hardcore",
                        "E6 hard-core family: n = (L/d)^2 stems, minimum distance c d (level = c), d = 5 m, L = 60 m, teacher at beta_field");
}

int cmd_aniso_jitter(int argc, char **argv)
{
    return aniso_family("aniso-jitter", "--calibration DIR/calibration.tsv --out DIR/jitter.tsv [--stands N]",
                        "E6 jitter family (SPEC §7): controlled lattice with per-axis jitter sd a d, a in\n"
                        "anisotropy.gate jitter_levels, N stands per level (default 12), teacher at beta_field.",
                        argc, argv, STAND_LATTICE, "jitter_levels", "anisotropy/jitter",
                        "E6 jitter family: lattice d = 5 m, L = 60 m, jitter sd a d (level = a), teacher at beta_field");
}

int cmd_aniso_jitter_calibrate(int argc, char **argv)
{
    fs_opts o = {0};
    const opt_spec spec[] = {
        {"sweep", OPT_STR, &o.sweep, 0, 0, "E6 jitter sweep table DIR/jitter.tsv (required)"},
        FS_OPT_OUT(o),
    };
    const opts_cmd oc = {"aniso-jitter-calibrate", "--sweep DIR/jitter.tsv --out DIR/jitter_calibration.tsv",
                         "E6: the jitter sweep's median anisotropy per level (checked against the per-tree table) and\n"
                         "a* = linear interpolation to anisotropy.gate field_median, rounded to 0.01.",
                         spec, sizeof spec / sizeof *spec, 0, 0};
    int rc = fs_parse(&oc, argc, argv, &o);
    if (rc) return opts_exit_code(rc);
    if (!o.sweep) { opts_usage_error("aniso-jitter-calibrate", "--sweep DIR/jitter.tsv is required"); return 2; }
    prov p;
    prov_begin(&p, "anisotropy", argc, argv);
    tsv *t;
    fs_trees tr;
    cs_status st = fs_load_checked(o.sweep, &t, &tr);
    if (st) return fs_die("aniso-jitter-calibrate", st);
    fs_trees_free(&tr);
    tsv_writer *w;
    if ((st = tsv_writer_open(&w, o.out))) { tsv_free(t); return fs_die("aniso-jitter-calibrate", st); }
    snprintf(p.seeds, sizeof p.seeds, "%s", tsv_meta(t, "seeds") ? tsv_meta(t, "seeds") : "-");
    p.worst_overlap_m = -1;
    if ((st = prov_write(w, &p))) { tsv_writer_abort(w); tsv_free(t); return fs_die("aniso-jitter-calibrate", st); }
    tsv_writer_meta(w, "what", "E6 jitter calibration curve: median anisotropy per jitter level (from %s); a* = interpolation to the field median, rounded to 0.01 (fs_jitter_star)", o.sweep);
    tsv_writer_columns(w, "level\taniso_median\taniso_trees");
    for (size_t r = 0; r < tsv_nrows(t) && !st; r++) {
        double lv, am;
        long n;
        const char *arm;
        if ((st = tsv_text(t, r, "arm", &arm))) break;
        if (strcmp(arm, "coupled")) continue;
        if ((st = tsv_double(t, r, "level", &lv)) || (st = tsv_double(t, r, "aniso_median", &am)) || (st = tsv_long(t, r, "aniso_trees", &n))) break;
        tsv_writer_dbl(w, lv);
        tsv_writer_dbl(w, am);
        tsv_writer_long(w, n);
        tsv_writer_endrow(w);
    }
    tsv_free(t);
    if (st) { tsv_writer_abort(w); return fs_die("aniso-jitter-calibrate", st); }
    if ((st = tsv_writer_commit(w))) return fs_die("aniso-jitter-calibrate", st);
    fs_calibration c;
    if ((st = fs_jitter_star(o.out, &c))) return fs_die("aniso-jitter-calibrate", st);
    printf("aniso-jitter-calibrate: field median %.3f, a interpolated %.6f, a* %.2f%s\n", c.target, c.interp, c.value,
           c.bracketed ? "" : " (FIELD MEDIAN NOT BRACKETED by the sweep: nearest end)");
    return 0;
}

int cmd_aniso_heldout(int argc, char **argv)
{
    fs_opts o = {.stands_opt = 28};
    const opt_spec spec[] = {
        FS_OPT_CAL(o),
        {"jitter-calibration", OPT_STR, &o.jitter_calibration, 0, 0, "E6 jitter calibration table DIR/jitter_calibration.tsv, gives a* (required)"},
        FS_OPT_OUT(o),
        FS_OPT_STANDS(o, "stands (default 28)"),
    };
    const opts_cmd oc = {"aniso-heldout",
                         "--calibration DIR/calibration.tsv --jitter-calibration DIR/jitter_calibration.tsv\n"
                         "                              --out DIR/heldout.tsv [--stands N]",
                         "E6 held-out (SPEC §7): N stands (default 28) at jitter a* on seeds disjoint from the sweep,\n"
                         "teacher at beta_field: anisotropy, elongation, spread; every stand must build.",
                         spec, sizeof spec / sizeof *spec, 0, 0};
    int rc = fs_parse(&oc, argc, argv, &o);
    if (rc) return opts_exit_code(rc);
    if (!o.jitter_calibration) { opts_usage_error("aniso-heldout", "--jitter-calibration is required (a*)"); return 2; }
    fs_calibration c, js;
    if ((rc = need_beta("aniso-heldout", &o, &c))) return rc;
    cs_status st = fs_jitter_star(o.jitter_calibration, &js);
    if (st) return fs_die("aniso-heldout", st);
    prov p;
    prov_begin(&p, "anisotropy", argc, argv);
    fs_job j = {"anisotropy/heldout", STAND_LATTICE, js.value, js.value, c.value, o.stands, 0, 0};
    fs_trees acc;
    fs_trees_init(&acc);
    double worst = 0;
    st = fs_run_job(&j, &acc, &worst);
    snprintf(p.seeds, sizeof p.seeds, "seed_derive(\"anisotropy/heldout\", 5.0, s, stems|crowns), s = 0..%u", o.stands - 1);
    p.worst_overlap_m = worst;
    meta_ctx m = {c.value, js.value, "E6 held-out at a*: lattice d = 5 m, L = 60 m, jitter a* (level), teacher at beta_field"};
    if (!st) st = fs_write(o.out, &p, &acc, &j, 1, meta_generic, &m);
    if (!st) {
        fs_summary s;
        if (!fs_group(&acc, 1, js.value, &s))
            printf("aniso-heldout: a* %.2f: anisotropy median %.4f (%zu trees, %zu excluded), elongation %.4f, spread %.4f m; %zu of %u stands built\n",
                   js.value, s.f.aniso_median, s.f.aniso_trees, s.f.aniso_excluded, s.elong_median, s.f.spread, s.stands, o.stands);
        print_spread_ratios("aniso-heldout", &acc, js.value, 0);
    }
    fs_trees_free(&acc);
    return st ? fs_die("aniso-heldout", st) : 0;
}

/* -------------------------------------------------------- diagnosis ---- */

/* Why the elongation and anisotropy gates fail (printed, not frozen): the
 * open-grown crown targets (SPEC §3) and the two knobs' reach. */
int cmd_field_diagnose(int argc, char **argv)
{
    fs_opts o = {.stands_opt = 12};
    const opt_spec spec[] = {FS_OPT_CAL(o), FS_OPT_STANDS(o, "stands of the perfect lattice (default 12)")};
    const opts_cmd oc = {"field-diagnose", "--calibration DIR/calibration.tsv [--stands N]",
                         "Print diagnostics for the E5/E6 verdicts: elongation of the open-grown crown targets\n"
                         "(by lobe count k), the reach of beta over the calibration grid (elongation, anisotropy),\n"
                         "and the anisotropy of a perfect lattice (a = 0) at beta_field (N stands, default 12,\n"
                         "seeds 'field/diagnose'). Nothing is written.",
                         spec, sizeof spec / sizeof *spec, 0, 0};
    int rc = fs_parse(&oc, argc, argv, &o);
    if (rc) return opts_exit_code(rc);
    fs_calibration c;
    if ((rc = need_beta("field-diagnose", &o, &c))) return rc;
    double d = DESIGN_FIELD_SPACING_M, L = FS_L_FACTOR * d, a;
    cs_status st = fs_canonical_jitter(&a);
    if (st) return fs_die("field-diagnose", st);
    /* 1. open-grown target elongation on the E5 held-out stands' draws */
    size_t n[6] = {0}, ge[6] = {0}, tot = 0, totge = 0;
    double emax = 0, lo;
    if ((st = gate_read_value(PATHS_GATE("field"), "elongation_band", 0, &lo))) return fs_die("field-diagnose", st);
    for (unsigned s = 0; s < o.stands && !st; s++) {
        stand *sd;
        if ((st = stand_alloc(&sd, STAND_LATTICE, d, L, a, "field/heldout", s))) break;
        for (size_t i = 0; i < sd->s->n; i++) {
            double e = est_elongation(sd->rstar + i * CROWN_NSEC);
            int k = sd->draw[i].k;
            n[k]++; tot++;
            if (e >= lo) { ge[k]++; totge++; }
            if (e > emax) emax = e;
        }
        stand_free(sd);
    }
    if (st) return fs_die("field-diagnose", st);
    printf("open-grown targets (%zu crowns): max elongation %.4f; share >= %.2f: %.4f\n", tot, emax, lo, (double)totge / (double)tot);
    for (int k = 2; k <= 5; k++)
        printf("  lobe count k = %d: %zu crowns, share >= %.2f: %.4f\n", k, n[k], lo, n[k] ? (double)ge[k] / (double)n[k] : 0.0);
    /* 2. reach of beta: calibration grid */
    tsv *t;
    fs_trees tr;
    if ((st = fs_load_checked(o.calibration, &t, &tr))) return fs_die("field-diagnose", st);
    fs_trees_free(&tr);
    double emx = 0, amn = INFINITY, bea = 0, baa = 0;
    for (size_t r = 0; r < tsv_nrows(t) && !st; r++) {
        double b, e, an;
        if ((st = tsv_double(t, r, "beta", &b)) || (st = tsv_double(t, r, "elong_median", &e)) || (st = tsv_double(t, r, "aniso_median", &an))) break;
        if (e > emx) { emx = e; bea = b; }
        if (an < amn) { amn = an; baa = b; }
    }
    tsv_free(t);
    if (st) return fs_die("field-diagnose", st);
    printf("calibration grid: largest median elongation %.4f (beta %.2f); smallest median anisotropy %.4f (beta %.2f)\n", emx, bea, amn, baa);
    /* 3. a perfect lattice at beta_field */
    fs_trees acc;
    fs_trees_init(&acc);
    fs_job j = {"field/diagnose", STAND_LATTICE, 0.0, 0.0, c.value, o.stands, 0, 0};
    double worst = 0;
    st = fs_run_job(&j, &acc, &worst);
    fs_summary sm;
    if (!st) st = fs_group(&acc, 1, 0.0, &sm);
    fs_trees_free(&acc);
    if (st) return fs_die("field-diagnose", st);
    printf("perfect lattice (a = 0) at beta_field %.2f, %u stands: median anisotropy %.4f (%zu trees), tree-mean median %.4f m, elongation %.4f\n",
           c.value, o.stands, sm.f.aniso_median, sm.f.aniso_trees, sm.f.tree_mean_median, sm.elong_median);
    return 0;
}
