# experiments.mk: one make target per unit of the full run (included by the
# Makefile). Each experiment block appends its units to REPRODUCE_UNITS and
# gives a rule writing $(RESULTS)/<experiment>/<unit>.tsv via the CLI.

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
	$(CLI) run fig-hero --out $(RESULTS)
$(RESULTS)/pointcloud/figure_crowns.tsv: $(TEACHER_DEPS)
	$(CLI) run fig-pointcloud --out $(RESULTS)
