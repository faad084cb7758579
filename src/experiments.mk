# experiments.mk: one make target per unit of the full run (included by the
# Makefile). Each experiment block appends its units to REPRODUCE_UNITS and
# gives a rule writing $(RESULTS)/<experiment>/<unit>.tsv via the CLI.
