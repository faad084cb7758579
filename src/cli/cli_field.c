/* cli_field: the argv tables of E5 (field-*) and E6 (anisotropy-*): each
 * fills exp_field_opts and calls its entry point (src/exp/exp_field.h,
 * exp_anisotropy.h). */
#include "cli.h"
#include "exp_anisotropy.h"
#include "exp_field.h"
#include "fieldrun.h"
#include "opts.h"
#include <stdio.h>

#define OPT_OUT(o) {"out", OPT_STR, &(o).out, 0, 0, "output table", .required = 1}
#define OPT_CAL(o)                                                                                                     \
    {                                                                                                                  \
        "calibration", OPT_STR, &(o).calibration, 0, 0, "E5 calibration table DIR/calibration.tsv, gives beta_field",  \
            .required = 1                                                                                              \
    }
#define OPT_STANDS(o, help) {"stands", OPT_LONG, &(o).stands_opt, 1, 10000, help}
#define OPT_READING(o) CLI_OPT_TEACHER((o).teacher), CLI_OPT_LAYOUT((o).layout), CLI_OPT_VARY((o).vary)

/* opts_parse, then the reading from --teacher/--layout; an opts result. */
static int field_parse(const opts_cmd *c, int argc, char **argv, exp_field_opts *o)
{
    int r = opts_parse(c, argc, argv, NULL, NULL);
    if (r) return r;
    o->stands = (unsigned)o->stands_opt;
    o->argc = argc;
    o->argv = argv;
    if (exp_reading_parse(o->teacher, o->layout, &o->rd) || exp_reading_vary(o->vary, &o->rd)) {
        opts_usage_error(c->cmd, "%s", cs_errmsg());
        return OPTS_USAGE;
    }
    return OPTS_OK;
}

int cli_field_calibrate(int argc, char **argv)
{
    exp_field_opts o = {0};
    const opt_spec spec[] = {OPT_OUT(o), OPT_READING(o)};
    const opts_cmd oc = {
        "field-calibrate",
        "--out DIR/calibration.tsv",
        "E5 calibration (design.md §7): grow the calibration stands (gates/field.gate calibration_seeds)\n"
        "at every beta of dieback_grid, record the median tree-mean clearance per beta, and print\n"
        "beta_field (interpolated to calibration_target_m, rounded to the grid). Also writes\n"
        "DIR/calibration_trees.tsv.",
        spec, sizeof spec / sizeof *spec, 0, 0};
    int r = field_parse(&oc, argc, argv, &o);
    if (r) return opts_exit_code(r);
    cs_status st = exp_field_calibrate(&o);
    return st ? cli_fail("field-calibrate", st) : 0;
}

int cli_field_heldout(int argc, char **argv)
{
    exp_field_opts o = {.stands_opt = 28};
    const opt_spec spec[] = {OPT_CAL(o), OPT_OUT(o), OPT_STANDS(o, "stands (default 28)"), OPT_READING(o)};
    const opts_cmd oc = {
        "field-heldout",
        "--calibration DIR/calibration.tsv --out DIR/heldout.tsv [--stands N]",
        "E5 held-out (design.md §7): N stands (default 28) on seeds disjoint from the calibration, grown at\n"
        "beta_field coupled and as the uncoupled twin: tree-mean median, spread, elongation, anisotropy.\n"
        "The spread ratios need the raw field table (FIELD_TABLE=path); without it they are pending.",
        spec, sizeof spec / sizeof *spec, 0, 0};
    int r = field_parse(&oc, argc, argv, &o);
    if (r) return opts_exit_code(r);
    cs_status st = exp_field_heldout(&o);
    return st ? cli_fail("field-heldout", st) : 0;
}

int cli_field_diagnose(int argc, char **argv)
{
    exp_field_opts o = {.stands_opt = 12};
    const opt_spec spec[] = {OPT_CAL(o), OPT_STANDS(o, "stands of the perfect lattice (default 12)"), OPT_READING(o)};
    const opts_cmd oc = {"field-diagnose", "--calibration DIR/calibration.tsv [--stands N]",
                         "Print diagnostics for the E5/E6 verdicts: elongation of the open-grown crown targets\n"
                         "(by lobe count k), the reach of beta over the calibration grid (elongation, anisotropy),\n"
                         "and the anisotropy of a perfect lattice (a = 0) at beta_field (N stands, default 12,\n"
                         "seeds 'field/diagnose'). Nothing is written.",
                         spec, sizeof spec / sizeof *spec, 0, 0};
    int r = field_parse(&oc, argc, argv, &o);
    if (r) return opts_exit_code(r);
    cs_status st = exp_field_diagnose(&o);
    return st ? cli_fail("field-diagnose", st) : 0;
}

int cli_anisotropy_lattice(int argc, char **argv)
{
    exp_field_opts o = {.stands_opt = 28};
    const opt_spec spec[] = {OPT_CAL(o), OPT_OUT(o), OPT_STANDS(o, "stands (default 28)"), OPT_READING(o)};
    const opts_cmd oc = {
        "anisotropy-lattice",
        "--calibration DIR/calibration.tsv --out DIR/lattice.tsv [--stands N]",
        "E6 (design.md §7): anisotropy on the controlled lattice (field layout, canonical jitter) at beta_field,\n"
        "N stands (default 28).",
        spec, sizeof spec / sizeof *spec, 0, 0};
    int r = field_parse(&oc, argc, argv, &o);
    if (r) return opts_exit_code(r);
    cs_status st = exp_anisotropy_lattice(&o);
    return st ? cli_fail("anisotropy-lattice", st) : 0;
}

int cli_anisotropy_jitter_calibrate(int argc, char **argv)
{
    exp_field_opts o = {0};
    const opt_spec spec[] = {
        {"sweep", OPT_STR, &o.sweep, 0, 0, "E6 jitter sweep table DIR/jitter.tsv", .required = 1},
        OPT_OUT(o),
    };
    const opts_cmd oc = {"anisotropy-jitter-calibrate", "--sweep DIR/jitter.tsv --out DIR/jitter_calibration.tsv",
                         "E6: the jitter sweep's median anisotropy per level (checked against the per-tree table) and\n"
                         "a* = linear interpolation to anisotropy.gate field_median, rounded to 0.01.",
                         spec, sizeof spec / sizeof *spec, 0, 0};
    int r = field_parse(&oc, argc, argv, &o);
    if (r) return opts_exit_code(r);
    cs_status st = exp_anisotropy_jitter_calibrate(&o);
    return st ? cli_fail("anisotropy-jitter-calibrate", st) : 0;
}

int cli_anisotropy_heldout(int argc, char **argv)
{
    exp_field_opts o = {.stands_opt = 28};
    const opt_spec spec[] = {
        OPT_CAL(o),
        {"jitter-calibration", OPT_STR, &o.jitter_calibration, 0, 0, "E6 jitter calibration table DIR/jitter_calibration.tsv, gives a*", .required = 1},
        OPT_OUT(o),
        OPT_STANDS(o, "stands (default 28)"),
        OPT_READING(o),
    };
    const opts_cmd oc = {
        "anisotropy-heldout",
        "--calibration DIR/calibration.tsv --jitter-calibration DIR/jitter_calibration.tsv\n"
        "                              --out DIR/heldout.tsv [--stands N]",
        "E6 held-out (design.md §7): N stands (default 28) at jitter a* on seeds disjoint from the sweep,\n"
        "teacher at beta_field: anisotropy, elongation, spread; every stand must build.",
        spec, sizeof spec / sizeof *spec, 0, 0};
    int r = field_parse(&oc, argc, argv, &o);
    if (r) return opts_exit_code(r);
    cs_status st = exp_anisotropy_heldout(&o);
    return st ? cli_fail("anisotropy-heldout", st) : 0;
}

static int aniso_family(const char *cmd, const char *synopsis, const char *about,
                        cs_status (*run)(const exp_field_opts *), int argc, char **argv)
{
    exp_field_opts o = {.stands_opt = 12};
    const opt_spec spec[] = {OPT_CAL(o), OPT_OUT(o), OPT_STANDS(o, "stands per level (default 12)"), OPT_READING(o)};
    const opts_cmd oc = {cmd, synopsis, about, spec, sizeof spec / sizeof *spec, 0, 0};
    int r = field_parse(&oc, argc, argv, &o);
    if (r) return opts_exit_code(r);
    cs_status st = run(&o);
    return st ? cli_fail(cmd, st) : 0;
}

int cli_anisotropy_hardcore(int argc, char **argv)
{
    return aniso_family(
        "anisotropy-hardcore", "--calibration DIR/calibration.tsv --out DIR/hardcore.tsv [--stands N]",
        "E6 hard-core family (design.md §7): stems by random sequential addition with minimum distance c d,\n"
        "c in anisotropy.gate hardcore_levels, N stands per level (default 12), teacher at beta_field.\n"
        "A level whose stands cannot be built is recorded (stands_failed, trees 0), not a crash.",
        exp_anisotropy_hardcore, argc, argv);
}

int cli_anisotropy_jitter(int argc, char **argv)
{
    return aniso_family("anisotropy-jitter", "--calibration DIR/calibration.tsv --out DIR/jitter.tsv [--stands N]",
                        "E6 jitter family (design.md §7): controlled lattice with per-axis jitter sd a d, a in\n"
                        "anisotropy.gate jitter_levels, N stands per level (default 12), teacher at beta_field.",
                        exp_anisotropy_jitter, argc, argv);
}

int cli_field_summary(int argc, char **argv)
{
    const opts_cmd oc = {"field-summary", "[TABLE.tsv]",
                         "Summarise a raw field table (default: $FIELD_TABLE): trees, measurements, tree-mean\n"
                         "median clearance, spread (IQR of all cardinal gaps), anisotropy median (+ excluded),\n"
                         "with the canonical estimator's functions, next to the published figures of\n"
                         "frozen/field/reference.tsv. Columns: tree, direction (E/N/W/S or east/north/west/south),\n"
                         "clearance_m; each tree needs each direction exactly once. Exit 3 on a bad table.",
                         NULL, 0, 0, 1};
    char *pos[argc > 0 ? argc : 1];
    int npos = 0, r = opts_parse(&oc, argc, argv, pos, &npos);
    if (r) return opts_exit_code(r);
    cs_status st = exp_field_summary(npos ? pos[0] : NULL);
    return st ? cli_fail("field-summary", st) : 0;
}

int cli_field_beta(int argc, char **argv)
{
    const opts_cmd oc = {"field-beta", "DIR/calibration.tsv",
                         "Print beta_field (%.17g) recomputed from an E5 calibration table (used by the make units\n"
                         "that rerun E2 at the field operating point).",
                         NULL, 0, 1, 1};
    char *pos[argc > 0 ? argc : 1];
    int r = opts_parse(&oc, argc, argv, pos, NULL);
    if (r) return opts_exit_code(r);
    cs_status st = exp_field_beta(pos[0]);
    return st ? cli_fail("field-beta", st) : 0;
}
