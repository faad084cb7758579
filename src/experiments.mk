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
