# main.gp — Fig. main (reference paper §5.1-5.2): the paper reading, the
# generator as the reference paper describes it and the reading the
# preregistered main and extrapolation gates judge (design.md §8), at
# evaluation volume 96-stands; drawn by figures/main.gpi.
# Usage: gnuplot figures/main.gp   (dir='build/results' to draw unfrozen data)
# data: frozen/paper-reading/main/runs.tsv
# data: frozen/paper-reading/main/baselines.tsv
# data: frozen/paper-reading/extrapolation/runs.tsv
rd = 'paper-reading'
name = 'main'
heading = "the paper reading (gated): joint vs independent, matched capacity"
load 'figures/main.gpi'
