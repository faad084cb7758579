# main-pair.gp — the pair-aware generator (design.md §8: an extension added
# after the first verdict, judged by the same thresholds beside the paper
# reading): its twelve models re-evaluated at volume 96-stands, drawn by
# figures/main.gpi like Fig. main.
# Usage: gnuplot figures/main-pair.gp   (dir='build/results' to draw unfrozen data)
# data: frozen/extension-pair/main/runs.tsv
# data: frozen/extension-pair/main/baselines.tsv
# data: frozen/extension-pair/extrapolation/runs.tsv
rd = 'extension-pair'
name = 'main-pair'
heading = "the pair extension (gates beside the paper reading): joint vs independent"
load 'figures/main.gpi'
