/* cli_sens: the argv tables of the E0 sensitivity (design.md §7 E0
 * "sensitivity"): `crownshy sensitivity-run`, one unit = one unstated choice
 * (src/base/unstated.h) at one value, or the centre run (src/exp/exp_sensitivity.h,
 * handed this CLI's dispatcher to run the unit's steps); and
 * `crownshy sensitivity-summary`, the table over all units (src/claims/sens.h). */
#include "cli.h"
#include "exp_sensitivity.h"
#include "opts.h"
#include "paths.h"
#include "sens.h"
#include "unstated.h"
#include <stdio.h>
#include <stdlib.h>

int cli_sensitivity_run(int argc, char **argv)
{
    exp_sensitivity_args x = {
        .stands = 4, .field_stands = 28, .sweep_stands = 12, .run = cli_main, .argc = argc, .argv = argv};
    const opt_spec spec[] = {
        {"unit", OPT_STR, &x.unit, 0, 0, "the unit: centre, or <choice>_<value> with a value of the list below", .required = 1},
        {"out", OPT_STR, &x.out, 0, 0, "the unit's folder, e.g. build/results/sensitivity/crown_R_3", .required = 1},
        {"stands", OPT_LONG, &x.stands, 1, 10000, "E1/E2 stands per cell (default 4)"},
        {"field-stands", OPT_LONG, &x.field_stands, 1, 10000, "E5/E6 held-out and lattice stands (default 28)"},
        {"sweep-stands", OPT_LONG, &x.sweep_stands, 1, 10000, "E6 stands per sweep level (default 12)"},
    };
    char about[2048];
    size_t off =
        (size_t)snprintf(about, sizeof about,
                         "One E0 sensitivity unit (design.md §7 E0): the cheap teacher experiments with one unstated\n"
                         "choice changed (every other pinned), into DIR; resumable (tables present are kept). Units:\n"
                         "  centre         every choice ours\n");
    size_t nc;
    const unstated_choice *cl = unstated_list(&nc);
    for (size_t i = 0; i < nc && off < sizeof about; i++) {
        off += (size_t)snprintf(about + off, sizeof about - off, "  %s_<v>, ours %g, v in", cl[i].name, cl[i].ours);
        for (int k = 0; k < cl[i].nvalues && off < sizeof about; k++)
            off += (size_t)snprintf(about + off, sizeof about - off, " %g", cl[i].values[k]);
        if (off < sizeof about) off += (size_t)snprintf(about + off, sizeof about - off, ": %s\n", cl[i].what);
    }
    const opts_cmd oc = {
        "sensitivity-run", "--unit UNIT --out DIR [--stands N]", about, spec, sizeof spec / sizeof *spec, 0, 0};
    int r = opts_parse(&oc, argc, argv, NULL, NULL);
    if (r) return opts_exit_code(r);
    cs_status st = exp_sensitivity_run(&x);
    return st ? cli_fail("sensitivity-run", st) : 0;
}

int cli_sensitivity_summary(int argc, char **argv)
{
    const char *dir = NULL, *out = NULL;
    const opt_spec spec[] = {
        {"dir", OPT_STR, &dir, 0, 0, "sensitivity root holding centre/ and <choice>_<value>/", .required = 1},
        {"out", OPT_STR, &out, 0, 0, "the table, e.g. DIR/summary.tsv", .required = 1},
    };
    const opts_cmd oc = {"sensitivity-summary", "--dir DIR --out DIR/summary.tsv",
                         "E0 sensitivity: every quantity of the sensitivity table under the centre run and each\n"
                         "(choice, value), recomputed from the units' tables by the registry's computing functions.",
                         spec, sizeof spec / sizeof *spec, 0, 0};
    int r = opts_parse(&oc, argc, argv, NULL, NULL);
    if (r) return opts_exit_code(r);
    claims cl;
    cs_status st = claims_registry(&cl);
    if (st) return cli_fail("sensitivity-summary", st);
    size_t n = sens_count();
    sens_row *rows = calloc(n, sizeof *rows);
    st = rows ? sens_compute(&cl, dir, rows) : cs_err(CS_ENOMEM, "out of memory");
    if (!st) st = sens_write(out, dir, rows, n);
    if (!st) printf("sensitivity-summary: %zu rows -> %s\n", n, out);
    free(rows);
    claims_free(&cl);
    return st ? cli_fail("sensitivity-summary", st) : 0;
}
