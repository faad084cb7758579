# experiments.mk: one make target per unit of the full run (included by the
# Makefile). Each experiment block appends its units to REPRODUCE_UNITS and
# gives a rule writing $(RESULTS)/<experiment>/<unit>.tsv via the CLI.

# ---- E3 main experiment + E4 extrapolation (src/exp/exp_main.c) ------------------
# One unit per (seed, arm); checkpoints in build/ckpt/<scale>/ make a killed
# unit resume bit-identically. `make -j2 reproduce` runs two units at a time.
# Each unit also writes the samples behind its W1 (samples_s<seed>_<arm>.tsv)
# and its final weights (weights_s<seed>_<arm>.ckpt, README "Frozen samples
# and weights"); `crownshy main-redraw` draws the samples again from them.
ifeq ($(SCALE),smoke)
MAIN_NSEEDS := 2
else
MAIN_NSEEDS := $(shell awk '$$1=="seeds"{print $$2}' gates/main.gate)
endif
MAIN_SEED_LIST := $(shell seq -f '%02g' 1 $(MAIN_NSEEDS))
MAIN_RUNS := $(foreach s,$(MAIN_SEED_LIST),$(RESULTS)/main/run_s$(s)_joint.tsv $(RESULTS)/main/run_s$(s)_indep.tsv)

$(RESULTS)/main/run_s%_joint.tsv: | $(CLI)
	@mkdir -p $(B)/ckpt/$(SCALE)
	$(CLI) main-run --seed $* --arm joint --scale $(SCALE) --ckpt $(B)/ckpt/$(SCALE)/main_s$*_joint.ckpt \
	  --samples $(RESULTS)/main/samples_s$*_joint.tsv --weights $(RESULTS)/main/weights_s$*_joint.ckpt --out $@
$(RESULTS)/main/run_s%_indep.tsv: | $(CLI)
	@mkdir -p $(B)/ckpt/$(SCALE)
	$(CLI) main-run --seed $* --arm indep --scale $(SCALE) --ckpt $(B)/ckpt/$(SCALE)/main_s$*_indep.ckpt \
	  --samples $(RESULTS)/main/samples_s$*_indep.tsv --weights $(RESULTS)/main/weights_s$*_indep.ckpt --out $@
$(RESULTS)/main/baselines.tsv: | $(CLI)
	$(CLI) main-baselines --scale $(SCALE) --samples $(RESULTS)/main/samples_baselines.tsv --out $@
$(RESULTS)/main/runs.tsv: $(MAIN_RUNS) $(RESULTS)/main/baselines.tsv | $(CLI)
	$(CLI) main-summary --dir $(RESULTS) --seeds $(MAIN_NSEEDS)

.PHONY: main-experiment
main-experiment: $(RESULTS)/main/runs.tsv
REPRODUCE_UNITS += $(RESULTS)/main/runs.tsv
# ---- E1 mechanism, E2 irreducibility (teacher) and teacher figure data ----------
# 8 stands per cell at full scale, 1 at smoke scale (each unit is one process).
ifeq ($(SCALE),smoke)
TEACHER_STANDS := 1
else
TEACHER_STANDS := 8
endif
# $(CLI) is order-only below: rebuilding the binary must not invalidate finished units.
TEACHER_DEPS := gates/mechanism.gate gates/irreducibility.gate
MECH_UNITS := $(RESULTS)/mechanism/sweep.tsv $(RESULTS)/mechanism/ablation.tsv $(RESULTS)/mechanism/figure_crowns.tsv
IRRED_UNITS := $(RESULTS)/irreducibility/perturb_train.tsv $(RESULTS)/irreducibility/refine_train.tsv \
               $(RESULTS)/irreducibility/reduction_train.tsv
TEACHER_FIG_UNITS := $(RESULTS)/hero/figure_crowns.tsv $(RESULTS)/pointcloud/figure_crowns.tsv
REPRODUCE_UNITS += $(MECH_UNITS) $(IRRED_UNITS) $(TEACHER_FIG_UNITS)

$(RESULTS)/mechanism/sweep.tsv: $(TEACHER_DEPS) | $(CLI)
	$(CLI) run mechanism-sweep --stands $(TEACHER_STANDS) --out $(RESULTS)
$(RESULTS)/mechanism/ablation.tsv: $(TEACHER_DEPS) | $(CLI)
	$(CLI) run mechanism-ablation --stands $(TEACHER_STANDS) --out $(RESULTS)
$(RESULTS)/mechanism/figure_crowns.tsv: $(TEACHER_DEPS) | $(CLI)
	$(CLI) run fig-mechanism --out $(RESULTS)
# the Mech* macros on the figure stand: written by the fig-mechanism unit
$(RESULTS)/mechanism/figure_stats.tsv: $(RESULTS)/mechanism/figure_crowns.tsv
	@test -f $@
$(RESULTS)/irreducibility/perturb_train.tsv: $(TEACHER_DEPS) | $(CLI)
	$(CLI) run irreducibility-perturb --stands $(TEACHER_STANDS) --out $(RESULTS)
$(RESULTS)/irreducibility/refine_train.tsv: $(TEACHER_DEPS) | $(CLI)
	$(CLI) run irreducibility-refine --stands $(TEACHER_STANDS) --out $(RESULTS)
$(RESULTS)/irreducibility/reduction_train.tsv: $(TEACHER_DEPS) | $(CLI)
	$(CLI) run irreducibility-reduction --stands $(TEACHER_STANDS) --out $(RESULTS)
# second row at beta_field (E5): recomputed from the field calibration table
$(RESULTS)/hero/figure_crowns.tsv: $(TEACHER_DEPS) $(RESULTS)/field/calibration.tsv | $(CLI)
	$(CLI) run fig-hero --beta $$($(CLI) field-beta $(RESULTS)/field/calibration.tsv) --out $(RESULTS)
$(RESULTS)/pointcloud/figure_crowns.tsv: $(TEACHER_DEPS) | $(CLI)
	$(CLI) run fig-pointcloud --out $(RESULTS)

# ---- E5 field validation (src/exp/exp_field.c), E6 anisotropy (src/exp/exp_aniso.c) --
# Stand counts: full run 28 held-out stands (E5, E6 lattice, E6 held-out) and 12
# per sweep level; smoke 3 and 2. Calibration seeds come from gates/field.gate.
# E6 runs at beta_field, so every E6 unit depends on the E5 calibration.
ifeq ($(SCALE),smoke)
FIELD_STANDS := 3
ANISO_SWEEP_STANDS := 2
else
FIELD_STANDS := 28
ANISO_SWEEP_STANDS := 12
endif
FIELD_CAL := $(RESULTS)/field/calibration.tsv
$(FIELD_CAL): | $(CLI)
	$(CLI) field-calibrate --out $@
$(RESULTS)/field/heldout.tsv: $(FIELD_CAL) | $(CLI)
	$(CLI) field-heldout --calibration $(FIELD_CAL) --stands $(FIELD_STANDS) --out $@
$(RESULTS)/anisotropy/lattice.tsv: $(FIELD_CAL) | $(CLI)
	$(CLI) aniso-lattice --calibration $(FIELD_CAL) --stands $(FIELD_STANDS) --out $@
$(RESULTS)/anisotropy/hardcore.tsv: $(FIELD_CAL) | $(CLI)
	$(CLI) aniso-hardcore --calibration $(FIELD_CAL) --stands $(ANISO_SWEEP_STANDS) --out $@
$(RESULTS)/anisotropy/jitter.tsv: $(FIELD_CAL) | $(CLI)
	$(CLI) aniso-jitter --calibration $(FIELD_CAL) --stands $(ANISO_SWEEP_STANDS) --out $@
$(RESULTS)/anisotropy/jitter_calibration.tsv: $(RESULTS)/anisotropy/jitter.tsv | $(CLI)
	$(CLI) aniso-jitter-calibrate --sweep $< --out $@
$(RESULTS)/anisotropy/heldout.tsv: $(FIELD_CAL) $(RESULTS)/anisotropy/jitter_calibration.tsv | $(CLI)
	$(CLI) aniso-heldout --calibration $(FIELD_CAL) --jitter-calibration $(RESULTS)/anisotropy/jitter_calibration.tsv --stands $(FIELD_STANDS) --out $@
REPRODUCE_UNITS += $(FIELD_CAL) $(RESULTS)/field/heldout.tsv $(RESULTS)/anisotropy/lattice.tsv \
  $(RESULTS)/anisotropy/hardcore.tsv $(RESULTS)/anisotropy/jitter.tsv \
  $(RESULTS)/anisotropy/jitter_calibration.tsv $(RESULTS)/anisotropy/heldout.tsv
.PHONY: field anisotropy
field: $(FIELD_CAL) $(RESULTS)/field/heldout.tsv
anisotropy: $(RESULTS)/anisotropy/lattice.tsv $(RESULTS)/anisotropy/hardcore.tsv $(RESULTS)/anisotropy/heldout.tsv
# E2 irreducibility again at the field operating point (design.md §7 E2 "at beta_train
# and at beta_field (E5)"): beta_field is recomputed from the E5 calibration table.
IRRED_FIELD_UNITS := $(RESULTS)/irreducibility/perturb_field.tsv $(RESULTS)/irreducibility/refine_field.tsv \
                     $(RESULTS)/irreducibility/reduction_field.tsv
$(RESULTS)/irreducibility/perturb_field.tsv: $(FIELD_CAL) | $(CLI)
	$(CLI) run irreducibility-perturb --stands $(TEACHER_STANDS) --beta $$($(CLI) field-beta $(FIELD_CAL)) --tag field --out $(RESULTS)
$(RESULTS)/irreducibility/refine_field.tsv: $(FIELD_CAL) | $(CLI)
	$(CLI) run irreducibility-refine --stands $(TEACHER_STANDS) --beta $$($(CLI) field-beta $(FIELD_CAL)) --tag field --out $(RESULTS)
$(RESULTS)/irreducibility/reduction_field.tsv: $(FIELD_CAL) | $(CLI)
	$(CLI) run irreducibility-reduction --stands $(TEACHER_STANDS) --beta $$($(CLI) field-beta $(FIELD_CAL)) --tag field --out $(RESULTS)
REPRODUCE_UNITS += $(IRRED_FIELD_UNITS)

# ---- E7 comparison patch and dart probe (src/exp/exp_comp.c): E3 seed-1 models ----
$(RESULTS)/comparison/patch.tsv: $(RESULTS)/main/run_s01_joint.tsv $(RESULTS)/main/run_s01_indep.tsv | $(CLI)
	$(CLI) comp-run --joint $(RESULTS)/main/weights_s01_joint.ckpt --indep $(RESULTS)/main/weights_s01_indep.ckpt --out $(RESULTS)
REPRODUCE_UNITS += $(RESULTS)/comparison/patch.tsv

# ---- E0 readings (design.md §7 E0; src/claims/readings.c) -----------------------------
# The cheap experiments under each reading of the paper, by the same units with
# switches (never copied files): run <teacher>-<layout> in $(RESULTS)/readings/<run>/
# (t1 = teacher-1, t2 = teacher-2; r1 = 5 m on 60 m, r2 = 4 m on 36 m), then
# readings/summary.tsv (quantity x reading, beside the paper's values).
# Stand counts as in the adopted run (smoke: the smoke counts).
READINGS_DIR := $(RESULTS)/readings
# t2a / t2t: teacher-2 with the other die-back readings (-arc: the contact arc
# s-1..s+1 dies back too; -target: beta of the target length, against Eq. 3).
READING_RUNS := t1-r1 t2-r1 t1-r2 t2-r2 t2a-r2 t2t-r2
reading_teacher = $(if $(filter t1-%,$(1)),teacher-1,$(if $(filter t2a-%,$(1)),teacher-2-arc,$(if $(filter t2t-%,$(1)),teacher-2-target,teacher-2)))
reading_layout = $(if $(filter %-r1,$(1)),r1,r2)
define READING_UNITS
$(READINGS_DIR)/$(1)/mechanism/sweep.tsv: $$(TEACHER_DEPS) | $$(CLI)
	$$(CLI) run mechanism-sweep --teacher $(call reading_teacher,$(1)) --stands $$(TEACHER_STANDS) --out $(READINGS_DIR)/$(1)
$(READINGS_DIR)/$(1)/mechanism/ablation.tsv: $$(TEACHER_DEPS) | $$(CLI)
	$$(CLI) run mechanism-ablation --teacher $(call reading_teacher,$(1)) --stands $$(TEACHER_STANDS) --out $(READINGS_DIR)/$(1)
$(READINGS_DIR)/$(1)/mechanism/figure_crowns.tsv: $$(TEACHER_DEPS) | $$(CLI)
	$$(CLI) run fig-mechanism --teacher $(call reading_teacher,$(1)) --out $(READINGS_DIR)/$(1)
$(READINGS_DIR)/$(1)/pointcloud/figure_crowns.tsv: $$(TEACHER_DEPS) | $$(CLI)
	$$(CLI) run fig-pointcloud --teacher $(call reading_teacher,$(1)) --out $(READINGS_DIR)/$(1)
$(READINGS_DIR)/$(1)/field/calibration.tsv: | $$(CLI)
	$$(CLI) field-calibrate --teacher $(call reading_teacher,$(1)) --layout $(call reading_layout,$(1)) --out $$@
$(READINGS_DIR)/$(1)/field/heldout.tsv: $(READINGS_DIR)/$(1)/field/calibration.tsv | $$(CLI)
	$$(CLI) field-heldout --teacher $(call reading_teacher,$(1)) --layout $(call reading_layout,$(1)) --calibration $$< --stands $$(FIELD_STANDS) --out $$@
$(READINGS_DIR)/$(1)/anisotropy/lattice.tsv: $(READINGS_DIR)/$(1)/field/calibration.tsv | $$(CLI)
	$$(CLI) aniso-lattice --teacher $(call reading_teacher,$(1)) --layout $(call reading_layout,$(1)) --calibration $$< --stands $$(FIELD_STANDS) --out $$@
$(READINGS_DIR)/$(1)/anisotropy/hardcore.tsv: $(READINGS_DIR)/$(1)/field/calibration.tsv | $$(CLI)
	$$(CLI) aniso-hardcore --teacher $(call reading_teacher,$(1)) --layout $(call reading_layout,$(1)) --calibration $$< --stands $$(ANISO_SWEEP_STANDS) --out $$@
$(READINGS_DIR)/$(1)/anisotropy/jitter.tsv: $(READINGS_DIR)/$(1)/field/calibration.tsv | $$(CLI)
	$$(CLI) aniso-jitter --teacher $(call reading_teacher,$(1)) --layout $(call reading_layout,$(1)) --calibration $$< --stands $$(ANISO_SWEEP_STANDS) --out $$@
$(READINGS_DIR)/$(1)/anisotropy/jitter_calibration.tsv: $(READINGS_DIR)/$(1)/anisotropy/jitter.tsv | $$(CLI)
	$$(CLI) aniso-jitter-calibrate --sweep $$< --out $$@
$(READINGS_DIR)/$(1)/anisotropy/heldout.tsv: $(READINGS_DIR)/$(1)/field/calibration.tsv $(READINGS_DIR)/$(1)/anisotropy/jitter_calibration.tsv | $$(CLI)
	$$(CLI) aniso-heldout --teacher $(call reading_teacher,$(1)) --layout $(call reading_layout,$(1)) --calibration $(READINGS_DIR)/$(1)/field/calibration.tsv --jitter-calibration $(READINGS_DIR)/$(1)/anisotropy/jitter_calibration.tsv --stands $$(FIELD_STANDS) --out $$@
READING_TARGETS += $(addprefix $(READINGS_DIR)/$(1)/,mechanism/sweep.tsv mechanism/ablation.tsv mechanism/figure_crowns.tsv \
  pointcloud/figure_crowns.tsv field/calibration.tsv field/heldout.tsv anisotropy/lattice.tsv anisotropy/hardcore.tsv \
  anisotropy/jitter_calibration.tsv anisotropy/heldout.tsv)
endef
$(foreach r,$(READING_RUNS),$(eval $(call READING_UNITS,$(r))))
$(READINGS_DIR)/summary.tsv: $(READING_TARGETS) audit/claims.tsv | $(CLI)
	$(CLI) readings-summary --dir $(READINGS_DIR) --out $@
.PHONY: readings
readings: $(READINGS_DIR)/summary.tsv
REPRODUCE_UNITS += $(READINGS_DIR)/summary.tsv

# ---- E0 sensitivity (design.md §7 E0 "sensitivity"; src/cli/cli_sens.c, src/claims/sens.c) --
# One make unit per (unstated choice, value) and one centre unit (the design's
# values), each `crownshy sens-run` into $(SENS_DIR)/<choice>_<value>/ (resumable:
# finished tables are kept; unit.tsv is written last). E1/E2 at SENS_STANDS stands
# per cell (the full run uses 8; the centre run uses the same reduced count, so the
# columns compare), E5/E6 at the full run's counts. Then sensitivity/summary.tsv.
# The values are those of src/base/unstated.c, printed with %g (tests/test_sens.c
# checks that the two lists agree).
SENS_DIR := $(RESULTS)/sensitivity
ifeq ($(SCALE),smoke)
SENS_STANDS := 1
else
SENS_STANDS := 4
endif
SENS_VARIANTS := crown_R:3 crown_R:5 crown_spread:0.05 crown_spread:0.25 height_sd:2 height_sd:6 \
  lobing:0.1 lobing:0.3 growth_N:24 growth_N:96 start:0.02 start:0.1 \
  fig_hardcore:0.3 fig_hardcore:0.4 fig_hardcore:0.6 fig_hardcore:0.7 \
  field_d:3 field_d:3.5 field_d:4.5 field_d:5 \
  field_L:28 field_L:32 field_L:44 field_L:60
SENS_ARGS = --stands $(SENS_STANDS) --field-stands $(FIELD_STANDS) --sweep-stands $(ANISO_SWEEP_STANDS)
SENS_DEPS := $(TEACHER_DEPS) gates/field.gate gates/anisotropy.gate gates/main.gate
define SENS_UNIT
$(SENS_DIR)/$(1)_$(2)/unit.tsv: $$(SENS_DEPS) | $$(CLI)
	$$(CLI) sens-run --choice $(1) --value $(2) $$(SENS_ARGS) --out $$(@D)
SENS_TARGETS += $(SENS_DIR)/$(1)_$(2)/unit.tsv
endef
$(foreach v,$(SENS_VARIANTS),$(eval $(call SENS_UNIT,$(word 1,$(subst :, ,$(v))),$(word 2,$(subst :, ,$(v))))))
$(SENS_DIR)/centre/unit.tsv: $(SENS_DEPS) | $(CLI)
	$(CLI) sens-run $(SENS_ARGS) --out $(@D)
SENS_TARGETS += $(SENS_DIR)/centre/unit.tsv
$(SENS_DIR)/summary.tsv: $(SENS_TARGETS) audit/claims.tsv | $(CLI)
	$(CLI) sens-summary --dir $(SENS_DIR) --out $@
.PHONY: sensitivity
sensitivity: $(SENS_DIR)/summary.tsv
REPRODUCE_UNITS += $(SENS_DIR)/summary.tsv
