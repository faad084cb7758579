# data: frozen/anisotropy/jitter.tsv
# data: frozen/anisotropy/lattice.tsv
# data: frozen/anisotropy/heldout.tsv
# data: frozen/anisotropy/hardcore.tsv
# data: frozen/field/reference.tsv
# Figure anisotropy (reference paper Fig. fig:anisotropy, §5.4; design.md §7 E6, §12).
# Left: median per-tree anisotropy (widest / narrowest cardinal gap) against
# stem jitter amplitude a: circles = calibration sweep, square = the controlled
# lattice (canonical a), star = held-out stands at the calibrated a*; shaded =
# the published field band, dotted = the published field median.
# Right: the hard-core family (minimum stem distance c d), same band.
# Reads only frozen files. Run from the repository root: gnuplot figures/anisotropy.gp
ref(q) = real(system(sprintf("awk -F'\t' '$1==\"%s\"{print $2}' frozen/field/reference.tsv", q)))
col(f, arm, c) = real(system(sprintf("awk -F'\t' '$1==\"%s\"{print $%d; exit}' %s", arm, c, f)))
blo = ref("aniso_band_lo"); bhi = ref("aniso_band_hi"); bmed = ref("aniso_median")
lat_a = col("frozen/anisotropy/lattice.tsv", "coupled", 2)
lat_v = col("frozen/anisotropy/lattice.tsv", "coupled", 9)
ho_a = col("frozen/anisotropy/heldout.tsv", "coupled", 2)
ho_v = col("frozen/anisotropy/heldout.tsv", "coupled", 9)
# lowest sweep median: when it is above the field median, a* cannot be bracketed
swmin = real(system("awk -F'\t' '$1==\"coupled\" && (m==\"\" || $9<m){m=$9} END{print m}' frozen/anisotropy/jitter.tsv"))

if (!exists("outdir")) outdir = 'figures'
do for [fmt in "png pdf"] {
  if (fmt eq "png") { set terminal pngcairo size 1200,500 font "DejaVu Sans,11"; set output outdir.'/anisotropy.png' } \
  else { set terminal pdfcairo size 7in,2.9in font "DejaVu Sans,7"; set output outdir.'/anisotropy.pdf' }
  K = (fmt eq "png") ? 1 : 0.55   # point sizes of the printed (pdf) figure
  set datafile separator "\t"
  set multiplot layout 1,2
  set yrange [1.0:*]
  set object 1 rect from graph 0, first blo to graph 1, first bhi fc rgb "#2ca02c" fs solid 0.2 noborder behind
  set arrow 1 from graph 0, first bmed to graph 1, first bmed nohead dt 3 lw 2 lc rgb "#1a6b1a"
  set label 1 sprintf("field band %.2f-%.2f, median %.3f", blo, bhi, bmed) at graph 0.02, graph 0.04 tc rgb "#1a6b1a"
  # ---- left: jitter family
  set title "Jitter family (lattice, d = 4 m, L = 36 m, β_{field})"
  set xlabel "stem jitter amplitude a (sd / spacing)"
  set ylabel "median anisotropy (widest / narrowest cardinal gap)"
  set xrange [0.02:0.18]
  set yrange [1.0:2.0]
  set key top left
  if (swmin > bmed) { set label 2 "whole sweep above the field median:\na* not bracketed (nearest end)" at graph 0.45, graph 0.62 font (fmt eq "png" ? "DejaVu Sans,10" : "DejaVu Sans,6") tc rgb "#b00000" } else { unset label 2 }
  plot "frozen/anisotropy/jitter.tsv" using (strcol(1) eq "coupled" ? $2 : NaN):9 with linespoints pt 6 ps 1.6*K lw 1.5 lc rgb "#1f77b4" title "calibration sweep", \
       "+" using (lat_a):(lat_v) every ::0::0 with points pt 5 ps 1.8*K lc rgb "#000000" title sprintf("controlled lattice (a = %.2f)", lat_a), \
       "+" using (ho_a):(ho_v) every ::0::0 with points pt 3 ps 3*K lw 2 lc rgb "#d62728" title sprintf("held out at a* = %.2f: %.3f", ho_a, ho_v)
  unset label 2
  # ---- right: hard-core family
  set title "Hard-core family (d = 4 m, L = 36 m, β_{field})"
  set xlabel "minimum stem distance c (fraction of spacing)"
  set xrange [0.25:0.75]
  set yrange [1.0:*]
  plot "frozen/anisotropy/hardcore.tsv" using (strcol(1) eq "coupled" ? $2 : NaN):9 with linespoints pt 7 ps 1.4*K lw 1.5 lc rgb "#9467bd" title "hard-core sweep (buildable levels)"
  unset multiplot
  unset output
}
