# experiments.mk: one make target per unit of the full run (included by the
# Makefile). Each experiment block appends its units to REPRODUCE_UNITS and
# gives a rule writing $(RESULTS)/<experiment>/<unit>.tsv via the CLI.

# ---- E3 main experiment + E4 extrapolation (src/exp/exp_main.c) ------------------
# The generator readings (design.md §8 "Readings of the generator"; model.h):
# the preregistered gates judge the paper reading (paper §4.2 as written), in
# $(RESULTS)/paper/{main,extrapolation}; the pair-aware model, added
# after the first verdict, is an extension judged beside it in
# $(RESULTS)/extension-pair; plain and paper-fourier are descriptive rows in
# $(RESULTS)/model-readings/<reading>. One unit per (reading, seed, arm);
# checkpoints in build/ckpt/<scale>/ make a killed unit resume bit-identically.
# Every reading is evaluated at volume v2 (src/exp/mainrun.h), the same for all.
# Each unit also writes the samples behind its W1 (samples_s<seed>_<arm>.tsv)
# and its final weights (weights_s<seed>_<arm>.ckpt, README "Frozen samples
# and weights"); `crownshy main-redraw` draws the samples again from them.
ifeq ($(SCALE),smoke)
MAIN_NSEEDS := 2
READING_NSEEDS := 1
else
MAIN_NSEEDS := $(shell awk '$$1=="seeds"{print $$2}' gates/main.gate)
READING_NSEEDS := 4
endif
MAIN_VOLUME := v2
MAIN_SEED_LIST := $(shell seq -f '%02g' 1 $(MAIN_NSEEDS))
READING_SEED_LIST := $(shell seq -f '%02g' 1 $(READING_NSEEDS))
PAPER := $(RESULTS)/paper
MAIN_RUNS := $(foreach s,$(MAIN_SEED_LIST),$(PAPER)/main/run_s$(s)_joint.tsv $(PAPER)/main/run_s$(s)_indep.tsv)

# main_unit(dir, reading, ckpt prefix, arm): main-run of one reading into dir/main
define MAIN_UNIT
$(1)/main/run_s%_$(4).tsv: | $$(CLI)
	@mkdir -p $$(B)/ckpt/$$(SCALE)
	$$(CLI) main-run --reading $(2) --volume $$(MAIN_VOLUME) --seed $$* --arm $(4) --scale $$(SCALE) --ckpt $$(B)/ckpt/$$(SCALE)/$(3)main_s$$*_$(4).ckpt \
	  --samples $(1)/main/samples_s$$*_$(4).tsv --weights $(1)/main/weights_s$$*_$(4).ckpt --out $$@
endef
$(foreach a,joint indep,$(eval $(call MAIN_UNIT,$(PAPER),paper,paper-,$(a))))
$(PAPER)/main/baselines.tsv: | $(CLI)
	$(CLI) main-baselines --volume $(MAIN_VOLUME) --scale $(SCALE) --samples $(PAPER)/main/samples_baselines.tsv --out $@
$(PAPER)/main/runs.tsv: $(MAIN_RUNS) $(PAPER)/main/baselines.tsv | $(CLI)
	$(CLI) main-summary --dir $(PAPER) --seeds $(MAIN_NSEEDS)

# The extension: the pair-aware model. Its units as first run (training and
# evaluation at volume v1, the frozen weights) in extension-pair/main/v1, then
# evaluated from those weights at the volume of every reading (main-eval).
EXT_PAIR := $(RESULTS)/extension-pair
EXT_PAIR_RUNS := $(foreach s,$(MAIN_SEED_LIST),$(EXT_PAIR)/main/run_s$(s)_joint.tsv $(EXT_PAIR)/main/run_s$(s)_indep.tsv)
define PAIR_UNIT
$(EXT_PAIR)/main/v1/run_s%_$(1).tsv: | $$(CLI)
	@mkdir -p $$(B)/ckpt/$$(SCALE)
	$$(CLI) main-run --reading pair --volume v1 --seed $$* --arm $(1) --scale $$(SCALE) --ckpt $$(B)/ckpt/$$(SCALE)/pair-main_s$$*_$(1).ckpt \
	  --samples $(EXT_PAIR)/main/v1/samples_s$$*_$(1).tsv --weights $(EXT_PAIR)/main/v1/weights_s$$*_$(1).ckpt --out $$@
$(EXT_PAIR)/main/run_s%_$(1).tsv: $(EXT_PAIR)/main/v1/run_s%_$(1).tsv | $$(CLI)
	$$(CLI) main-eval --reading pair --volume $$(MAIN_VOLUME) --seed $$* --arm $(1) --scale $$(SCALE) --weights $(EXT_PAIR)/main/v1/weights_s$$*_$(1).ckpt \
	  --trained $$< --samples $(EXT_PAIR)/main/samples_s$$*_$(1).tsv --out $$@
endef
$(foreach a,joint indep,$(eval $(call PAIR_UNIT,$(a))))
.PRECIOUS: $(EXT_PAIR)/main/v1/run_s%_joint.tsv $(EXT_PAIR)/main/v1/run_s%_indep.tsv
$(EXT_PAIR)/main/runs.tsv: $(EXT_PAIR_RUNS) | $(CLI)
	$(CLI) main-summary --dir $(EXT_PAIR) --seeds $(MAIN_NSEEDS)

# The descriptive readings, READING_NSEEDS seeds each.
MODEL_READINGS := plain paper-fourier
MR_DIR := $(RESULTS)/model-readings
$(foreach r,$(MODEL_READINGS),$(foreach a,joint indep,$(eval $(call MAIN_UNIT,$(MR_DIR)/$(r),$(r),$(r)-,$(a)))))
MR_RUNS = $(foreach s,$(READING_SEED_LIST),$(MR_DIR)/$(1)/main/run_s$(s)_joint.tsv $(MR_DIR)/$(1)/main/run_s$(s)_indep.tsv)
$(foreach r,$(MODEL_READINGS),$(eval $(MR_DIR)/$(r)/main/runs.tsv: $(call MR_RUNS,$(r)) | $$(CLI) ; $$(CLI) main-summary --dir $(MR_DIR)/$(r) --seeds $(READING_NSEEDS)))

# E7 and the dart probe as distributions over fresh patches (src/exp/exp_compdist.h),
# seed-1 models of the paper reading and of the pair extension.
$(PAPER)/comparison/dist_summary.tsv: $(PAPER)/main/run_s01_joint.tsv $(PAPER)/main/run_s01_indep.tsv | $(CLI)
	$(CLI) comp-dist --joint $(PAPER)/main/weights_s01_joint.ckpt --indep $(PAPER)/main/weights_s01_indep.ckpt --out $(PAPER)
$(EXT_PAIR)/comparison/dist_summary.tsv: $(EXT_PAIR)/main/v1/run_s01_joint.tsv $(EXT_PAIR)/main/v1/run_s01_indep.tsv | $(CLI)
	$(CLI) comp-dist --joint $(EXT_PAIR)/main/v1/weights_s01_joint.ckpt --indep $(EXT_PAIR)/main/v1/weights_s01_indep.ckpt --out $(EXT_PAIR)
REPRODUCE_UNITS += $(PAPER)/comparison/dist_summary.tsv $(EXT_PAIR)/comparison/dist_summary.tsv
# The readings table (src/claims/model_readings.h) from every reading's runs.
$(MR_DIR)/summary.tsv: $(PAPER)/main/runs.tsv $(EXT_PAIR)/main/runs.tsv $(foreach r,$(MODEL_READINGS),$(MR_DIR)/$(r)/main/runs.tsv) | $(CLI)
	$(CLI) model-readings --dir $(RESULTS) --out $@
.PHONY: main-experiment main-extension model-readings
main-experiment: $(PAPER)/main/runs.tsv
main-extension: $(EXT_PAIR)/main/runs.tsv
model-readings: $(MR_DIR)/summary.tsv
REPRODUCE_UNITS += $(PAPER)/main/runs.tsv $(EXT_PAIR)/main/runs.tsv
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

# ---- E7 comparison patch and dart probe (src/exp/exp_comp.c): seed-1 models of the pair extension ----
$(RESULTS)/comparison/patch.tsv: $(EXT_PAIR)/main/v1/run_s01_joint.tsv $(EXT_PAIR)/main/v1/run_s01_indep.tsv | $(CLI)
	$(CLI) comp-run --joint $(EXT_PAIR)/main/v1/weights_s01_joint.ckpt --indep $(EXT_PAIR)/main/v1/weights_s01_indep.ckpt --out $(RESULTS)
REPRODUCE_UNITS += $(RESULTS)/comparison/patch.tsv

# ---- E0 readings (design.md §7 E0; src/claims/readings.c) -----------------------------
# The cheap experiments under each reading of the paper, by the same units with
# switches (never copied files): run <teacher>-<layout> in $(RESULTS)/readings/<run>/
# (t1 = teacher-1, t2 = teacher-2; r1 = 5 m on 60 m, r2 = 4 m on 36 m), then
# readings/summary.tsv (quantity x reading, beside the paper's values).
# Stand counts as in the adopted run (smoke: the smoke counts).
READINGS_DIR := $(RESULTS)/readings
READING_RUNS := t1-r1 t2-r1 t1-r2 t2-r2
reading_teacher = $(if $(filter t1-%,$(1)),teacher-1,teacher-2)
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
