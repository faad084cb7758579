# experiments.mk: the scale of the full run (included by the Makefile). The
# units themselves, their rules, REPRODUCE_UNITS and DEEP_UNITS are generated
# from the experiment manifest src/base/manifest.h into $(B)/manifest.mk
# (src/base/manifest.sh make); nothing here lists an experiment or a unit.
# $(CLI) is an order-only prerequisite of every unit: rebuilding the binary
# does not invalidate finished units.

# E3/E4 (src/exp/exp_main.c): one unit per (seed, arm); checkpoints in
# build/ckpt/<scale>/ make a killed unit resume bit-identically. Each unit
# also writes the samples behind its W1 and its final weights, from which
# `crownshy main-redraw` draws the samples again.
ifeq ($(SCALE),smoke)
MAIN_NSEEDS := 2
else
MAIN_NSEEDS := $(shell awk '$$1=="seeds"{print $$2}' gates/main.gate)
endif
MAIN_SEED_LIST := $(shell seq -f '%02g' 1 $(MAIN_NSEEDS))
# the intermediate generator readings (plain, paper-fourier; design.md §8): descriptive rows
ifeq ($(SCALE),smoke)
READING_NSEEDS := 1
else
READING_NSEEDS := 4
endif
READING_SEED_LIST := $(shell seq -f '%02g' 1 $(READING_NSEEDS))
# the generator sensitivity (design.md §8.2): four times the plan's training
# stands per spacing and four times its epochs, at either scale (full: 12 and
# 300; smoke: 1 and 4); width, blocks and learning rate are the same at both
ifeq ($(SCALE),smoke)
GENSENS_STANDS := 4
GENSENS_EPOCHS := 16
else
GENSENS_STANDS := 48
GENSENS_EPOCHS := 1200
endif

# E1, E2, E8, E9 (teacher): 8 stands per cell at full scale, 1 at smoke scale.
ifeq ($(SCALE),smoke)
TEACHER_STANDS := 1
else
TEACHER_STANDS := 8
endif
TEACHER_DEPS := gates/mechanism.gate gates/irreducibility.gate

# Replicate stands of the one-stand figure numbers (design.md §6.1): 100 per
# family at full scale, 3 at smoke scale.
# E5, E6: 28 held-out stands (E5, E6 lattice, E6 held-out) and 12 per sweep
# level at full scale; 3 and 2 at smoke scale. Calibration seeds come from
# gates/field.gate; E6 and E2's field rows run at beta_field, so they depend
# on the E5 calibration.
ifeq ($(SCALE),smoke)
FIELD_STANDS := 3
REPLICATE_STANDS := 3
ANISO_SWEEP_STANDS := 2
else
FIELD_STANDS := 28
REPLICATE_STANDS := 100
ANISO_SWEEP_STANDS := 12
endif

# E0 sensitivity (src/exp/exp_sensitivity.c): E1 and E2 at 4 stands per cell (the
# full run: 8; the centre unit uses the same count, so the columns compare),
# E5/E6 at the full run's counts; smoke 1.
ifeq ($(SCALE),smoke)
SENS_STANDS := 1
else
SENS_STANDS := 4
endif
SENS_ARGS = --stands $(SENS_STANDS) --field-stands $(FIELD_STANDS) --sweep-stands $(ANISO_SWEEP_STANDS)
SENS_DEPS := $(TEACHER_DEPS) gates/field.gate gates/anisotropy.gate gates/main.gate

$(B)/manifest.mk: src/base/manifest.h src/base/manifest.sh
	@mkdir -p $(dir $@)
	@bash src/base/manifest.sh make > $@.tmp && mv $@.tmp $@
-include $(B)/manifest.mk
