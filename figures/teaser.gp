# teaser.gp — Fig. teaser (reference paper §3.1): the paper reading, the
# generator as the reference paper describes it (seed 1); drawn by
# figures/teaser.gpi from the figure patch of its E7 distribution.
# Usage: gnuplot figures/teaser.gp   (dir='build/results' to draw unfrozen data)
# data: frozen/paper-reading/comparison/figure_crowns.tsv
# data: frozen/paper-reading/comparison/dist_patches.tsv
rd = 'paper-reading'
name = 'teaser'
titles = "'(b) teacher' '(c) joint model' '(d) attention ablated'"
load 'figures/teaser.gpi'
