# main-pair.gp — the pair-aware generator (design.md §8: an extension added
# after the first verdict, judged by the same thresholds beside the paper
# reading): its E3/E4 runs, drawn by figures/main.gpi like Fig. main.
# Usage: gnuplot figures/main-pair.gp   (dir='build/results' to draw unfrozen data)
# data: frozen/main/runs.tsv
# data: frozen/main/baselines.tsv
# data: frozen/extrapolation/runs.tsv
rd = '.'
name = 'main-pair'
heading = "the pair extension (volume v1): joint vs independent"
load 'figures/main.gpi'
