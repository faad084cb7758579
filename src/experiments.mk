# experiments.mk: one make target per unit of the full run (included by the
# Makefile). Each experiment block appends its units to REPRODUCE_UNITS and
# gives a rule writing $(RESULTS)/<experiment>/<unit>.tsv via the CLI.

# ---- E3 main experiment + E4 extrapolation (src/exp_main.c) ------------------
# One unit per (seed, arm); checkpoints in build/ckpt/<scale>/ make a killed
# unit resume bit-identically. `make -j2 reproduce` runs two units at a time.
ifeq ($(SCALE),smoke)
MAIN_NSEEDS := 2
else
MAIN_NSEEDS := $(shell awk '$$1=="seeds"{print $$2}' gates/main.gate)
endif
MAIN_SEED_LIST := $(shell seq -f '%02g' 1 $(MAIN_NSEEDS))
MAIN_RUNS := $(foreach s,$(MAIN_SEED_LIST),$(RESULTS)/main/run_s$(s)_joint.tsv $(RESULTS)/main/run_s$(s)_indep.tsv)

$(RESULTS)/main/run_s%_joint.tsv: | $(CLI)
	@mkdir -p $(B)/ckpt/$(SCALE)
	$(CLI) main-run --seed $* --arm joint --scale $(SCALE) --ckpt $(B)/ckpt/$(SCALE)/main_s$*_joint.ckpt --out $@
$(RESULTS)/main/run_s%_indep.tsv: | $(CLI)
	@mkdir -p $(B)/ckpt/$(SCALE)
	$(CLI) main-run --seed $* --arm indep --scale $(SCALE) --ckpt $(B)/ckpt/$(SCALE)/main_s$*_indep.ckpt --out $@
$(RESULTS)/main/baselines.tsv: | $(CLI)
	$(CLI) main-baselines --scale $(SCALE) --out $@
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
TEACHER_DEPS := $(CLI) gates/mechanism.gate gates/irreducibility.gate
MECH_UNITS := $(RESULTS)/mechanism/sweep.tsv $(RESULTS)/mechanism/ablation.tsv $(RESULTS)/mechanism/figure_crowns.tsv
IRRED_UNITS := $(RESULTS)/irreducibility/perturb_train.tsv $(RESULTS)/irreducibility/refine_train.tsv \
               $(RESULTS)/irreducibility/reduction_train.tsv
TEACHER_FIG_UNITS := $(RESULTS)/hero/figure_crowns.tsv $(RESULTS)/pointcloud/figure_crowns.tsv
REPRODUCE_UNITS += $(MECH_UNITS) $(IRRED_UNITS) $(TEACHER_FIG_UNITS)

$(RESULTS)/mechanism/sweep.tsv: $(TEACHER_DEPS)
	$(CLI) run mechanism-sweep --stands $(TEACHER_STANDS) --out $(RESULTS)
$(RESULTS)/mechanism/ablation.tsv: $(TEACHER_DEPS)
	$(CLI) run mechanism-ablation --stands $(TEACHER_STANDS) --out $(RESULTS)
$(RESULTS)/mechanism/figure_crowns.tsv: $(TEACHER_DEPS)
	$(CLI) run fig-mechanism --out $(RESULTS)
$(RESULTS)/irreducibility/perturb_train.tsv: $(TEACHER_DEPS)
	$(CLI) run irreducibility-perturb --stands $(TEACHER_STANDS) --out $(RESULTS)
$(RESULTS)/irreducibility/refine_train.tsv: $(TEACHER_DEPS)
	$(CLI) run irreducibility-refine --stands $(TEACHER_STANDS) --out $(RESULTS)
$(RESULTS)/irreducibility/reduction_train.tsv: $(TEACHER_DEPS)
	$(CLI) run irreducibility-reduction --stands $(TEACHER_STANDS) --out $(RESULTS)
$(RESULTS)/hero/figure_crowns.tsv: $(TEACHER_DEPS)
	$(CLI) run fig-hero --out $(RESULTS) $(if $(BETA_FIELD),--beta $(BETA_FIELD))
$(RESULTS)/pointcloud/figure_crowns.tsv: $(TEACHER_DEPS)
	$(CLI) run fig-pointcloud --out $(RESULTS)

# E2 at the field die-back (SPEC §7 E2 "at beta_train and at beta_field"): set
# BETA_FIELD to the E5 calibration (e.g. make reproduce BETA_FIELD=0.19) and
# the three field units are registered; the hero figure then gets its second row.
ifneq ($(strip $(BETA_FIELD)),)
IRRED_FIELD_UNITS := $(RESULTS)/irreducibility/perturb_field.tsv $(RESULTS)/irreducibility/refine_field.tsv \
                     $(RESULTS)/irreducibility/reduction_field.tsv
REPRODUCE_UNITS += $(IRRED_FIELD_UNITS)
$(RESULTS)/irreducibility/%_field.tsv: $(TEACHER_DEPS)
	$(CLI) run irreducibility-$* --stands $(TEACHER_STANDS) --beta $(BETA_FIELD) --tag field --out $(RESULTS)
endif
