/* cli: the command handlers of `crownshy <command>` (design.md §11). Each returns
 * the process exit code: 0 ok, 1 a check failed, 2 usage error, 3 bad or
 * missing input, 4 environment (I/O, memory). Options are parsed by opts.h. */
#ifndef CLI_H
#define CLI_H
#include "cs.h"
#include "exp_common.h"

/* cli_audit.c */
int cli_cmd_verify(int argc, char **argv);
int cli_cmd_numbers(int argc, char **argv);
int cli_cmd_audit(int argc, char **argv);
int cli_cmd_trace(int argc, char **argv);
int cli_cmd_report(int argc, char **argv);
int cli_cmd_pin(int argc, char **argv);
int cli_cmd_hash_frozen(int argc, char **argv);
int cli_cmd_claims_table(int argc, char **argv);
int cli_cmd_gates(int argc, char **argv);
int cli_cmd_check_tsv(int argc, char **argv);
int cli_cmd_figures(int argc, char **argv);
/* cli_model.c */
int cli_cmd_train(int argc, char **argv);
int cli_cmd_sample(int argc, char **argv);
int cli_cmd_bench_model(int argc, char **argv);
/* cli_run.c (and the teacher units' handlers, declared from src/base/manifest.h) */
int cli_cmd_bench_teacher(int argc, char **argv);

/* The arms of the generator, one vocabulary for every command: joint, indep
 * (independent is accepted for indep). An OPT_CHOICE list (opts.h). */
extern const char *const CLI_ARMS[];
/* The readings of the teacher (teacher-2, the adopted mutual abrasion;
 * teacher-1, one-sided die-back; design.md §4) and of the field layout
 * (4m-on-36m, 5m-on-60m; design.md §7 E5), one vocabulary for every
 * command that takes them. */
extern const char *const CLI_TEACHERS[];
extern const char *const CLI_LAYOUTS[];
#define CLI_OPT_TEACHER(var) {"teacher", OPT_CHOICE, &(var), 0, 0, "teacher reading (default teacher-2, design.md §4; -arc, -target: the other die-back readings)", .choices = CLI_TEACHERS}
#define CLI_OPT_VARY(var) {"vary", OPT_STR, &(var), 0, 0, "sensitivity: NAME=VALUE changes one unstated choice (crownshy sensitivity-run --help lists them)"}
#define CLI_OPT_LAYOUT(var) {"layout", OPT_CHOICE, &(var), 0, 0, "field layout: lattice spacing on footprint side (default 4m-on-36m, design.md §7 E5)", .choices = CLI_LAYOUTS}

/* The whole command line: dispatch argv[1] to its handler (cli.c). */
int cli_main(int argc, char **argv);
/* "crownshy CMD: <cs_errmsg>" on stderr; the exit code of st. */
int cli_fail(const char *cmd, cs_status st);
/* The argv table shared by the RUN rows of src/base/manifest.h (cli_run.c):
 * --out DIR, --teacher, --vary and what `takes` names ("stands", "beta",
 * "tag", "rows"; "-" none), then entry; the exit code of the command.
 * name: the experiment (its tables under DIR/<name>/); help: its --help line. */
int cli_run_unit(const char *name, const char *cmd, cs_status (*entry)(const exp_opts *), const char *takes,
                 const char *help, int argc, char **argv);

#endif
