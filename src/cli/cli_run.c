/* cli_run: `crownshy run <unit>` (the teacher experiments' units of E1, E2
 * and the figure stands, one process per make target of experiments.mk) and
 * `crownshy bench-teacher`. Only the CLI decides how the process dies. */
#include "afile.h"
#include "model_readings.h"
#include "cli.h"
#include "exp_irred.h"
#include "exp_mechanism.h"
#include "exp_stands.h"
#include "gate.h"
#include "opts.h"
#include "paths.h"
#include "readings.h"
#include "stand_grow.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef enum { U_PLAIN, U_IRRED } unit_kind;
typedef struct {
    const char *name;
    unit_kind kind;
    cs_status (*plain)(const exp_opts *);
    cs_status (*irred)(const exp_opts *, double);
    const char *help;
} run_unit;

static const run_unit UNITS[] = {
    {"mechanism-sweep", U_PLAIN, exp_mechanism_sweep, NULL, "E1: 16 rows beta x d on the controlled lattice -> mechanism/sweep.tsv"},
    {"mechanism-ablation", U_PLAIN, exp_mechanism_ablation, NULL, "E1: coupling off / abrasion off / both on at 3.5 m -> mechanism/ablation.tsv"},
    {"irreducibility-perturb", U_IRRED, NULL, exp_irred_perturb, "E2: one tree 30% taller, 5 spacings -> irreducibility/perturb_<tag>.tsv"},
    {"irreducibility-refine", U_IRRED, NULL, exp_irred_refine, "E2: N in {48,96,192,384} -> irreducibility/refine_<tag>.tsv"},
    {"irreducibility-reduction", U_IRRED, NULL, exp_irred_reduction, "E2: best-fit Voronoi reduction -> irreducibility/reduction_<tag>.tsv"},
    {"fig-mechanism", U_PLAIN, exp_mechanism_figure, NULL, "crowns of the three mechanism panels (hard-core, 3.5 m, L = 36 m)"},
    {"fig-hero", U_PLAIN, exp_hero_figure, NULL, "crowns of the hero figure (hard-core, L = 36 m, d = 3.0..6.5)"},
    {"fig-pointcloud", U_PLAIN, exp_pointcloud_figure, NULL, "E8: point-cloud stands (5/4/3 m, + uncoupled) and pointcloud/stats.tsv"},
};
#define NUNITS (sizeof UNITS / sizeof UNITS[0])

int cli_cmd_run(int argc, char **argv)
{
    long stands = EXP_STANDS_DEFAULT;
    double beta = NAN;
    const char *out = "build/results", *tag = "train", *teacher = NULL;
    const opt_spec spec[] = {
        {"stands", OPT_LONG, &stands, 1, 10000, "stands per cell (default 8)"},
        {"out", OPT_STR, &out, 0, 0, "results root; each unit writes DIR/<experiment>/<file>.tsv (default build/results)"},
        {"beta", OPT_DOUBLE, &beta, 0, 0.999, "die-back for E2 and the hero's beta_field row (default: the gate's dieback_train; no beta_field row)"},
        {"tag", OPT_STR, &tag, 0, 0, "E2 output tag: train or field (default train; field needs --beta)"},
        EXP_OPT_TEACHER(teacher),
    };
    char about[2048];
    size_t off = (size_t)snprintf(about, sizeof about, "units:\n");
    for (size_t i = 0; i < NUNITS && off < sizeof about; i++)
        off += (size_t)snprintf(about + off, sizeof about - off, "  %-26s %s\n", UNITS[i].name, UNITS[i].help);
    const opts_cmd c = {"run", "<unit> [options]", about, spec, sizeof spec / sizeof *spec, 1, 1};
    char *pos[argc > 0 ? argc : 1];
    int r = opts_parse(&c, argc, argv, pos, NULL);
    if (r) return opts_exit_code(r);
    const run_unit *u = NULL;
    for (size_t i = 0; i < NUNITS; i++)
        if (!strcmp(pos[0], UNITS[i].name)) u = &UNITS[i];
    if (!u) { opts_usage_error("run", "unknown unit '%s'", pos[0]); return 2; }
    if (strcmp(tag, "train") && strcmp(tag, "field")) { opts_usage_error("run", "--tag: must be train or field, not '%s'", tag); return 2; }
    exp_opts o = {.out = out, .stands = (int)stands, .beta = beta, .tag = tag, .argc = argc, .argv = argv};
    if (exp_reading_parse(teacher, NULL, &o.rd)) { opts_usage_error("run", "%s", cs_errmsg()); return 2; }
    cs_status st = CS_OK;
    if (u->kind == U_IRRED) {
        double b = beta;
        if (isnan(b)) {
            if (!strcmp(tag, "field")) { opts_usage_error("run", "--tag field needs --beta (the calibrated field die-back)"); return 2; }
            st = gate_read_value(PATHS_GATE("mechanism"), "dieback_train", 0, &b);
        }
        if (!st) st = u->irred(&o, b);
    } else st = u->plain(&o);
    if (st) fprintf(stderr, "crownshy run %s: %s\n", u->name, cs_errmsg()[0] ? cs_errmsg() : cs_status_name(st));
    return cs_exit_code(st);
}

int cli_cmd_bench_teacher(int argc, char **argv)
{
    long reps = 10;
    const opt_spec spec[] = {{"reps", OPT_LONG, &reps, 1, 10000, "stands timed at N = 48 (a quarter of them at N = 384; default 10)"}};
    const opts_cmd c = {"bench-teacher", "[--reps N]",
                        "Teacher ms per 144-tree controlled-lattice stand (d = 3.5 m, beta 0.06) at N = 48 and N = 384 (design.md §10).",
                        spec, 1, 0, 0};
    int r = opts_parse(&c, argc, argv, NULL, NULL);
    if (r) return opts_exit_code(r);
    const int levels[2] = {48, 384};
    for (int k = 0; k < 2; k++) {
        double ms = 0.0;
        cs_status st = stand_grow_bench(levels[k], k ? (int)(reps + 3) / 4 : (int)reps, &ms);
        if (st) { fprintf(stderr, "crownshy bench-teacher: %s\n", cs_errmsg()); return cs_exit_code(st); }
        printf("teacher_ms_per_stand_N%d\t%.3f\n", levels[k], ms);
    }
    return 0;
}

/* E0 readings summary (design.md §7 E0): one row per quantity and reading from
 * the runs under --dir (readings.h), with the paper's value and the
 * relative difference; prints the within-10 %/25 % counts per reading. */
int cli_cmd_readings_summary(int argc, char **argv)
{
    const char *dir = NULL, *out = NULL;
    const opt_spec spec[] = {
        {"dir", OPT_STR, &dir, 0, 0, "readings root holding t1-r1/, t2-r1/, t1-r2/, t2-r2/ (required)"},
        {"out", OPT_STR, &out, 0, 0, "summary table (required), e.g. DIR/summary.tsv"},
    };
    const opts_cmd c = {"readings-summary", "--dir DIR --out DIR/summary.tsv",
                        "E0 readings: recompute every quantity of the readings table from each run's tables with the\n"
                        "registry's computing functions, beside the reference paper's value (audit/claims.tsv).",
                        spec, 2, 0, 0};
    int r = opts_parse(&c, argc, argv, NULL, NULL);
    if (r) return opts_exit_code(r);
    if (!dir || !out) { opts_usage_error("readings-summary", "--dir and --out are required"); return 2; }
    claims cl;
    cs_status st = claims_load(PATHS_CLAIMS, &cl);
    if (st) { fprintf(stderr, "crownshy readings-summary: %s\n", cs_errmsg()); return cs_exit_code(st); }
    size_t n = readings_count(), nr;
    readings_row *rows = calloc(n, sizeof *rows);
    st = rows ? readings_compute(&cl, dir, rows) : cs_err(CS_ENOMEM, "out of memory");
    if (!st) st = readings_write(out, dir, rows, n);
    if (!st) {
        const readings_def *d = readings_list(&nr);
        for (size_t k = 0; k < nr; k++) {
            size_t m, a, b;
            readings_within(rows, n, d[k].name, &m, &a, &b);
            printf("%-11s %zu of %zu within 10 %%, %zu within 25 %% of the reference paper\n", d[k].name, a, m, b);
        }
    }
    free(rows);
    claims_free(&cl);
    if (st) { fprintf(stderr, "crownshy readings-summary: %s\n", cs_errmsg()); return cs_exit_code(st); }
    return 0;
}

/* The generator readings table (design.md §8; src/claims/model_readings.h). */
int cli_cmd_model_readings(int argc, char **argv)
{
    const char *dir = NULL, *out = NULL;
    const opt_spec spec[] = {
        {"dir", OPT_STR, &dir, 0, 0, "results or frozen root holding paper/, extension-pair/, model-readings/ (required)"},
        {"out", OPT_STR, &out, 0, 0, "table FILE.tsv (required), e.g. DIR/model-readings/summary.tsv"},
    };
    const opts_cmd c = {"model-readings", "--dir DIR --out FILE.tsv",
                        "E3/E4 generator readings: per reading that has run, seeds, parameters, joint, independent and\n"
                        "direction-blind errors, relative improvement, Wilcoxon p, probe ratios, extrapolation advantage, steps/s.",
                        spec, 2, 0, 0};
    int r = opts_parse(&c, argc, argv, NULL, NULL);
    if (r) return opts_exit_code(r);
    if (!dir || !out) { opts_usage_error("model-readings", "--dir and --out are required"); return 2; }
    model_readings_row rows[4];
    size_t n = 0;
    cs_status st = model_readings_compute(dir, rows, &n);
    if (!st && !n) st = cs_err(CS_EINPUT, "%s: no reading has a main/runs.tsv", dir);
    if (!st) st = afile_mkdir_parents(out);
    if (!st) st = model_readings_write(out, dir, rows, n, argc, argv);
    for (size_t i = 0; !st && i < n; i++)
        printf("%-13s %-11s seeds %2d  joint %.4f  indep %.4f  rel %.1f %%  p %.5f  shuffle x%.2f\n", rows[i].reading, rows[i].role,
               rows[i].seeds, rows[i].joint, rows[i].indep, 100 * rows[i].rel, rows[i].p, rows[i].shuf_joint);
    if (st) { fprintf(stderr, "crownshy model-readings: %s\n", cs_errmsg()); return cs_exit_code(st); }
    return 0;
}
