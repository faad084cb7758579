/* manifest: every experiment of the study, in one place (design.md §7). One
 * EXPERIMENT row per experiment, its COMMAND or RUN rows (the crownshy
 * commands it adds), its UNIT rows (the make units of the full run) and, for an
 * experiment that reruns other units under changed switches, its VARIANT
 * rows. Everything else is derived from this file:
 *  - the make units, `make reproduce`'s unit list and `make verify-deep`'s
 *    list (src/base/manifest.sh make -> build/manifest.mk, included by the
 *    Makefile);
 *  - the CLI's command table and its --help groups (src/cli/cli.c);
 *  - the experiment table of src/README.md (src/base/manifest.sh readme);
 *  - trace's experiment line (manifest.c);
 *  - the claim registry: its tables and their order (CLAIMS rows).
 * tests/layout.sh fails when any of them is listed by hand elsewhere, when a
 * named file is missing, or when a frozen/ folder has no row here.
 *
 * The rows are X-macros: an includer defines the kinds it reads, the others
 * expand to nothing. Each row stays on one line (the shell generator reads
 * the file line by line); every field after the name is a string literal.
 *
 * EXPERIMENT(name, code, source, gate, claims, figure, deep, what)
 *   name    one word used everywhere: frozen/<name>/, the command prefix
 *           <name>-..., `make <name>`, the provenance's experiment; the
 *           commands every generator reading runs are named after the gate
 *           of the experiment that lists them (main-..., gates/main.gate;
 *           their provenance's experiment is main; tests/layout.sh)
 *   code    the study's label (E0..E9)
 *   source  the experiment's code; gate, claims, figure: its preregistered
 *           gate file, its claim code, its gnuplot script ("-": none)
 *   deep    what `make verify-deep` does with it: "rerun" (every unit rerun
 *           and compared bit for bit), "redraw" (model samples redrawn from
 *           the frozen weights) or "-"
 * COMMAND(name, command, handler, help)
 *   handler is `int handler(int argc, char **argv)` in src/cli (the argv
 *   table lives there); help is the line of `crownshy --help`.
 * RUN(name, command, entry, takes, help)
 *   a command whose options are the common ones of a unit (--out DIR,
 *   --teacher, --vary, and those takes names: "stands", "beta", "tag",
 *   "rows" for --stand-rows; "-" none): entry is `cs_status entry(const
 *   exp_opts *)` in the experiment's file, declared here, its argv table the
 *   CLI's one for such units (src/cli/cli_run.c).
 * UNIT(name, target, prereqs, recipe, flags)
 *   target  file under <root>/<name>/ (a % makes a pattern rule);
 *   prereqs and recipe are make text, with @R@ = the results root of the
 *           run, @TEACHER@ / @LAYOUT@ = the switches of a variant run (empty
 *           in the adopted run) and @VARIANT_UNITS@ = every unit of this
 *           experiment's variant runs; an empty recipe marks a table written
 *           by another unit of the same experiment;
 *   flags   "top": registered in `make reproduce` (and in verify-deep when
 *           the experiment is rerun); "side": a table written by another
 *           unit, checked to exist; a variant experiment's name: the unit
 *           also runs in each of that experiment's VARIANT runs.
 * CLAIMS(table)
 *   a claim table (`const claim_spec table[]`, src/claims/claims.h) defined
 *   in src/claims/ (its experiment's claim code or a claim_*_table.c beside
 *   it): the CLAIMS rows in their
 *   order are the registry, audit/claims.tsv its print (`crownshy
 *   claims-table`; src/claims/claims_registry.c). An experiment's claims may
 *   sit in more than one table where the paper's order interleaves them.
 * VARIANT(name, run, teacher, layout)
 *   one run of experiment name's variants under <root>/<name>/<run>/:
 *   teacher and layout are the switches put in place of @TEACHER@ and
 *   @LAYOUT@ in the units flagged with name. */
#ifndef EXPERIMENT
#define EXPERIMENT(name, code, source, gate, claims, figure, deep, what)
#endif
#ifndef COMMAND
#define COMMAND(name, command, handler, help)
#endif
#ifndef CLAIMS
#define CLAIMS(table)
#endif
#ifndef RUN
#define RUN(name, command, entry, takes, help)
#endif
#ifndef UNIT
#define UNIT(name, target, prereqs, recipe, flags)
#endif
#ifndef VARIANT
#define VARIANT(name, run, teacher, layout)
#endif

EXPERIMENT(readings, "E0", "src/claims/readings.c", "-", "src/claims/readings.c", "figures/readings.gp", "rerun", "the cheap experiments under each reading of the paper (teacher rule x field layout), beside the paper's values")
COMMAND(readings, "readings-summary", cli_readings_summary, "E0: the readings table from the runs under --dir")
UNIT(readings, "summary.tsv", "@VARIANT_UNITS@ audit/claims.tsv", "$(CLI) readings-summary --dir @R@/readings --out $@", "top")
VARIANT(readings, "one-sided-60m", "--teacher teacher-1", "--layout 5m-on-60m")
VARIANT(readings, "mutual-60m", "--teacher teacher-2", "--layout 5m-on-60m")
VARIANT(readings, "one-sided-36m", "--teacher teacher-1", "--layout 4m-on-36m")
VARIANT(readings, "mutual-36m", "--teacher teacher-2", "--layout 4m-on-36m")
VARIANT(readings, "arc-36m", "--teacher teacher-2-arc", "--layout 4m-on-36m")

EXPERIMENT(sensitivity, "E0", "src/exp/exp_sensitivity.c", "-", "src/claims/sens.c", "figures/sensitivity.gp", "rerun", "the cheap teacher numbers with one unstated choice (src/base/unstated.c) moved either side of ours, everything else pinned: one unit per choice and value, and a centre unit with our choices")
COMMAND(sensitivity, "sensitivity-run", cli_sensitivity_run, "E0: one sensitivity unit: one unstated choice at one value, or the centre")
COMMAND(sensitivity, "sensitivity-summary", cli_sensitivity_summary, "E0: the sensitivity table from the units under --dir")
UNIT(sensitivity, "%/unit.tsv", "$(SENS_DEPS)", "$(CLI) sensitivity-run --unit $* $(SENS_ARGS) --out $(@D)", "-")
UNIT(sensitivity, "summary.tsv", "$(foreach u,centre crown_R_3 crown_R_5 crown_spread_0.05 crown_spread_0.25 height_sd_2 height_sd_6 lobing_0.1 lobing_0.3 growth_N_24 growth_N_96 start_0.02 start_0.1 fig_hardcore_0.3 fig_hardcore_0.4 fig_hardcore_0.6 fig_hardcore_0.7 field_d_3 field_d_3.5 field_d_4.5 field_d_5 field_L_28 field_L_32 field_L_44 field_L_60 dieback_1 dieback_2 dieback_3,@R@/sensitivity/$(u)/unit.tsv) audit/claims.tsv", "$(CLI) sensitivity-summary --dir @R@/sensitivity --out $@", "top")

EXPERIMENT(mechanism, "E1", "src/exp/exp_mechanism.c", "gates/mechanism.gate", "src/claims/claim_teacher.c", "figures/mechanism.gp", "rerun", "the growth rule's mechanism: a beta x spacing sweep, the coupling/abrasion ablation, the figure stand")
RUN(mechanism, "mechanism-sweep", exp_mechanism_sweep, "stands rows", "E1: 16 rows beta x d on the controlled lattice")
RUN(mechanism, "mechanism-ablation", exp_mechanism_ablation, "stands", "E1: coupling off / abrasion off / both on at 3.5 m")
RUN(mechanism, "mechanism-figure", exp_mechanism_figure, "-", "E1: crowns and statistics of the three figure panels (hard-core, 3.5 m, L = 36 m)")
UNIT(mechanism, "sweep.tsv", "$(TEACHER_DEPS)", "$(CLI) mechanism-sweep @TEACHER@ --stands $(TEACHER_STANDS) --stand-rows --out @R@", "top readings")
UNIT(mechanism, "sweep_trees.tsv", "@R@/mechanism/sweep.tsv", "", "side")
UNIT(mechanism, "ablation.tsv", "$(TEACHER_DEPS)", "$(CLI) mechanism-ablation @TEACHER@ --stands $(TEACHER_STANDS) --out @R@", "top readings")
UNIT(mechanism, "figure_crowns.tsv", "$(TEACHER_DEPS)", "$(CLI) mechanism-figure @TEACHER@ --out @R@", "top readings")
UNIT(mechanism, "figure_stats.tsv", "@R@/mechanism/figure_crowns.tsv", "", "side")

EXPERIMENT(irreducibility, "E2", "src/exp/exp_irreducibility.c", "gates/irreducibility.gate", "src/claims/claim_teacher.c", "figures/irreducible.gp", "rerun", "no local rule reproduces the growth: response to a perturbed tree, refinement of N, best-fit Voronoi reduction, at beta_train and beta_field")
COMMAND(irreducibility, "irreducibility-perturb", cli_irreducibility_perturb, "E2: one tree 30% taller, 5 spacings")
COMMAND(irreducibility, "irreducibility-refine", cli_irreducibility_refine, "E2: growth resolution N in {48, 96, 192, 384}")
COMMAND(irreducibility, "irreducibility-reduction", cli_irreducibility_reduction, "E2: best-fit Voronoi reduction")
UNIT(irreducibility, "perturb_train.tsv", "$(TEACHER_DEPS)", "$(CLI) irreducibility-perturb --stands $(TEACHER_STANDS) --stand-rows --out @R@", "top")
UNIT(irreducibility, "perturb_train_stands.tsv", "@R@/irreducibility/perturb_train.tsv", "", "side")
UNIT(irreducibility, "refine_train.tsv", "$(TEACHER_DEPS)", "$(CLI) irreducibility-refine --stands $(TEACHER_STANDS) --stand-rows --out @R@", "top")
UNIT(irreducibility, "refine_train_sectors.tsv", "@R@/irreducibility/refine_train.tsv", "", "side")
UNIT(irreducibility, "reduction_train.tsv", "$(TEACHER_DEPS)", "$(CLI) irreducibility-reduction --stands $(TEACHER_STANDS) --stand-rows --out @R@", "top")
UNIT(irreducibility, "reduction_train_sectors.tsv", "@R@/irreducibility/reduction_train.tsv", "", "side")
UNIT(irreducibility, "perturb_field.tsv", "@R@/field/calibration.tsv", "$(CLI) irreducibility-perturb --stands $(TEACHER_STANDS) --beta $$($(CLI) field-beta @R@/field/calibration.tsv) --tag field --stand-rows --out @R@", "top")
UNIT(irreducibility, "perturb_field_stands.tsv", "@R@/irreducibility/perturb_field.tsv", "", "side")
UNIT(irreducibility, "refine_field.tsv", "@R@/field/calibration.tsv", "$(CLI) irreducibility-refine --stands $(TEACHER_STANDS) --beta $$($(CLI) field-beta @R@/field/calibration.tsv) --tag field --stand-rows --out @R@", "top")
UNIT(irreducibility, "refine_field_sectors.tsv", "@R@/irreducibility/refine_field.tsv", "", "side")
UNIT(irreducibility, "reduction_field.tsv", "@R@/field/calibration.tsv", "$(CLI) irreducibility-reduction --stands $(TEACHER_STANDS) --beta $$($(CLI) field-beta @R@/field/calibration.tsv) --tag field --stand-rows --out @R@", "top")
UNIT(irreducibility, "reduction_field_sectors.tsv", "@R@/irreducibility/reduction_field.tsv", "", "side")

EXPERIMENT(extension-pair-16-stands, "E3", "src/exp/exp_main.c", "gates/main.gate", "src/claims/claim_main.c", "-", "redraw", "the pair-aware generator (design.md §8, an extension added after the first verdict) trained and first judged at the 16-stands evaluation volume, joint vs independent generation at the unseen spacings: one training and evaluation unit per (seed, arm), baselines, the summary and the runs at the extrapolation spacings; the weights extension-pair re-evaluates")
COMMAND(extension-pair-16-stands, "main-run", cli_main_run, "E3/E4: one (seed, arm) training + evaluation unit")
COMMAND(extension-pair-16-stands, "main-baselines", cli_main_baselines, "E3/E4: direction-blind baseline and noise floor")
COMMAND(extension-pair-16-stands, "main-summary", cli_main_summary, "E3/E4: gather the runs into the frozen tables")
COMMAND(extension-pair-16-stands, "main-redraw", cli_main_redraw, "E3/E4: draw a unit's clearance samples again from its frozen weights")
COMMAND(extension-pair-16-stands, "main-train", cli_main_train, "E3/E4: train one (seed, arm, reading) unit: weights and training table")
COMMAND(extension-pair-16-stands, "main-eval", cli_main_eval, "E3/E4: evaluate one unit from its weights, without training: run table and samples")
UNIT(extension-pair-16-stands, "main/run_s%_joint.tsv", "", "mkdir -p $(B)/ckpt/$(SCALE) && $(CLI) main-run --seed $* --arm joint --scale $(SCALE) --ckpt $(B)/ckpt/$(SCALE)/extension-pair-16-stands_s$*_joint.ckpt --samples @R@/extension-pair-16-stands/main/samples_s$*_joint.tsv --weights @R@/extension-pair-16-stands/main/weights_s$*_joint.ckpt --out $@", "-")
UNIT(extension-pair-16-stands, "main/run_s%_indep.tsv", "", "mkdir -p $(B)/ckpt/$(SCALE) && $(CLI) main-run --seed $* --arm indep --scale $(SCALE) --ckpt $(B)/ckpt/$(SCALE)/extension-pair-16-stands_s$*_indep.ckpt --samples @R@/extension-pair-16-stands/main/samples_s$*_indep.tsv --weights @R@/extension-pair-16-stands/main/weights_s$*_indep.ckpt --out $@", "-")
UNIT(extension-pair-16-stands, "main/baselines.tsv", "", "$(CLI) main-baselines --scale $(SCALE) --samples @R@/extension-pair-16-stands/main/samples_baselines.tsv --stand-rows --out $@", "-")
UNIT(extension-pair-16-stands, "main/baselines_stands.tsv", "@R@/extension-pair-16-stands/main/baselines.tsv", "", "-")
UNIT(extension-pair-16-stands, "main/runs.tsv", "$(foreach s,$(MAIN_SEED_LIST),@R@/extension-pair-16-stands/main/run_s$(s)_joint.tsv @R@/extension-pair-16-stands/main/run_s$(s)_indep.tsv) @R@/extension-pair-16-stands/main/baselines.tsv", "$(CLI) main-summary --dir @R@/extension-pair-16-stands --seeds $(MAIN_NSEEDS)", "top")
UNIT(extension-pair-16-stands, "extrapolation/runs.tsv", "@R@/extension-pair-16-stands/main/runs.tsv", "", "side")

EXPERIMENT(field, "E5", "src/exp/exp_field.c", "gates/field.gate", "src/claims/claim_field.c", "figures/field.gp", "rerun", "die-back calibrated to the field's median clearance, then held-out spread, elongation and the uncoupled control")
COMMAND(field, "field-calibrate", cli_field_calibrate, "E5: calibrate die-back beta to the field tree-mean median clearance")
COMMAND(field, "field-beta", cli_field_beta, "E5: print beta_field from a calibration table")
COMMAND(field, "field-heldout", cli_field_heldout, "E5: held-out spread, elongation and uncoupled control at beta_field")
COMMAND(field, "field-summary", cli_field_summary, "E5: summarise a raw field table (FIELD_TABLE) with the canonical estimator")
COMMAND(field, "field-diagnose", cli_field_diagnose, "E5/E6: diagnostics for the elongation and anisotropy verdicts")
UNIT(field, "calibration.tsv", "", "$(CLI) field-calibrate @TEACHER@ @LAYOUT@ --out $@", "top readings")
UNIT(field, "heldout.tsv", "@R@/field/calibration.tsv", "$(CLI) field-heldout @TEACHER@ @LAYOUT@ --calibration @R@/field/calibration.tsv --stands $(FIELD_STANDS) --out $@", "top readings")

EXPERIMENT(anisotropy, "E6", "src/exp/exp_anisotropy.c", "gates/anisotropy.gate", "src/claims/claim_aniso.c", "figures/anisotropy.gp", "rerun", "what sets the gap anisotropy: the lattice, a hard-core and a jitter family, a* calibrated, held-out stands at a*")
COMMAND(anisotropy, "anisotropy-lattice", cli_anisotropy_lattice, "E6: anisotropy on the controlled lattice at beta_field")
COMMAND(anisotropy, "anisotropy-hardcore", cli_anisotropy_hardcore, "E6: hard-core stem family sweep")
COMMAND(anisotropy, "anisotropy-jitter", cli_anisotropy_jitter, "E6: jitter-amplitude family sweep")
COMMAND(anisotropy, "anisotropy-jitter-calibrate", cli_anisotropy_jitter_calibrate, "E6: calibrate the jitter a* to the field anisotropy median")
COMMAND(anisotropy, "anisotropy-heldout", cli_anisotropy_heldout, "E6: held-out stands at a*")
UNIT(anisotropy, "lattice.tsv", "@R@/field/calibration.tsv", "$(CLI) anisotropy-lattice @TEACHER@ @LAYOUT@ --calibration @R@/field/calibration.tsv --stands $(FIELD_STANDS) --out $@", "top readings")
UNIT(anisotropy, "hardcore.tsv", "@R@/field/calibration.tsv", "$(CLI) anisotropy-hardcore @TEACHER@ @LAYOUT@ --calibration @R@/field/calibration.tsv --stands $(ANISO_SWEEP_STANDS) --out $@", "top readings")
UNIT(anisotropy, "jitter.tsv", "@R@/field/calibration.tsv", "$(CLI) anisotropy-jitter @TEACHER@ @LAYOUT@ --calibration @R@/field/calibration.tsv --stands $(ANISO_SWEEP_STANDS) --out $@", "top readings")
UNIT(anisotropy, "jitter_calibration.tsv", "@R@/anisotropy/jitter.tsv", "$(CLI) anisotropy-jitter-calibrate --sweep $< --out $@", "top readings")
UNIT(anisotropy, "heldout.tsv", "@R@/field/calibration.tsv @R@/anisotropy/jitter_calibration.tsv", "$(CLI) anisotropy-heldout @TEACHER@ @LAYOUT@ --calibration @R@/field/calibration.tsv --jitter-calibration @R@/anisotropy/jitter_calibration.tsv --stands $(FIELD_STANDS) --out $@", "top readings")

EXPERIMENT(comparison, "E7", "src/exp/exp_comp.c", "-", "src/claims/claim_comp.c", "-", "-", "a 24-tree patch at 5.0 m by the teacher, the joint and the independent model of seed 1, and the dart probe")
COMMAND(comparison, "comparison-run", cli_comparison_run, "E7: comparison patch (teacher, joint, independent) and dart probe")
COMMAND(comparison, "comparison-dist", cli_comparison_dist, "E7: the comparison patch and the dart probe as distributions over fresh patches")
UNIT(comparison, "patch.tsv", "@R@/extension-pair-16-stands/main/run_s01_joint.tsv @R@/extension-pair-16-stands/main/run_s01_indep.tsv", "$(CLI) comparison-run --joint @R@/extension-pair-16-stands/main/weights_s01_joint.ckpt --indep @R@/extension-pair-16-stands/main/weights_s01_indep.ckpt --out @R@", "top")

EXPERIMENT(paper-reading, "E3", "src/exp/exp_main.c", "gates/main.gate", "src/claims/claim_main.c", "figures/main.gp", "redraw", "the generator as the reference paper describes it (design.md §8 readings: tokens from the noisy profile, position and size, standardised; plain attention), 12 seeds x 2 arms at the 96-stands evaluation volume: the reading the preregistered main and extrapolation gates judge; its E7 distribution")
UNIT(paper-reading, "main/run_s%_joint.tsv", "", "mkdir -p $(B)/ckpt/$(SCALE) && $(CLI) main-run --reading paper --volume 96-stands --seed $* --arm joint --scale $(SCALE) --ckpt $(B)/ckpt/$(SCALE)/paper-main_s$*_joint.ckpt --samples @R@/paper-reading/main/samples_s$*_joint.tsv --weights @R@/paper-reading/main/weights_s$*_joint.ckpt --out $@", "-")
UNIT(paper-reading, "main/run_s%_indep.tsv", "", "mkdir -p $(B)/ckpt/$(SCALE) && $(CLI) main-run --reading paper --volume 96-stands --seed $* --arm indep --scale $(SCALE) --ckpt $(B)/ckpt/$(SCALE)/paper-main_s$*_indep.ckpt --samples @R@/paper-reading/main/samples_s$*_indep.tsv --weights @R@/paper-reading/main/weights_s$*_indep.ckpt --out $@", "-")
UNIT(paper-reading, "main/baselines.tsv", "", "$(CLI) main-baselines --volume 96-stands --scale $(SCALE) --samples @R@/paper-reading/main/samples_baselines.tsv --stand-rows --out $@", "-")
UNIT(paper-reading, "main/baselines_stands.tsv", "@R@/paper-reading/main/baselines.tsv", "", "-")
UNIT(paper-reading, "main/runs.tsv", "$(foreach s,$(MAIN_SEED_LIST),@R@/paper-reading/main/run_s$(s)_joint.tsv @R@/paper-reading/main/run_s$(s)_indep.tsv) @R@/paper-reading/main/baselines.tsv", "$(CLI) main-summary --dir @R@/paper-reading --seeds $(MAIN_NSEEDS)", "top")
UNIT(paper-reading, "comparison/dist_summary.tsv", "@R@/paper-reading/main/run_s01_joint.tsv @R@/paper-reading/main/run_s01_indep.tsv", "$(CLI) comparison-dist --joint @R@/paper-reading/main/weights_s01_joint.ckpt --indep @R@/paper-reading/main/weights_s01_indep.ckpt --out @R@/paper-reading", "top")

EXPERIMENT(extension-pair, "E3", "src/exp/exp_main.c", "-", "src/claims/claim_main.c", "figures/main-pair.gp", "redraw", "the pair-aware generator (design.md §8, an extension added after the first verdict): E3's frozen pair units re-evaluated from their weights at the 96-stands volume, and its E7 distribution")
UNIT(extension-pair, "main/run_s%_joint.tsv", "@R@/extension-pair-16-stands/main/run_s%_joint.tsv", "$(CLI) main-eval --reading pair --volume 96-stands --seed $* --arm joint --scale $(SCALE) --weights @R@/extension-pair-16-stands/main/weights_s$*_joint.ckpt --trained @R@/extension-pair-16-stands/main/run_s$*_joint.tsv --samples @R@/extension-pair/main/samples_s$*_joint.tsv --out $@", "-")
UNIT(extension-pair, "main/run_s%_indep.tsv", "@R@/extension-pair-16-stands/main/run_s%_indep.tsv", "$(CLI) main-eval --reading pair --volume 96-stands --seed $* --arm indep --scale $(SCALE) --weights @R@/extension-pair-16-stands/main/weights_s$*_indep.ckpt --trained @R@/extension-pair-16-stands/main/run_s$*_indep.tsv --samples @R@/extension-pair/main/samples_s$*_indep.tsv --out $@", "-")
UNIT(extension-pair, "main/baselines.tsv", "", "$(CLI) main-baselines --volume 96-stands --scale $(SCALE) --samples @R@/extension-pair/main/samples_baselines.tsv --stand-rows --out $@", "-")
UNIT(extension-pair, "main/baselines_stands.tsv", "@R@/extension-pair/main/baselines.tsv", "", "-")
UNIT(extension-pair, "main/runs.tsv", "$(foreach s,$(MAIN_SEED_LIST),@R@/extension-pair/main/run_s$(s)_joint.tsv @R@/extension-pair/main/run_s$(s)_indep.tsv) @R@/extension-pair/main/baselines.tsv", "$(CLI) main-summary --dir @R@/extension-pair --seeds $(MAIN_NSEEDS)", "top")
UNIT(extension-pair, "comparison/dist_summary.tsv", "@R@/extension-pair-16-stands/main/run_s01_joint.tsv @R@/extension-pair-16-stands/main/run_s01_indep.tsv", "$(CLI) comparison-dist --joint @R@/extension-pair-16-stands/main/weights_s01_joint.ckpt --indep @R@/extension-pair-16-stands/main/weights_s01_indep.ckpt --out @R@/extension-pair", "top")

EXPERIMENT(model-readings, "E3", "src/claims/model_readings.c", "-", "src/claims/model_readings.c", "figures/model-readings.gp", "redraw", "the intermediate generator readings (plain, paper-fourier; 4 seeds, the 96-stands volume, descriptive) and the readings table beside the paper reading and the pair extension")
COMMAND(model-readings, "model-readings-summary", cli_model_readings_summary, "E3/E4: the generator readings table from the runs under --dir")
UNIT(model-readings, "plain/main/run_s%_joint.tsv", "", "mkdir -p $(B)/ckpt/$(SCALE) && $(CLI) main-run --reading plain --volume 96-stands --seed $* --arm joint --scale $(SCALE) --ckpt $(B)/ckpt/$(SCALE)/plain-main_s$*_joint.ckpt --samples @R@/model-readings/plain/main/samples_s$*_joint.tsv --weights @R@/model-readings/plain/main/weights_s$*_joint.ckpt --out $@", "-")
UNIT(model-readings, "plain/main/run_s%_indep.tsv", "", "mkdir -p $(B)/ckpt/$(SCALE) && $(CLI) main-run --reading plain --volume 96-stands --seed $* --arm indep --scale $(SCALE) --ckpt $(B)/ckpt/$(SCALE)/plain-main_s$*_indep.ckpt --samples @R@/model-readings/plain/main/samples_s$*_indep.tsv --weights @R@/model-readings/plain/main/weights_s$*_indep.ckpt --out $@", "-")
UNIT(model-readings, "paper-fourier/main/run_s%_joint.tsv", "", "mkdir -p $(B)/ckpt/$(SCALE) && $(CLI) main-run --reading paper-fourier --volume 96-stands --seed $* --arm joint --scale $(SCALE) --ckpt $(B)/ckpt/$(SCALE)/paper-fourier-main_s$*_joint.ckpt --samples @R@/model-readings/paper-fourier/main/samples_s$*_joint.tsv --weights @R@/model-readings/paper-fourier/main/weights_s$*_joint.ckpt --out $@", "-")
UNIT(model-readings, "paper-fourier/main/run_s%_indep.tsv", "", "mkdir -p $(B)/ckpt/$(SCALE) && $(CLI) main-run --reading paper-fourier --volume 96-stands --seed $* --arm indep --scale $(SCALE) --ckpt $(B)/ckpt/$(SCALE)/paper-fourier-main_s$*_indep.ckpt --samples @R@/model-readings/paper-fourier/main/samples_s$*_indep.tsv --weights @R@/model-readings/paper-fourier/main/weights_s$*_indep.ckpt --out $@", "-")
UNIT(model-readings, "plain/main/runs.tsv", "$(foreach s,$(READING_SEED_LIST),@R@/model-readings/plain/main/run_s$(s)_joint.tsv @R@/model-readings/plain/main/run_s$(s)_indep.tsv)", "$(CLI) main-summary --dir @R@/model-readings/plain --seeds $(READING_NSEEDS)", "-")
UNIT(model-readings, "paper-fourier/main/runs.tsv", "$(foreach s,$(READING_SEED_LIST),@R@/model-readings/paper-fourier/main/run_s$(s)_joint.tsv @R@/model-readings/paper-fourier/main/run_s$(s)_indep.tsv)", "$(CLI) main-summary --dir @R@/model-readings/paper-fourier --seeds $(READING_NSEEDS)", "-")
UNIT(model-readings, "summary.tsv", "@R@/paper-reading/main/runs.tsv @R@/extension-pair/main/runs.tsv @R@/model-readings/plain/main/runs.tsv @R@/model-readings/paper-fourier/main/runs.tsv", "$(CLI) model-readings-summary --dir @R@ --out $@", "top")

EXPERIMENT(generator-sensitivity, "E3", "src/exp/exp_main.c", "-", "src/claims/gensens.c", "-", "redraw", "the paper reading (design.md §8) under each training choice the paper leaves unstated, one at a time (width, blocks, training stands, epochs, learning rate), 4 seeds x 2 arms at the 96-stands volume, descriptive; a choice whose joint arm met both preconditions at 4 seeds (training stands, epochs) at the gate's 12 seeds, judged beside the verdict by the same thresholds")
UNIT(generator-sensitivity, "width-x2/main/run_s%_joint.tsv", "", "mkdir -p $(B)/ckpt/$(SCALE) && $(CLI) main-run --reading paper --width 128 --volume 96-stands --seed $* --arm joint --scale $(SCALE) --ckpt $(B)/ckpt/$(SCALE)/gensens-width-x2_s$*_joint.ckpt --samples @R@/generator-sensitivity/width-x2/main/samples_s$*_joint.tsv --weights @R@/generator-sensitivity/width-x2/main/weights_s$*_joint.ckpt --out $@", "-")
UNIT(generator-sensitivity, "width-x2/main/run_s%_indep.tsv", "", "mkdir -p $(B)/ckpt/$(SCALE) && $(CLI) main-run --reading paper --width 128 --volume 96-stands --seed $* --arm indep --scale $(SCALE) --ckpt $(B)/ckpt/$(SCALE)/gensens-width-x2_s$*_indep.ckpt --samples @R@/generator-sensitivity/width-x2/main/samples_s$*_indep.tsv --weights @R@/generator-sensitivity/width-x2/main/weights_s$*_indep.ckpt --out $@", "-")
UNIT(generator-sensitivity, "blocks-x2/main/run_s%_joint.tsv", "", "mkdir -p $(B)/ckpt/$(SCALE) && $(CLI) main-run --reading paper --blocks 6 --volume 96-stands --seed $* --arm joint --scale $(SCALE) --ckpt $(B)/ckpt/$(SCALE)/gensens-blocks-x2_s$*_joint.ckpt --samples @R@/generator-sensitivity/blocks-x2/main/samples_s$*_joint.tsv --weights @R@/generator-sensitivity/blocks-x2/main/weights_s$*_joint.ckpt --out $@", "-")
UNIT(generator-sensitivity, "blocks-x2/main/run_s%_indep.tsv", "", "mkdir -p $(B)/ckpt/$(SCALE) && $(CLI) main-run --reading paper --blocks 6 --volume 96-stands --seed $* --arm indep --scale $(SCALE) --ckpt $(B)/ckpt/$(SCALE)/gensens-blocks-x2_s$*_indep.ckpt --samples @R@/generator-sensitivity/blocks-x2/main/samples_s$*_indep.tsv --weights @R@/generator-sensitivity/blocks-x2/main/weights_s$*_indep.ckpt --out $@", "-")
UNIT(generator-sensitivity, "stands-x4/main/run_s%_joint.tsv", "", "mkdir -p $(B)/ckpt/$(SCALE) && $(CLI) main-run --reading paper --train-stands $(GENSENS_STANDS) --volume 96-stands --seed $* --arm joint --scale $(SCALE) --ckpt $(B)/ckpt/$(SCALE)/gensens-stands-x4_s$*_joint.ckpt --samples @R@/generator-sensitivity/stands-x4/main/samples_s$*_joint.tsv --weights @R@/generator-sensitivity/stands-x4/main/weights_s$*_joint.ckpt --out $@", "-")
UNIT(generator-sensitivity, "stands-x4/main/run_s%_indep.tsv", "", "mkdir -p $(B)/ckpt/$(SCALE) && $(CLI) main-run --reading paper --train-stands $(GENSENS_STANDS) --volume 96-stands --seed $* --arm indep --scale $(SCALE) --ckpt $(B)/ckpt/$(SCALE)/gensens-stands-x4_s$*_indep.ckpt --samples @R@/generator-sensitivity/stands-x4/main/samples_s$*_indep.tsv --weights @R@/generator-sensitivity/stands-x4/main/weights_s$*_indep.ckpt --out $@", "-")
UNIT(generator-sensitivity, "epochs-x4/main/run_s%_joint.tsv", "", "mkdir -p $(B)/ckpt/$(SCALE) && $(CLI) main-run --reading paper --epochs $(GENSENS_EPOCHS) --volume 96-stands --seed $* --arm joint --scale $(SCALE) --ckpt $(B)/ckpt/$(SCALE)/gensens-epochs-x4_s$*_joint.ckpt --samples @R@/generator-sensitivity/epochs-x4/main/samples_s$*_joint.tsv --weights @R@/generator-sensitivity/epochs-x4/main/weights_s$*_joint.ckpt --out $@", "-")
UNIT(generator-sensitivity, "epochs-x4/main/run_s%_indep.tsv", "", "mkdir -p $(B)/ckpt/$(SCALE) && $(CLI) main-run --reading paper --epochs $(GENSENS_EPOCHS) --volume 96-stands --seed $* --arm indep --scale $(SCALE) --ckpt $(B)/ckpt/$(SCALE)/gensens-epochs-x4_s$*_indep.ckpt --samples @R@/generator-sensitivity/epochs-x4/main/samples_s$*_indep.tsv --weights @R@/generator-sensitivity/epochs-x4/main/weights_s$*_indep.ckpt --out $@", "-")
UNIT(generator-sensitivity, "lr-x0.25/main/run_s%_joint.tsv", "", "mkdir -p $(B)/ckpt/$(SCALE) && $(CLI) main-run --reading paper --lr 0.0005 --volume 96-stands --seed $* --arm joint --scale $(SCALE) --ckpt $(B)/ckpt/$(SCALE)/gensens-lr-x0.25_s$*_joint.ckpt --samples @R@/generator-sensitivity/lr-x0.25/main/samples_s$*_joint.tsv --weights @R@/generator-sensitivity/lr-x0.25/main/weights_s$*_joint.ckpt --out $@", "-")
UNIT(generator-sensitivity, "lr-x0.25/main/run_s%_indep.tsv", "", "mkdir -p $(B)/ckpt/$(SCALE) && $(CLI) main-run --reading paper --lr 0.0005 --volume 96-stands --seed $* --arm indep --scale $(SCALE) --ckpt $(B)/ckpt/$(SCALE)/gensens-lr-x0.25_s$*_indep.ckpt --samples @R@/generator-sensitivity/lr-x0.25/main/samples_s$*_indep.tsv --weights @R@/generator-sensitivity/lr-x0.25/main/weights_s$*_indep.ckpt --out $@", "-")
UNIT(generator-sensitivity, "lr-x4/main/run_s%_joint.tsv", "", "mkdir -p $(B)/ckpt/$(SCALE) && $(CLI) main-run --reading paper --lr 0.008 --volume 96-stands --seed $* --arm joint --scale $(SCALE) --ckpt $(B)/ckpt/$(SCALE)/gensens-lr-x4_s$*_joint.ckpt --samples @R@/generator-sensitivity/lr-x4/main/samples_s$*_joint.tsv --weights @R@/generator-sensitivity/lr-x4/main/weights_s$*_joint.ckpt --out $@", "-")
UNIT(generator-sensitivity, "lr-x4/main/run_s%_indep.tsv", "", "mkdir -p $(B)/ckpt/$(SCALE) && $(CLI) main-run --reading paper --lr 0.008 --volume 96-stands --seed $* --arm indep --scale $(SCALE) --ckpt $(B)/ckpt/$(SCALE)/gensens-lr-x4_s$*_indep.ckpt --samples @R@/generator-sensitivity/lr-x4/main/samples_s$*_indep.tsv --weights @R@/generator-sensitivity/lr-x4/main/weights_s$*_indep.ckpt --out $@", "-")
UNIT(generator-sensitivity, "width-x2/main/runs.tsv", "$(foreach s,$(READING_SEED_LIST),@R@/generator-sensitivity/width-x2/main/run_s$(s)_joint.tsv @R@/generator-sensitivity/width-x2/main/run_s$(s)_indep.tsv)", "$(CLI) main-summary --dir @R@/generator-sensitivity/width-x2 --seeds $(READING_NSEEDS)", "top")
UNIT(generator-sensitivity, "blocks-x2/main/runs.tsv", "$(foreach s,$(READING_SEED_LIST),@R@/generator-sensitivity/blocks-x2/main/run_s$(s)_joint.tsv @R@/generator-sensitivity/blocks-x2/main/run_s$(s)_indep.tsv)", "$(CLI) main-summary --dir @R@/generator-sensitivity/blocks-x2 --seeds $(READING_NSEEDS)", "top")
UNIT(generator-sensitivity, "stands-x4/main/runs.tsv", "$(foreach s,$(MAIN_SEED_LIST),@R@/generator-sensitivity/stands-x4/main/run_s$(s)_joint.tsv @R@/generator-sensitivity/stands-x4/main/run_s$(s)_indep.tsv)", "$(CLI) main-summary --dir @R@/generator-sensitivity/stands-x4 --seeds $(MAIN_NSEEDS)", "top")
UNIT(generator-sensitivity, "epochs-x4/main/runs.tsv", "$(foreach s,$(MAIN_SEED_LIST),@R@/generator-sensitivity/epochs-x4/main/run_s$(s)_joint.tsv @R@/generator-sensitivity/epochs-x4/main/run_s$(s)_indep.tsv)", "$(CLI) main-summary --dir @R@/generator-sensitivity/epochs-x4 --seeds $(MAIN_NSEEDS)", "top")
UNIT(generator-sensitivity, "lr-x0.25/main/runs.tsv", "$(foreach s,$(READING_SEED_LIST),@R@/generator-sensitivity/lr-x0.25/main/run_s$(s)_joint.tsv @R@/generator-sensitivity/lr-x0.25/main/run_s$(s)_indep.tsv)", "$(CLI) main-summary --dir @R@/generator-sensitivity/lr-x0.25 --seeds $(READING_NSEEDS)", "top")
UNIT(generator-sensitivity, "lr-x4/main/runs.tsv", "$(foreach s,$(READING_SEED_LIST),@R@/generator-sensitivity/lr-x4/main/run_s$(s)_joint.tsv @R@/generator-sensitivity/lr-x4/main/run_s$(s)_indep.tsv)", "$(CLI) main-summary --dir @R@/generator-sensitivity/lr-x4 --seeds $(READING_NSEEDS)", "top")

EXPERIMENT(generator-probes, "E3", "src/exp/genprobe.c", "-", "src/claims/claim_probe.c", "figures/generator-probes.gp", "-", "what each generator reading uses: evaluation-only probes on the frozen weights of seeds 1-4, both arms (attention masked to the tree, turns of 15/45/90 degrees, nearest neighbour swapped, positions de-jittered, neighbour sizes permuted), the same on the paper reading trained on four times the stands (generator-sensitivity), and the teacher's own crowns under each probe that has a teacher's side; descriptive")
COMMAND(generator-probes, "generator-probes-summary", cli_generator_probes_summary, "E3: the probe ratios of every reading, arm and probe from the units under --dir")
COMMAND(generator-probes, "generator-probes-run", cli_generator_probes_run, "E3: one unit's frozen weights under the probes of what a generator uses, or the teacher's side (--perfect)")
UNIT(generator-probes, "paper/probes_s%_joint.tsv", "@R@/paper-reading/main/run_s%_joint.tsv", "$(CLI) generator-probes-run --reading paper --seed $* --arm joint --scale $(SCALE) --weights @R@/paper-reading/main/weights_s$*_joint.ckpt --trained @R@/paper-reading/main/run_s$*_joint.tsv --samples @R@/generator-probes/paper/samples_s$*_joint.tsv --out $@", "-")
UNIT(generator-probes, "paper/probes_s%_indep.tsv", "@R@/paper-reading/main/run_s%_indep.tsv", "$(CLI) generator-probes-run --reading paper --seed $* --arm indep --scale $(SCALE) --weights @R@/paper-reading/main/weights_s$*_indep.ckpt --trained @R@/paper-reading/main/run_s$*_indep.tsv --samples @R@/generator-probes/paper/samples_s$*_indep.tsv --out $@", "-")
UNIT(generator-probes, "pair/probes_s%_joint.tsv", "@R@/extension-pair-16-stands/main/run_s%_joint.tsv", "$(CLI) generator-probes-run --reading pair --seed $* --arm joint --scale $(SCALE) --weights @R@/extension-pair-16-stands/main/weights_s$*_joint.ckpt --trained @R@/extension-pair-16-stands/main/run_s$*_joint.tsv --samples @R@/generator-probes/pair/samples_s$*_joint.tsv --out $@", "-")
UNIT(generator-probes, "pair/probes_s%_indep.tsv", "@R@/extension-pair-16-stands/main/run_s%_indep.tsv", "$(CLI) generator-probes-run --reading pair --seed $* --arm indep --scale $(SCALE) --weights @R@/extension-pair-16-stands/main/weights_s$*_indep.ckpt --trained @R@/extension-pair-16-stands/main/run_s$*_indep.tsv --samples @R@/generator-probes/pair/samples_s$*_indep.tsv --out $@", "-")
UNIT(generator-probes, "paper-fourier/probes_s%_joint.tsv", "@R@/model-readings/paper-fourier/main/run_s%_joint.tsv", "$(CLI) generator-probes-run --reading paper-fourier --seed $* --arm joint --scale $(SCALE) --weights @R@/model-readings/paper-fourier/main/weights_s$*_joint.ckpt --trained @R@/model-readings/paper-fourier/main/run_s$*_joint.tsv --samples @R@/generator-probes/paper-fourier/samples_s$*_joint.tsv --out $@", "-")
UNIT(generator-probes, "paper-fourier/probes_s%_indep.tsv", "@R@/model-readings/paper-fourier/main/run_s%_indep.tsv", "$(CLI) generator-probes-run --reading paper-fourier --seed $* --arm indep --scale $(SCALE) --weights @R@/model-readings/paper-fourier/main/weights_s$*_indep.ckpt --trained @R@/model-readings/paper-fourier/main/run_s$*_indep.tsv --samples @R@/generator-probes/paper-fourier/samples_s$*_indep.tsv --out $@", "-")
UNIT(generator-probes, "plain/probes_s%_joint.tsv", "@R@/model-readings/plain/main/run_s%_joint.tsv", "$(CLI) generator-probes-run --reading plain --seed $* --arm joint --scale $(SCALE) --weights @R@/model-readings/plain/main/weights_s$*_joint.ckpt --trained @R@/model-readings/plain/main/run_s$*_joint.tsv --samples @R@/generator-probes/plain/samples_s$*_joint.tsv --out $@", "-")
UNIT(generator-probes, "plain/probes_s%_indep.tsv", "@R@/model-readings/plain/main/run_s%_indep.tsv", "$(CLI) generator-probes-run --reading plain --seed $* --arm indep --scale $(SCALE) --weights @R@/model-readings/plain/main/weights_s$*_indep.ckpt --trained @R@/model-readings/plain/main/run_s$*_indep.tsv --samples @R@/generator-probes/plain/samples_s$*_indep.tsv --out $@", "-")
UNIT(generator-probes, "stands-x4/probes_s%_joint.tsv", "@R@/generator-sensitivity/stands-x4/main/run_s%_joint.tsv", "$(CLI) generator-probes-run --reading paper --seed $* --arm joint --scale $(SCALE) --weights @R@/generator-sensitivity/stands-x4/main/weights_s$*_joint.ckpt --trained @R@/generator-sensitivity/stands-x4/main/run_s$*_joint.tsv --samples @R@/generator-probes/stands-x4/samples_s$*_joint.tsv --out $@", "-")
UNIT(generator-probes, "stands-x4/probes_s%_indep.tsv", "@R@/generator-sensitivity/stands-x4/main/run_s%_indep.tsv", "$(CLI) generator-probes-run --reading paper --seed $* --arm indep --scale $(SCALE) --weights @R@/generator-sensitivity/stands-x4/main/weights_s$*_indep.ckpt --trained @R@/generator-sensitivity/stands-x4/main/run_s$*_indep.tsv --samples @R@/generator-probes/stands-x4/samples_s$*_indep.tsv --out $@", "-")
UNIT(generator-probes, "teacher/probes.tsv", "", "$(CLI) generator-probes-run --perfect --scale $(SCALE) --samples @R@/generator-probes/teacher/samples.tsv --out $@", "top")
UNIT(generator-probes, "summary.tsv", "$(foreach r,paper pair paper-fourier plain,$(foreach s,$(READING_SEED_LIST),@R@/generator-probes/$(r)/probes_s$(s)_joint.tsv @R@/generator-probes/$(r)/probes_s$(s)_indep.tsv))", "$(CLI) generator-probes-summary --dir @R@ --seeds $(READING_NSEEDS) --out $@", "top")

EXPERIMENT(pointcloud, "E8", "src/exp/exp_stands.c", "-", "src/claims/claim_teacher.c", "figures/hardcore-canopies.gp", "rerun", "hard-core stands at 5, 4 and 3 m: crowns contacting a neighbour, coupled vs uncoupled clearance")
RUN(pointcloud, "pointcloud-figure", exp_pointcloud_figure, "-", "E8: point-cloud stands (5/4/3 m and uncoupled) and pointcloud/stats.tsv")
UNIT(pointcloud, "figure_crowns.tsv", "$(TEACHER_DEPS)", "$(CLI) pointcloud-figure @TEACHER@ --out @R@", "top readings")

EXPERIMENT(hero, "E9", "src/exp/exp_stands.c", "-", "src/claims/claim_teacher.c", "figures/hero.gp", "rerun", "hard-core stands from 3.0 to 6.5 m at beta_train and beta_field")
RUN(hero, "hero-figure", exp_hero_figure, "beta", "E9: crowns of the hero figure (hard-core, L = 36 m, d = 3.0..6.5)")
UNIT(hero, "figure_crowns.tsv", "$(TEACHER_DEPS) @R@/field/calibration.tsv", "$(CLI) hero-figure --beta $$($(CLI) field-beta @R@/field/calibration.tsv) --out @R@", "top")

EXPERIMENT(replicates, "E1", "src/exp/exp_replicates.c", "-", "src/agree/interval_src.c", "-", "rerun", "replicate stands of the numbers resting on one figure stand (E1 figure stand, E8 point-cloud stands, E9 hero stems): the same family, disjoint seeds; their intervals (design.md §6.1)")
RUN(replicates, "replicates-run", exp_replicates_run, "stands", "E1/E8/E9: replicate stands k = 0..N-1 of the one-stand figure numbers (k = 0: the figure's own)")
UNIT(replicates, "figure_stands.tsv", "$(TEACHER_DEPS)", "$(CLI) replicates-run --stands $(REPLICATE_STANDS) --out @R@", "top")

/* the claim tables, in the registry's order (audit/claims.tsv prints them so) */
CLAIMS(claim_table_teacher)
CLAIMS(claim_table_main)
CLAIMS(claim_table_field)
CLAIMS(claim_table_anisotropy)
CLAIMS(claim_table_comparison)
CLAIMS(claim_table_perfect)
CLAIMS(claim_table_probes)
CLAIMS(claim_table_comparison_dart_pair)
CLAIMS(claim_table_pointcloud)
CLAIMS(claim_table_sensitivity)
CLAIMS(claim_table_variants)

#undef EXPERIMENT
#undef COMMAND
#undef RUN
#undef UNIT
#undef VARIANT
#undef CLAIMS
