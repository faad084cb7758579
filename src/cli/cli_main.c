/* cli_main: the argv tables of E3/E4 (main-run, main-train, main-eval,
 * main-redraw, main-baselines, main-summary), the generator readings table
 * (model-readings-summary) and E7 (comparison-run, comparison-dist); each
 * fills its experiment's args and calls the entry point (src/exp/exp_main.h,
 * mainsum.h, exp_comp.h, exp_compdist.h; src/claims/model_readings.h). */
#include "cli.h"
#include "exp_comp.h"
#include "exp_common.h"
#include "exp_main.h"
#include "exp_compdist.h"
#include "genprobe.h"
#include "claim_probe.h"
#include "mainsum.h"
#include "evalvol.h"
#include "model_readings.h"
#include "afile.h"
#include <stdio.h>
#include "opts.h"

static const char *const SCALES[] = {"full", "smoke", NULL};

static const char *const READINGS[] = {"plain", "paper", "paper-fourier", "pair", NULL};
static const char *const VOLUMES[] = {EVALVOL_SMALL, EVALVOL_LARGE, NULL};
static const char *const PROBES[] = {"generated", "shuffled", "rotated", NULL};

#define UNIT_OPTS(a, seed) \
    {"seed", OPT_LONG, &seed, 1, 4294967295.0, "model seed (zero-padded 01 is 1)", .required = 1}, \
    {"arm", OPT_CHOICE, &(a).arm, 0, 0, "the model's arm", .required = 1, .choices = CLI_ARMS}, \
    {"scale", OPT_CHOICE, &(a).scale, 0, 0, "the plan's scale (default full)", .choices = SCALES}
#define TRAIN_OPTS(a, pair) \
    {"ckpt", OPT_STR, &(a).ckpt, 0, 0, "checkpoint FILE, resumed from when it exists (default none)"}, \
    {"epochs", OPT_LONG, &(a).epochs, 1, 1000000, "exploration override of the plan's epochs (default: the plan's)"}, \
    {"train-stands", OPT_LONG, &(a).train_stands, 1, 10000, "exploration override of the plan's stands per training spacing (default: the plan's)"}, \
    {"width", OPT_LONG, &(a).width, 8, 1024, "model width (a multiple of the 4 heads; MLP 4 x width; default the reference 64)"}, \
    {"blocks", OPT_LONG, &(a).blocks, 1, 64, "transformer blocks (default the reference 3)"}, \
    {"lr", OPT_DOUBLE, &(a).lr, 1e-6, 1.0, "peak learning rate (default the plan's 2e-3)"}, \
    {"reading", OPT_CHOICE, &(a).reading, 0, 0, "generator reading (model.h, design.md §8; default pair)", .choices = READINGS}, \
    {"pair", OPT_LONG, &pair, 0, 1, "1: the pair reading; 0: the plain reading (short for --reading pair | plain)"}

int cli_main_run(int argc, char **argv)
{
    long seed = 0, pair = -1;
    int cost = 0;
    exp_main_run_args a = {.scale = "full", .argc = argc, .argv = argv};
    const opt_spec spec[] = {
        UNIT_OPTS(a, seed), TRAIN_OPTS(a, pair),
        {"out", OPT_STR, &a.out, 0, 0, "output table FILE.tsv", .required = 1},
        {"samples", OPT_STR, &a.samples, 0, 0, "also write the clearance samples behind every W1 to FILE.tsv (default none)"},
        {"weights", OPT_STR, &a.weights, 0, 0, "also write the final weights to FILE (weights format, README; default none)"},
        {"volume", OPT_CHOICE, &a.volume, 0, 0, "evaluation volume, named by its teacher stands per spacing (src/exp/mainrun.h; default " EVALVOL_SMALL ")", .choices = VOLUMES},
        {"cost", OPT_FLAG, &cost, 0, 0, "run nothing: print the unit's model FLOPs (training, evaluation) and this core's rates for its model (make bench's study cost)"},
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
    if (cost) {
        exp_main_cost k;
        cs_status st = exp_main_run_cost(&a, &k);
        if (st) return cli_fail("main-run", st);
        const double cpu = (k.train_gflops > 0 ? k.train_flops / k.train_gflops / 1e9 : 0) +
                           (k.sample_gflops > 0 ? k.eval_flops / k.sample_gflops / 1e9 : 0);
        printf("unit_cost\ttrain_flops %.17g\teval_flops %.17g\ttrain_gflops %.3f\tsample_gflops %.3f\tcpu_s %.3f\n",
               k.train_flops, k.eval_flops, k.train_gflops, k.sample_gflops, cpu);
        return 0;
    }
    cs_status st = exp_main_run(&a);
    return st ? cli_fail("main-run", st) : 0;
}

int cli_main_train(int argc, char **argv)
{
    long seed = 0, pair = -1;
    exp_main_run_args a = {.scale = "full", .argc = argc, .argv = argv};
    const opt_spec spec[] = {
        UNIT_OPTS(a, seed), TRAIN_OPTS(a, pair),
        {"out", OPT_STR, &a.out, 0, 0, "output training table FILE.tsv", .required = 1},
        {"weights", OPT_STR, &a.weights, 0, 0, "final weights FILE (weights format, README)", .required = 1},
    };
    const opts_cmd c = {"main-train", "--seed S --arm joint|indep --weights FILE --out FILE.tsv [options]",
                        "Train one (seed, arm) unit of E3/E4 (resuming from --ckpt if it exists) and write its weights\n"
                        "and a training table; `crownshy main-eval` evaluates the weights.",
                        spec, sizeof spec / sizeof *spec, 0, 0};
    int r = opts_parse(&c, argc, argv, NULL, NULL);
    if (r) return opts_exit_code(r);
    a.seed = (unsigned)seed;
    a.pair = (int)pair;
    cs_status st = exp_main_train(&a);
    return st ? cli_fail("main-train", st) : 0;
}

int cli_main_eval(int argc, char **argv)
{
    long seed = 0;
    exp_main_run_args a = {.scale = "full", .pair = -1, .argc = argc, .argv = argv};
    const opt_spec spec[] = {
        UNIT_OPTS(a, seed),
        {"weights", OPT_STR, &a.weights, 0, 0, "weights FILE written by main-run/main-train --weights (or its checkpoint)", .required = 1},
        {"trained", OPT_STR, &a.trained, 0, 0, "the unit's training or run table, whose model, training, teacher and commit lines are recorded", .required = 1},
        {"out", OPT_STR, &a.out, 0, 0, "output run table FILE.tsv", .required = 1},
        {"samples", OPT_STR, &a.samples, 0, 0, "also write the clearance samples behind every W1 to FILE.tsv (default none)"},
        {"volume", OPT_CHOICE, &a.volume, 0, 0, "evaluation volume, named by its teacher stands per spacing (src/exp/mainrun.h; default " EVALVOL_SMALL ")", .choices = VOLUMES},
        {"reading", OPT_CHOICE, &a.reading, 0, 0, "the reading the weights must be (default: any)", .choices = READINGS},
    };
    const opts_cmd c = {"main-eval",
                        "--weights FILE --trained TABLE --seed S --arm joint|indep --out FILE.tsv [options]",
                        "Evaluate one E3/E4 unit from its weights, without training: the run table and samples of\n"
                        "main-run at the chosen volume (at the volume main-run used: the data rows of its table, bit for bit).",
                        spec, sizeof spec / sizeof *spec, 0, 0};
    int r = opts_parse(&c, argc, argv, NULL, NULL);
    if (r) return opts_exit_code(r);
    a.seed = (unsigned)seed;
    cs_status st = exp_main_eval(&a);
    return st ? cli_fail("main-eval", st) : 0;
}

int cli_main_redraw(int argc, char **argv)
{
    long seed = 0;
    int cost = 0;
    exp_main_run_args a = {.scale = "full", .pair = -1, .argc = argc, .argv = argv};
    const opt_spec spec[] = {
        {"weights", OPT_STR, &a.weights, 0, 0, "weights FILE written by main-run --weights (or its checkpoint)", .required = 1},
        {"seed", OPT_LONG, &seed, 1, 4294967295.0, "model seed of the unit", .required = 1},
        {"arm", OPT_CHOICE, &a.arm, 0, 0, "the arm (must match the weights)", .required = 1, .choices = CLI_ARMS},
        {"out", OPT_STR, &a.out, 0, 0, "output samples FILE.tsv (required unless --cost)"},
        {"scale", OPT_CHOICE, &a.scale, 0, 0, "the plan's scale (default full)", .choices = SCALES},
        {"volume", OPT_CHOICE, &a.volume, 0, 0, "evaluation volume, named by its teacher stands per spacing (src/exp/mainrun.h; default " EVALVOL_SMALL ")", .choices = VOLUMES},
        {"cost", OPT_FLAG, &cost, 0, 0, "draw nothing: print the redraw's model FLOPs, this core's sampling rate for the model and their quotient (make verify-deep's projection)"},
        {"spacing", OPT_DOUBLE, &a.only_spacing, 0.5, 100, "draw this evaluation spacing (m) alone (default every one)"},
        {"probe", OPT_CHOICE, &a.only_probe, 0, 0, "draw this probe alone (default every one)", .choices = PROBES},
        {"patches", OPT_LONG, &a.only_patches, 1, 1e6, "draw only the first N generated patches of each spacing and probe (default the plan's)"},
    };
    const opts_cmd c = {"main-redraw",
                        "--weights FILE --seed S --arm joint|indep --out FILE.tsv [--scale full|smoke] "
                        "[--volume 16-stands|96-stands] [--spacing D] [--probe P] [--patches N] [--cost]",
                        "Draw the clearance samples of one E3/E4 unit again from its weights, without training:\n"
                        "the data rows of FILE.tsv equal those of the unit's samples_s<seed>_<arm>.tsv bit for bit.\n"
                        "With --spacing and --probe only that slice is drawn (the spacing's teacher rows and the\n"
                        "probe's generated rows), with --patches only its first N patches: equal to those rows of\n"
                        "the whole (the spot check of make verify).",
                        spec, sizeof spec / sizeof *spec, 0, 0};
    int r = opts_parse(&c, argc, argv, NULL, NULL);
    if (r) return opts_exit_code(r);
    a.seed = (unsigned)seed;
    if (cost) {
        double flops = 0, gflops = 0;
        cs_status st = exp_main_redraw_cost(&a, &flops, &gflops);
        if (st) return cli_fail("main-redraw", st);
        printf("redraw_cost\tflops %.17g\tgflops %.3f\tcpu_s %.3f\n", flops, gflops,
               gflops > 0 ? flops / gflops / 1e9 : 0.0);
        return 0;
    }
    cs_status st = exp_main_redraw(&a);
    return st ? cli_fail("main-redraw", st) : 0;
}

int cli_main_baselines(int argc, char **argv)
{
    mainsum_baselines_args a = {.scale = "full", .argc = argc, .argv = argv};
    const opt_spec spec[] = {
        {"out", OPT_STR, &a.out, 0, 0, "output table FILE.tsv", .required = 1},
        {"scale", OPT_CHOICE, &a.scale, 0, 0, "the plan's scale (default full)", .choices = SCALES},
        {"samples", OPT_STR, &a.samples, 0, 0, "also write the clearance samples behind every W1 to FILE.tsv (default none)"},
        CLI_OPT_VARY(a.vary),
        {"volume", OPT_CHOICE, &a.volume, 0, 0, "evaluation volume, named by its teacher stands per spacing (src/exp/mainrun.h; default " EVALVOL_SMALL ")", .choices = VOLUMES},
        {"stand-rows", OPT_FLAG, &a.stand_rows, 0, 0, "also write baselines_stands.tsv beside FILE: the patches of each evaluation stand"},
    };
    const opts_cmd c = {"main-baselines",
                        "--out FILE.tsv [--scale full|smoke] [--volume 16-stands|96-stands] [--samples FILE.tsv]",
                        "Direction-blind baseline (every crown replaced by its circular mean), split-half noise floor\n"
                        "of the teacher, and the teacher's own crowns under the shuffled-geometry and rotation probes\n"
                        "(added after the first verdict), as W1 of focal nearest-neighbour clearances per eval spacing.",
                        spec, sizeof spec / sizeof *spec, 0, 0};
    int r = opts_parse(&c, argc, argv, NULL, NULL);
    if (r) return opts_exit_code(r);
    cs_status st = mainsum_baselines(&a);
    return st ? cli_fail("main-baselines", st) : 0;
}

int cli_main_summary(int argc, char **argv)
{
    long seeds = 0;
    mainsum_summary_args a = {.argc = argc, .argv = argv};
    const opt_spec spec[] = {
        {"dir", OPT_STR, &a.dir, 0, 0, "a reading's results root RESULTS", .required = 1},
        {"seeds", OPT_LONG, &seeds, 1, 64, "seeds 1..N to gather", .required = 1},
    };
    const opts_cmd c = {"main-summary", "--dir RESULTS --seeds N",
                        "Read RESULTS/main/run_s<seed>_<arm>.tsv for seeds 1..N and both arms; write\n"
                        "RESULTS/main/runs.tsv (per-run errors) and RESULTS/extrapolation/runs.tsv.",
                        spec, sizeof spec / sizeof *spec, 0, 0};
    int r = opts_parse(&c, argc, argv, NULL, NULL);
    if (r) return opts_exit_code(r);
    a.seeds = (int)seeds;
    cs_status st = mainsum_summary(&a);
    return st ? cli_fail("main-summary", st) : 0;
}

int cli_comparison_dist(int argc, char **argv)
{
    long np = 256;
    exp_compdist_args a = {.argc = argc, .argv = argv};
    const opt_spec spec[] = {
        {"joint", OPT_STR, &a.joint, 0, 0, "joint-arm weights CKPT", .required = 1},
        {"indep", OPT_STR, &a.indep, 0, 0, "independent-arm weights CKPT of the same seed and reading", .required = 1},
        {"out", OPT_STR, &a.out, 0, 0, "results root DIR: writes DIR/comparison/dist_{patches,summary}.tsv", .required = 1},
        {"patches", OPT_LONG, &np, 1, 100000, "fresh patches per probe (default 256)"},
    };
    const opts_cmd c = {"comparison-dist", "--joint CKPT --indep CKPT --out DIR [--patches N]",
                        "E7 and the dart probe as distributions: N fresh patches at 5.0 m (lattice; hard-core for the dart\n"
                        "probe), teacher, joint and independent arm; per-patch statistics, quantiles and the figure patch.",
                        spec, sizeof spec / sizeof *spec, 0, 0};
    int r = opts_parse(&c, argc, argv, NULL, NULL);
    if (r) return opts_exit_code(r);
    a.patches = (int)np;
    cs_status st = exp_compdist_run(&a);
    return st ? cli_fail("comparison-dist", st) : 0;
}

int cli_model_readings_summary(int argc, char **argv)
{
    const char *dir = NULL, *out = NULL;
    const opt_spec spec[] = {
        {"dir", OPT_STR, &dir, 0, 0, "results or frozen root holding paper/, extension-pair/, model-readings/", .required = 1},
        {"out", OPT_STR, &out, 0, 0, "table FILE.tsv, e.g. DIR/model-readings/summary.tsv", .required = 1},
    };
    const opts_cmd c = {"model-readings-summary", "--dir DIR --out FILE.tsv",
                        "E3/E4 generator readings: per reading that has run, seeds, parameters, joint, independent and\n"
                        "direction-blind errors, relative improvement, Wilcoxon p, probe ratios, extrapolation advantage, steps/s.",
                        spec, 2, 0, 0};
    int r = opts_parse(&c, argc, argv, NULL, NULL);
    if (r) return opts_exit_code(r);
    model_readings_row rows[4];
    size_t n = 0;
    cs_status st = model_readings_compute(dir, rows, &n);
    if (!st && !n) st = cs_err(CS_EINPUT, "%s: no reading has a main/runs.tsv", dir);
    if (!st) st = afile_mkdir_parents(out);
    if (!st) st = model_readings_write(out, dir, rows, n, argc, argv);
    for (size_t i = 0; !st && i < n; i++)
        printf("%-13s %-11s seeds %2d  joint %.4f  indep %.4f  rel %.1f %%  p %.5f  shuffle x%.2f\n",
               rows[i].reading, rows[i].role, rows[i].seeds, rows[i].joint, rows[i].indep, 100 * rows[i].rel,
               rows[i].p, rows[i].shuf_joint);
    return st ? cli_fail("model-readings-summary", st) : 0;
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

int cli_generator_probes_run(int argc, char **argv)
{
    long seed = 0;
    int perfect = 0;
    genprobe_args a = {.scale = "full", .argc = argc, .argv = argv};
    const opt_spec spec[] = {
        {"weights", OPT_STR, &a.weights, 0, 0, "frozen weights FILE of one unit (not with --perfect)"},
        {"trained", OPT_STR, &a.trained, 0, 0, "the unit's run table the weights were frozen with (recorded in the provenance)"},
        {"seed", OPT_LONG, &seed, 1, 4294967295.0, "the unit's model seed (the probes' sampling seeds derive from it)"},
        {"arm", OPT_CHOICE, &a.arm, 0, 0, "the weights' arm", .choices = CLI_ARMS},
        {"reading", OPT_CHOICE, &a.reading, 0, 0, "the reading the weights must be (default: any)", .choices = READINGS},
        {"perfect", OPT_FLAG, &perfect, 0, 0, "the teacher's own crowns under each probe that has a teacher's side, no model"},
        {"scale", OPT_CHOICE, &a.scale, 0, 0, "the plan's scale (default full)", .choices = SCALES},
        {"samples", OPT_STR, &a.samples, 0, 0, "also write the clearances behind every W1 to FILE.tsv (default none)"},
        {"out", OPT_STR, &a.out, 0, 0, "the probe table FILE.tsv", .required = 1},
    };
    const opts_cmd c = {"generator-probes-run",
                        "--weights FILE --seed S --arm joint|indep --out FILE.tsv [options] | --perfect --out FILE.tsv",
                        "What a generator uses (design.md §8.4): one unit's frozen weights sampled at the unseen spacings\n"
                        "with attention masked to the tree itself, the patch turned by 15, 45 and 90 degrees, the nearest\n"
                        "neighbour's position exchanged with the 2nd-4th, positions snapped to the ideal lattice and the\n"
                        "neighbours' sizes permuted; W1 of focal nearest-neighbour clearances against the teacher's.\n"
                        "--perfect: the teacher's own crowns under each probe that has a teacher's side.",
                        spec, sizeof spec / sizeof *spec, 0, 0};
    int r = opts_parse(&c, argc, argv, NULL, NULL);
    if (r) return opts_exit_code(r);
    a.seed = (unsigned)seed;
    a.perfect = perfect;
    cs_status st = genprobe_run(&a);
    return st ? cli_fail("generator-probes-run", st) : 0;
}

int cli_generator_probes_summary(int argc, char **argv)
{
    const char *dir = NULL, *out = NULL;
    long seeds = 4;
    const opt_spec spec[] = {
        {"dir", OPT_STR, &dir, 0, 0, "results or frozen root holding generator-probes/", .required = 1},
        {"seeds", OPT_LONG, &seeds, 1, 64, "seeds 1..N of every reading (default 4, the design's; smoke: 1)"},
        {"out", OPT_STR, &out, 0, 0, "table FILE.tsv, e.g. DIR/generator-probes/summary.tsv", .required = 1},
    };
    const opts_cmd c = {"generator-probes-summary", "--dir DIR --out FILE.tsv [--seeds N]",
                        "What each generator reading uses: per reading, arm and probe, the median error under the probe\n"
                        "over the median error without it (seeds 1-4), from the probe tables under DIR/generator-probes/.",
                        spec, sizeof spec / sizeof *spec, 0, 0};
    int r = opts_parse(&c, argc, argv, NULL, NULL);
    if (r) return opts_exit_code(r);
    cs_status st = claim_probe_summary_write(dir, out, (int)seeds, argc, argv);
    return st ? cli_fail("generator-probes-summary", st) : 0;
}
