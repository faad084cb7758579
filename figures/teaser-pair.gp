# teaser-pair.gp — the teaser panels of the pair-aware generator (an extension
# added after the first verdict; seed 1), drawn by figures/teaser.gpi from the
# figure patch of its E7 distribution.
# Usage: gnuplot figures/teaser-pair.gp   (dir='build/results' to draw unfrozen data)
# data: frozen/extension-pair/comparison/figure_crowns.tsv
# data: frozen/extension-pair/comparison/dist_patches.tsv
rd = 'extension-pair'
name = 'teaser-pair'
titles = "'(b) teacher' '(c) joint, pair extension' '(d) attention ablated'"
load 'figures/teaser.gpi'
