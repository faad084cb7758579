# irreducible.gp — Fig. irreducible (reference paper §3.3). Left: fraction of
# judged neighbours whose crowns respond when one tree is made 30% taller, by
# stem spacing, with the preregistered 0.50 gate dashed. Right: response
# magnitude under step refinement (circles) against the decay a
# discretisation artefact would show, i.e. the step ratio (squares, dashed).
# Data: crownshy irreducibility-perturb / irreducibility-refine (beta_train).
# Usage: gnuplot figures/irreducible.gp   (dir='build/results' for unfrozen data)
# data: frozen/irreducibility/perturb_train.tsv
# data: frozen/irreducibility/refine_train.tsv
if (!exists("dir")) dir = 'frozen'
if (!exists("outdir")) outdir = 'figures'
set datafile separator "\t"
set datafile columnheaders
fp = dir.'/irreducibility/perturb_train.tsv'
fr = dir.'/irreducibility/refine_train.tsv'
do for [term = 1:2] {
  if (term == 1) { set terminal pngcairo size 1200,460 font "DejaVu Sans,14"; set output outdir.'/irreducible.png' }
  else { set terminal pdfcairo size 6.5in,2.5in font "DejaVu Sans,9"; set output outdir.'/irreducible.pdf' }
  set multiplot layout 1,2
  set key top center horizontal
  set grid ytics
  set xlabel "stem spacing d (m)"
  # the spacings run are categories, one bar each at its row's position: a
  # numeric axis would leave empty slots between them that read as zero bars
  set xtics () # the right panel's tics must not leak into this one on the second pass
  set ylabel "neighbours responding"
  set xrange [-0.6:4.6]
  set yrange [0:1.3]
  set ytics (0, 0.25, 0.5, 0.75, 1)
  set style fill solid 0.8
  set boxwidth 0.6
  plot fp using 0:"response_fraction":xtic(sprintf("%g", column("spacing_m"))) with boxes lc rgb '#3f7f3f' title "response fraction", \
       0.5 with lines dt 2 lw 2 lc rgb '#b03030' title "gate 0.50"
  set xlabel "growth resolution N"
  set ylabel "relative to N = 48"
  set logscale xy 2
  set xrange [40:460]
  set yrange [0.09:1.6]
  set xtics (48, 96, 192, 384)
  set ytics (0.125, 0.25, 0.5, 1)
  set key bottom left
  plot fr using ((strcol("scope") eq "pooled") ? column("nres") : NaN):"magnitude_ratio" with linespoints pt 7 ps 1.5 lw 2 lc rgb '#3f7f3f' title "response magnitude", \
       fr using ((strcol("scope") eq "pooled") ? column("nres") : NaN):"step_ratio" with linespoints pt 5 ps 1.3 dt 2 lw 2 lc rgb '#808080' title "artefact (tracks the step)", \
       0.25 with lines dt 2 lw 2 lc rgb '#b03030' title "gate 0.25"
  unset logscale
  unset multiplot
  unset output
}
