/* exp_main: the main experiment E3 and extrapolation E4 (reference paper
 * §4.3-§5.2; design.md §7 E3/E4, §8). One unit per (seed, arm): build the teacher
 * data, train the flow model (joint or independent arm), generate eval
 * patches at the unseen (4.0, 5.0, 6.0 m) and extrapolation (3.0, 7.5 m)
 * spacings, and measure W1 between generated and teacher focal nearest-
 * neighbour clearances; both arms are also probed with shuffled geometry (the
 * preregistered probe) and rotated geometry (added after the first verdict),
 * and each unit writes the clearance samples behind its W1 and its weights.
 * A baselines unit measures the direction-blind baseline and the split-half
 * noise floor; a summary unit gathers the runs into the frozen tables.
 *
 * Data plan (ours; design.md §8 leaves it open): teacher at beta_train (from
 * gates/mechanism.gate) on the controlled lattice (jitter from
 * gates/anisotropy.gate canonical_jitter), L = 12 d; every interior stem of a
 * stand is a focal stem. Seeds: seed_derive("main-train"|"main-eval", d, k, ·)
 * for stands, seed_derive("main-model", 0, seed, "init"|"batch"|"noise"|
 * "sample"|"shuffle") for the model, so train and eval stands are disjoint
 * by construction and both arms of a seed share every seed. */
#ifndef EXP_MAIN_H
#define EXP_MAIN_H

/* CLI entry points (return process exit codes; design.md §11). */
int exp_main_cmd_run(int argc, char **argv);
int exp_main_cmd_redraw(int argc, char **argv);
int exp_main_cmd_train(int argc, char **argv);
int exp_main_cmd_eval(int argc, char **argv);

#endif
