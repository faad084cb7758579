/* exp_sensitivity: one unit of the E0 sensitivity (design.md §7 E0
 * "sensitivity"): the cheap teacher experiments with one unstated choice
 * (src/base/unstated.h) at one value, or the centre run (the design's
 * values), into one folder. The unit runs the same commands as the full
 * run, each with --vary NAME=VALUE, through the runner it is handed (the
 * CLI's dispatcher: the commands are the experiments' own, so their tables
 * are the full run's under the choice); it imports no experiment's code. The
 * summary over the units is a claim computation (src/claims/sens.h). The
 * entry point (argv table: src/cli/cli_sens.c). */
#ifndef EXP_SENSITIVITY_H
#define EXP_SENSITIVITY_H
#include "cs.h"

/* Runs one command line (argv[0] "crownshy"); returns its process exit code
 * (design.md §11). */
typedef int (*exp_sensitivity_runner)(int argc, char **argv);

typedef struct {
    const char *unit;      /* centre, or <choice>_<value> (unstated_dirname) */
    const char *out;       /* the unit's folder */
    long stands;           /* E1/E2 stands per cell */
    long field_stands;     /* E5/E6 held-out and lattice stands */
    long sweep_stands;     /* E6 stands per sweep level */
    exp_sensitivity_runner run;
    int argc;              /* the command line, for the provenance */
    char **argv;
} exp_sensitivity_args;

/* Build every table of the unit the choice can change (unstated_touches)
 * that is not yet present (resumable), then <out>/unit.tsv, the make target:
 * where each table of the variant lives, and why a table could not be built.
 * A step that exits 3 or 4 (a stand the choice cannot build, a statistic it
 * leaves undefined) is a finding of the choice: recorded, the other steps
 * still run. CS_EUSAGE for an unknown unit; a step failing otherwise stops
 * the unit with that step's status. */
cs_status exp_sensitivity_run(const exp_sensitivity_args *a);

#endif
