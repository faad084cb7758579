/* cli_run: the argv tables of the teacher experiments' commands (E1, E2, E8,
 * E9: one process per make unit of src/base/manifest.h), `crownshy
 * bench-teacher` and `crownshy readings-summary`. Only the CLI decides how the
 * process dies. */
#include "cli.h"
#include "exp_irreducibility.h"
#include "gate.h"
#include "opts.h"
#include "paths.h"
#include "readings.h"
#include "stand_grow.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* What a teacher unit's table takes besides --out and --teacher. */
enum { U_STANDS = 1, U_BETA = 2, U_TAG = 4, U_ROWS = 8 };

typedef struct {
    const char *cmd, *about;
    int takes;                                    /* U_* */
    cs_status (*plain)(const exp_opts *);         /* or: */
    cs_status (*irred)(const exp_opts *, double); /* E2: at one die-back */
} teacher_unit;

static int teacher_unit_run(const teacher_unit *u, int argc, char **argv)
{
    long stands = EXP_STANDS_DEFAULT;
    double beta = NAN;
    const char *out = "build/results", *tag = "train", *teacher = NULL, *vary = NULL;
    int rows = 0;
    opt_spec spec[7];
    size_t n = 0;
    spec[n++] =
        (opt_spec){"out", OPT_STR, &out,
                   0,     0,       "results root; the unit writes DIR/<experiment>/<file>.tsv (default build/results)"};
    spec[n++] = (opt_spec)CLI_OPT_TEACHER(teacher);
    spec[n++] = (opt_spec)CLI_OPT_VARY(vary);
    if (u->takes & U_STANDS)
        spec[n++] = (opt_spec){"stands", OPT_LONG, &stands, 1, 10000, "stands per cell (default 8)"};
    if (u->takes & U_BETA)
        spec[n++] = (opt_spec){"beta",
                               OPT_DOUBLE,
                               &beta,
                               0,
                               0.999,
                               u->irred ? "die-back (default: the gate's dieback_train)"
                                        : "beta_field: adds its row (default: no beta_field row)"};
    if (u->takes & U_TAG)
        spec[n++] =
            (opt_spec){"tag", OPT_STR, &tag, 0, 0, "output tag: train or field (default train; field needs --beta)"};
    if (u->takes & U_ROWS)
        spec[n++] = (opt_spec){
            "stand-rows",
            OPT_FLAG,
            &rows,
            0,
            0,
            "also write the per-stand rows the pooled table is made of (<table>_stands/_sectors/_trees.tsv)"};
    const opts_cmd c = {u->cmd, "[options]", u->about, spec, n, 0, 0};
    int r = opts_parse(&c, argc, argv, NULL, NULL);
    if (r) return opts_exit_code(r);
    if (strcmp(tag, "train") && strcmp(tag, "field")) {
        opts_usage_error(u->cmd, "--tag: must be train or field, not '%s'", tag);
        return 2;
    }
    exp_opts o = {
        .out = out, .stands = (int)stands, .beta = beta, .tag = tag, .stand_rows = rows, .argc = argc, .argv = argv};
    if (exp_reading_parse(teacher, NULL, &o.rd) || exp_reading_vary(vary, &o.rd)) {
        opts_usage_error(u->cmd, "%s", cs_errmsg());
        return 2;
    }
    cs_status st = CS_OK;
    if (u->irred) {
        double b = beta;
        if (isnan(b)) {
            if (!strcmp(tag, "field")) {
                opts_usage_error(u->cmd, "--tag field needs --beta (the calibrated field die-back)");
                return 2;
            }
            st = gate_read_value(PATHS_GATE("mechanism"), "dieback_train", 0, &b);
        }
        if (!st) st = u->irred(&o, b);
    } else st = u->plain(&o);
    return st ? cli_fail(u->cmd, st) : 0;
}

int cli_run_unit(const char *name, const char *cmd, cs_status (*entry)(const exp_opts *), const char *takes,
                 const char *help, int argc, char **argv)
{
    static const struct { const char *word; int flag; } words[] = {
        {"stands", U_STANDS}, {"beta", U_BETA}, {"tag", U_TAG}, {"rows", U_ROWS}};
    int flags = 0;
    for (const char *w = strcmp(takes, "-") ? takes : ""; *w;) {
        size_t n = strcspn(w, " "), k = 0;
        while (k < sizeof words / sizeof *words && (strlen(words[k].word) != n || strncmp(w, words[k].word, n))) k++;
        if (k == sizeof words / sizeof *words)
            return cli_fail(cmd, cs_err(CS_EINVARIANT, "src/base/manifest.h: RUN %s: takes '%.*s' is not one of "
                                                       "stands, beta, tag, rows", cmd, (int)n, w));
        flags |= words[k].flag;
        w += n + strspn(w + n, " ");
    }
    char about[512];
    snprintf(about, sizeof about, "%s\n-> DIR/%s/ (the tables its UNIT rows in src/base/manifest.h name)", help, name);
    const teacher_unit u = {cmd, about, flags, entry, NULL};
    return teacher_unit_run(&u, argc, argv);
}

int cli_irreducibility_perturb(int argc, char **argv)
{
    static const teacher_unit u = {
        "irreducibility-perturb",
        "E2: one tree 30% taller, 5 spacings -> DIR/irreducibility/perturb_<tag>.tsv (and _stands.tsv)",
        U_STANDS | U_BETA | U_TAG | U_ROWS, NULL, exp_irreducibility_perturb};
    return teacher_unit_run(&u, argc, argv);
}

int cli_irreducibility_refine(int argc, char **argv)
{
    static const teacher_unit u = {"irreducibility-refine",
                                   "E2: N in {48,96,192,384} -> DIR/irreducibility/refine_<tag>.tsv (and _sectors.tsv)",
                                   U_STANDS | U_BETA | U_TAG | U_ROWS, NULL, exp_irreducibility_refine};
    return teacher_unit_run(&u, argc, argv);
}

int cli_irreducibility_reduction(int argc, char **argv)
{
    static const teacher_unit u = {
        "irreducibility-reduction",
        "E2: best-fit Voronoi reduction -> DIR/irreducibility/reduction_<tag>.tsv (and _sectors.tsv)",
        U_STANDS | U_BETA | U_TAG | U_ROWS, NULL, exp_irreducibility_reduction};
    return teacher_unit_run(&u, argc, argv);
}

int cli_cmd_bench_teacher(int argc, char **argv)
{
    long reps = 11;
    const opt_spec spec[] = {{"reps", OPT_LONG, &reps, 1, 10000,
                              "stands timed at N = 48 (a third of them, at least 3, at N = 384; default 11)"}};
    const opts_cmd c = {
        "bench-teacher",
        "[--reps N]",
        "Teacher CPU ms per 144-tree controlled-lattice stand (d = 3.5 m, beta 0.06) at N = 48 and N = 384,\n"
        "median [fastest, slowest] over stands each timed alone (design.md §10).",
        spec, 1, 0, 0};
    int r = opts_parse(&c, argc, argv, NULL, NULL);
    if (r) return opts_exit_code(r);
    const int levels[2] = {48, 384};
    for (int k = 0; k < 2; k++) {
        double ms[3];
        const int n = k ? (int)(reps + 2) / 3 < 3 ? 3 : (int)(reps + 2) / 3 : (int)reps;
        cs_status st = stand_grow_bench(levels[k], n, ms);
        if (st) return cli_fail("bench-teacher", st);
        printf("teacher_ms_per_stand_N%d\t%.3f\t[%.3f, %.3f]\t(%d stands)\n", levels[k], ms[0], ms[1], ms[2], n);
    }
    return 0;
}

/* E0 readings summary (design.md §7 E0): one row per quantity and reading from
 * the runs under --dir (readings.h), with the paper's value and the
 * relative difference; prints the within-10 %/25 % counts per reading. */
int cli_readings_summary(int argc, char **argv)
{
    const char *dir = NULL, *out = NULL;
    const opt_spec spec[] = {
        {"dir", OPT_STR, &dir, 0, 0, "readings root holding one-sided-60m/, mutual-60m/, one-sided-36m/, mutual-36m/, arc-36m/ (required)"},
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
    cs_status st = claims_registry(&cl);
    if (st) return cli_fail("readings-summary", st);
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
    if (st) return cli_fail("readings-summary", st);
    return 0;
}
