/* crownshy: the one command-line entry point (design.md §11): the table of
 * commands. Handlers live in cli_audit.c (reviewer and auditor), cli_model.c
 * (generator), cli_run.c (teacher units and bench) and with their experiment
 * (exp_main, exp_comp, exp_field, exp_aniso). Only the CLI decides how the
 * process dies; library calls return a cs_status. */
#include "cli.h"
#include "exp_aniso.h"
#include "exp_comp.h"
#include "exp_compdist.h"
#include "exp_field.h"
#include "exp_main.h"
#include "mainsum.h"
#include "opts.h"
#include <stdio.h>
#include <string.h>

typedef int (*cmd_fn)(int argc, char **argv);
typedef struct { const char *name; cmd_fn fn; const char *help; } cli_cmd;

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
    {"figures", cli_cmd_figures, "redraw every figure with gnuplot from frozen data"},
    {"main-run", exp_main_cmd_run, "E3/E4: one (seed, arm) training + evaluation unit"},
    {"main-baselines", mainsum_cmd_baselines, "E3/E4: direction-blind baseline and noise floor"},
    {"main-summary", mainsum_cmd_summary, "E3/E4: gather runs into frozen tables"},
    {"main-redraw", exp_main_cmd_redraw, "E3/E4: draw a unit's clearance samples again from its frozen weights"},
    {"main-train", exp_main_cmd_train, "E3/E4: train one (seed, arm, reading) unit: weights and training table"},
    {"main-eval", exp_main_cmd_eval, "E3/E4: evaluate one unit from its weights, without training: run table and samples"},
    {"comp-run", exp_comp_cmd_run, "E7: comparison patch (teacher, joint, independent) and dart probe"},
    {"comp-dist", exp_compdist_cmd_run, "E7: the comparison patch and the dart probe as distributions over fresh patches"},
    {"model-readings", cli_cmd_model_readings, "E3/E4: the generator readings table from the runs under --dir (design.md §8)"},
    {"readings-summary", cli_cmd_readings_summary, "E0: the readings table from the runs under --dir (design.md §7 E0)"},
    {"bench-teacher", cli_cmd_bench_teacher, "teacher ms per 144-tree stand at N = 48 and 384"},
    {"run", cli_cmd_run, "run one experiment unit of E1/E2/figure data (crownshy run --help)"},
    {"gates", cli_cmd_gates, "parse and list the preregistered gate files"},
    {"check-tsv", cli_cmd_check_tsv, "validate frozen TSV files"},
    {"verify", cli_cmd_verify, "audit, recompute every claim, judge gates, redraw figures"},
    {"numbers", cli_cmd_numbers, "regenerate paper/numbers.tex from frozen/"},
    {"audit", cli_cmd_audit, "check pins, frozen hashes, provenance, registry and paper"},
    {"trace", cli_cmd_trace, "trace one macro to its value, file, function, gate and test"},
    {"pin", cli_cmd_pin, "re-pin the estimator, teacher and gates (deliberate)"},
    {"hash-frozen", cli_cmd_hash_frozen, "record the hashes of frozen/ (make freeze)"},
    {"field-summary", cmd_field_summary, "summarise a raw field table (FIELD_TABLE) with the canonical estimator"},
    {"field-calibrate", cmd_field_calibrate, "E5: calibrate die-back beta to the field tree-mean median clearance"},
    {"field-beta", cmd_field_beta, "E5: print beta_field from a calibration table"},
    {"field-heldout", cmd_field_heldout, "E5: held-out spread, elongation and uncoupled control at beta_field"},
    {"aniso-lattice", cmd_aniso_lattice, "E6: anisotropy on the controlled lattice at beta_field"},
    {"aniso-hardcore", cmd_aniso_hardcore, "E6: hard-core stem family sweep"},
    {"aniso-jitter", cmd_aniso_jitter, "E6: jitter-amplitude family sweep"},
    {"aniso-jitter-calibrate", cmd_aniso_jitter_calibrate, "E6: calibrate jitter a* to the field anisotropy median"},
    {"aniso-heldout", cmd_aniso_heldout, "E6: held-out stands at a*"},
    {"field-diagnose", cmd_field_diagnose, "E5/E6: diagnostics for the elongation and anisotropy verdicts"},
    {"version", cli_cmd_version, "print the version"},
    {"train", cli_cmd_train, "train the flow-matching generator (toy stands for now)"},
    {"sample", cli_cmd_sample, "generate crowns with a trained checkpoint (100 Euler steps)"},
    {"bench-model", cli_cmd_bench_model, "trainer steps/s, model and sgemm GFLOP/s (design.md §10)"},
};
#define NCMDS (sizeof cli_cmds / sizeof cli_cmds[0])

static void usage(FILE *f)
{
    fprintf(f, "usage: crownshy <command> [options]   (crownshy <command> --help)\n\ncommands:\n");
    for (size_t i = 0; i < NCMDS; i++) fprintf(f, "  %-16s %s\n", cli_cmds[i].name, cli_cmds[i].help);
    fprintf(f, "\nexit codes: 0 ok, 1 a check failed, 2 usage error, 3 bad or missing input, 4 environment (I/O, memory)\n");
}

int cli_main(int argc, char **argv)
{
    cs_gsl_install();
    if (argc < 2) { usage(stderr); return 2; }
    if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") || !strcmp(argv[1], "help")) {
        usage(stdout);
        return 0;
    }
    for (size_t i = 0; i < NCMDS; i++)
        if (!strcmp(argv[1], cli_cmds[i].name)) return cli_cmds[i].fn(argc - 1, argv + 1);
    fprintf(stderr, "crownshy: unknown command '%s'\n", argv[1]);
    usage(stderr);
    return 2;
}
