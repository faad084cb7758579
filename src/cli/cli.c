/* crownshy: the one command-line entry point (design.md §11): the table of
 * commands, grouped by who runs them. The experiments' commands come from the
 * manifest (src/base/manifest.h): a COMMAND row names its handler, a RUN
 * row an experiment's entry that cli_run_unit parses for; the others are
 * listed here. Every argv
 * table is in src/cli: cli_audit.c (reviewing and maintaining), cli_model.c
 * (the generator), cli_run.c (the teacher units, bench-teacher,
 * readings-summary), cli_main.c (E3/E4, E7), cli_field.c (E5, E6). Only the
 * CLI decides how the process dies, and cli_fail is its one failure printer;
 * library calls return a cs_status. */
#include "cli.h"
#include "opts.h"
#include "teacher.h"
#include "afile.h"
#include <signal.h>
#include <stdio.h>
#include <string.h>

/* the handler of every experiment command, declared from the manifest */
#define COMMAND(name, command, handler, help) int handler(int argc, char **argv);
#define RUN(name, command, entry, takes, help) cs_status entry(const exp_opts *o);
#include "manifest.h"

typedef int (*cmd_fn)(int argc, char **argv);
typedef enum { G_REVIEW, G_STUDY, G_MAINTAIN } cmd_group;
/* fn, or for a RUN row of the manifest: the unit's entry, what it takes and its experiment */
typedef struct {
    const char *name;
    cmd_fn fn;
    cmd_group group;
    const char *help;
    cs_status (*entry)(const exp_opts *);
    const char *takes, *experiment;
} cli_cmd;

const char *const CLI_ARMS[] = {"joint", "indep", "independent=indep", NULL};
const char *const CLI_TEACHERS[] = {TEACHER_VERSION,
                                    TEACHER_VERSION_ONE_SIDED,
                                    TEACHER_VERSION "-arc",
                                    TEACHER_VERSION "-target",
                                    TEACHER_VERSION_ONE_SIDED "-arc",
                                    TEACHER_VERSION_ONE_SIDED "-target",
                                    NULL};
const char *const CLI_LAYOUTS[] = {"4m-on-36m", "5m-on-60m", NULL};

int cli_fail(const char *cmd, cs_status st)
{
    fprintf(stderr, "crownshy %s: %s\n", cmd, cs_errmsg()[0] ? cs_errmsg() : cs_status_name(st));
    return cs_exit_code(st);
}

static int cli_cmd_version(int argc, char **argv)
{
    const opts_cmd c = {"version", "", "Print the version.", NULL, 0, 0, 0};
    int r = opts_parse(&c, argc, argv, NULL, NULL);
    if (r) return opts_exit_code(r);
    puts("crownshy 0.1");
    return 0;
}

static const cli_cmd cli_cmds[] = {
    {"verify", cli_cmd_verify, G_REVIEW, "audit, recompute every claim, judge the gates, redraw the figures (start here)"},
    {"report", cli_cmd_report, G_REVIEW, "the reproduction summary: paper vs ours with its 95 % interval, gate, agreement class"},
    {"trace", cli_cmd_trace, G_REVIEW, "one paper macro: its value, frozen file, computing function, gate, test"},
    {"audit", cli_cmd_audit, G_REVIEW, "the audit alone: pins, frozen hashes, provenance, registry, paper files"},
    {"gates", cli_cmd_gates, G_REVIEW, "parse and list the preregistered gate files"},
    {"check-tsv", cli_cmd_check_tsv, G_REVIEW, "validate frozen TSV files"},
#define COMMAND(name, command, handler, help) {command, handler, G_STUDY, help},
#define RUN(name, command, entry, takes, help) {command, NULL, G_STUDY, help, entry, takes, #name},
#include "manifest.h"
    {"train", cli_cmd_train, G_STUDY, "train the flow-matching generator on toy stands (a trainer check; E3 trains with main-run)"},
    {"sample", cli_cmd_sample, G_STUDY, "generate crowns with a checkpoint of train (100 Euler steps)"},
    {"numbers", cli_cmd_numbers, G_MAINTAIN, "regenerate paper/numbers.tex, comparison.tex, readings.tex from frozen/ (--check: compare only)"},
    {"figures", cli_cmd_figures, G_MAINTAIN, "redraw every figure from frozen/, install it into figures/ when its script succeeded"},
    {"pin", cli_cmd_pin, G_MAINTAIN, "re-pin the estimator, teacher, gates and claim code (deliberate)"},
    {"hash-frozen", cli_cmd_hash_frozen, G_MAINTAIN, "record the hashes of frozen/ (make freeze)"},
    {"claims-table", cli_cmd_claims_table, G_MAINTAIN, "write audit/claims.tsv, the print of the claim tables (--check: compare only)"},
    {"bench-teacher", cli_cmd_bench_teacher, G_MAINTAIN, "teacher ms per 144-tree stand at N = 48 and 384 (make bench)"},
    {"bench-model", cli_cmd_bench_model, G_MAINTAIN, "trainer steps/s, model and sgemm GFLOP/s (design.md §10; make bench)"},
    {"version", cli_cmd_version, G_MAINTAIN, "print the version"},
};
#define NCMDS (sizeof cli_cmds / sizeof cli_cmds[0])

static void usage(FILE *f)
{
    static const char *const groups[] = {
        "reviewing the package (start with `crownshy verify`, or `make verify`)",
        "running the study (one command per make unit; `make reproduce` runs them all, `make <experiment>` one "
        "experiment)",
        "maintaining the package",
    };
    fprintf(f, "usage: crownshy <command> [options]   (crownshy <command> --help)\n");
    for (int g = G_REVIEW; g <= G_MAINTAIN; g++) {
        fprintf(f, "\n%s:\n", groups[g]);
        for (size_t i = 0; i < NCMDS; i++)
            if (cli_cmds[i].group == (cmd_group)g) fprintf(f, "  %-27s %s\n", cli_cmds[i].name, cli_cmds[i].help);
    }
    fprintf(
        f,
        "\nexit codes: 0 ok, 1 a check failed, 2 usage error, 3 bad or missing input, 4 environment (I/O, memory)\n");
}

int cli_main(int argc, char **argv)
{
    cs_gsl_install();
    /* past the file-size limit a write then fails (EFBIG) and is reported as
     * an environment error, its temporary file removed, instead of the
     * process being killed mid-write */
    signal(SIGXFSZ, SIG_IGN);
    /* a run cancelled (scancel, a time limit, Ctrl-C) leaves no temp file */
    afile_remove_on_signal();
    if (argc < 2) { usage(stderr); return 2; }
    if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") || !strcmp(argv[1], "help")) {
        usage(stdout);
        return 0;
    }
    for (size_t i = 0; i < NCMDS; i++)
        if (!strcmp(argv[1], cli_cmds[i].name)) {
            const cli_cmd *c = &cli_cmds[i];
            return c->fn ? c->fn(argc - 1, argv + 1)
                         : cli_run_unit(c->experiment, c->name, c->entry, c->takes, c->help, argc - 1, argv + 1);
        }
    fprintf(stderr, "crownshy: unknown command '%s'\n", argv[1]);
    usage(stderr);
    return 2;
}
