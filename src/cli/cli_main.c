/* cli_main: the argv tables of E3/E4 (main-run, main-redraw, main-baselines,
 * main-summary) and E7 (comparison-run); each fills its experiment's args
 * and calls the entry point (src/exp/exp_main.h, exp_comp.h). */
#include "cli.h"
#include "exp_comp.h"
#include "exp_main.h"
#include "opts.h"

static const char *const SCALES[] = {"full", "smoke", NULL};

int cli_main_run(int argc, char **argv)
{
    long seed = 0, pair = 1;
    exp_main_run_args a = {.scale = "full", .argc = argc, .argv = argv};
    const opt_spec spec[] = {
        {"seed", OPT_LONG, &seed, 1, 4294967295.0, "model seed (zero-padded 01 is 1)", .required = 1},
        {"arm", OPT_CHOICE, &a.arm, 0, 0, "the model's arm", .required = 1, .choices = CLI_ARMS},
        {"out", OPT_STR, &a.out, 0, 0, "output table FILE.tsv", .required = 1},
        {"scale", OPT_CHOICE, &a.scale, 0, 0, "the plan's scale (default full)", .choices = SCALES},
        {"ckpt", OPT_STR, &a.ckpt, 0, 0, "checkpoint FILE, resumed from when it exists (default none)"},
        {"samples", OPT_STR, &a.samples, 0, 0, "also write the clearance samples behind every W1 to FILE.tsv (default none)"},
        {"weights", OPT_STR, &a.weights, 0, 0, "also write the final weights to FILE (weights format, README; default none)"},
        {"epochs", OPT_LONG, &a.epochs, 1, 1000000, "exploration override of the plan's epochs (default: the plan's)"},
        {"train-stands", OPT_LONG, &a.train_stands, 1, 10000, "exploration override of the plan's stands per training spacing (default: the plan's)"},
        {"pair", OPT_LONG, &pair, 0, 1, "1: the pair-aware model of design.md §8, every probe on both arms; 0: the plain model (default 1)"},
    };
    const opts_cmd c = {"main-run", "--seed S --arm joint|indep --out FILE.tsv [options]",
                        "One (seed, arm) unit of E3/E4: build teacher data, train the flow model (resuming from\n"
                        "--ckpt if it exists), evaluate W1 of focal nearest-neighbour clearances at the unseen and\n"
                        "extrapolation spacings, as generated and under the shuffled-geometry and rotation probes,\n"
                        "write FILE.tsv (and the samples and weights behind it).",
                        spec, sizeof spec / sizeof *spec, 0, 0};
    int r = opts_parse(&c, argc, argv, NULL, NULL);
    if (r) return opts_exit_code(r);
    a.seed = (unsigned)seed;
    a.pair = (int)pair;
    cs_status st = exp_main_run(&a);
    return st ? cli_fail("main-run", st) : 0;
}

int cli_main_redraw(int argc, char **argv)
{
    long seed = 0;
    exp_main_redraw_args a = {.scale = "full", .argc = argc, .argv = argv};
    const opt_spec spec[] = {
        {"weights", OPT_STR, &a.weights, 0, 0, "weights FILE written by main-run --weights (or its checkpoint)", .required = 1},
        {"seed", OPT_LONG, &seed, 1, 4294967295.0, "model seed of the unit", .required = 1},
        {"arm", OPT_CHOICE, &a.arm, 0, 0, "the arm (must match the weights)", .required = 1, .choices = CLI_ARMS},
        {"out", OPT_STR, &a.out, 0, 0, "output samples FILE.tsv", .required = 1},
        {"scale", OPT_CHOICE, &a.scale, 0, 0, "the plan's scale (default full)", .choices = SCALES},
    };
    const opts_cmd c = {"main-redraw", "--weights FILE --seed S --arm joint|indep --out FILE.tsv [--scale full|smoke]",
                        "Draw the clearance samples of one E3/E4 unit again from its weights, without training:\n"
                        "the data rows of FILE.tsv equal those of the unit's samples_s<seed>_<arm>.tsv bit for bit.",
                        spec, sizeof spec / sizeof *spec, 0, 0};
    int r = opts_parse(&c, argc, argv, NULL, NULL);
    if (r) return opts_exit_code(r);
    a.seed = (unsigned)seed;
    cs_status st = exp_main_redraw(&a);
    return st ? cli_fail("main-redraw", st) : 0;
}

int cli_main_baselines(int argc, char **argv)
{
    exp_main_baselines_args a = {.scale = "full", .argc = argc, .argv = argv};
    const opt_spec spec[] = {
        {"out", OPT_STR, &a.out, 0, 0, "output table FILE.tsv", .required = 1},
        {"scale", OPT_CHOICE, &a.scale, 0, 0, "the plan's scale (default full)", .choices = SCALES},
        {"samples", OPT_STR, &a.samples, 0, 0, "also write the clearance samples behind every W1 to FILE.tsv (default none)"},
    };
    const opts_cmd c = {"main-baselines", "--out FILE.tsv [--scale full|smoke] [--samples FILE.tsv]",
                        "Direction-blind baseline (every crown replaced by its circular mean), split-half noise floor\n"
                        "of the teacher, and the teacher's own crowns under the shuffled-geometry and rotation probes\n"
                        "(added after the first verdict), as W1 of focal nearest-neighbour clearances per eval spacing.",
                        spec, sizeof spec / sizeof *spec, 0, 0};
    int r = opts_parse(&c, argc, argv, NULL, NULL);
    if (r) return opts_exit_code(r);
    cs_status st = exp_main_baselines(&a);
    return st ? cli_fail("main-baselines", st) : 0;
}

int cli_main_summary(int argc, char **argv)
{
    long seeds = 0;
    exp_main_summary_args a = {.argc = argc, .argv = argv};
    const opt_spec spec[] = {
        {"dir", OPT_STR, &a.dir, 0, 0, "results root RESULTS", .required = 1},
        {"seeds", OPT_LONG, &seeds, 1, 64, "seeds 1..N to gather", .required = 1},
    };
    const opts_cmd c = {"main-summary", "--dir RESULTS --seeds N",
                        "Read RESULTS/main/run_s<seed>_<arm>.tsv for seeds 1..N and both arms; write\n"
                        "RESULTS/main/runs.tsv (per-run errors) and RESULTS/extrapolation/runs.tsv.",
                        spec, sizeof spec / sizeof *spec, 0, 0};
    int r = opts_parse(&c, argc, argv, NULL, NULL);
    if (r) return opts_exit_code(r);
    a.seeds = (int)seeds;
    cs_status st = exp_main_summary(&a);
    return st ? cli_fail("main-summary", st) : 0;
}

int cli_comparison_run(int argc, char **argv)
{
    exp_comp_args a = {.argc = argc, .argv = argv};
    const opt_spec spec[] = {
        {"joint", OPT_STR, &a.joint, 0, 0, "joint-arm weights (or checkpoint) CKPT of E3 seed 1", .required = 1},
        {"indep", OPT_STR, &a.indep, 0, 0, "independent-arm weights (or checkpoint) CKPT of E3 seed 1", .required = 1},
        {"out", OPT_STR, &a.out, 0, 0, "results root DIR", .required = 1},
    };
    const opts_cmd c = {"comparison-run", "--joint CKPT --indep CKPT --out DIR",
                        "E7: one 24-tree patch at 5.0 m (teacher, joint, independent arm) and the dart probe\n"
                        "(joint model on hard-core stems); writes DIR/comparison/{patch,patch_crowns,dart_probe}.tsv.",
                        spec, sizeof spec / sizeof *spec, 0, 0};
    int r = opts_parse(&c, argc, argv, NULL, NULL);
    if (r) return opts_exit_code(r);
    cs_status st = exp_comp_run(&a);
    return st ? cli_fail("comparison-run", st) : 0;
}
