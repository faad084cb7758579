# data: frozen/field/calibration.tsv
# data: frozen/field/heldout.tsv
# data: frozen/field/reference.tsv
# Figure field (reference paper Fig. fig:field, §5.3; design.md §7 E5, §12).
# Left: E5 calibration curve (median tree-mean clearance vs die-back beta) with
# the field target and the calibrated beta_field. Centre: held-out clearance
# spread of the coupled stands and of the uncoupled twin; the field spread
# (and so the preregistered ratio band 0.5-2.0) needs the raw field table,
# which is not on this machine, so the panel says so instead of drawing a band.
# Right: held-out crown elongation against the published field band.
# Reads only frozen files. Run from the repository root: gnuplot figures/field.gp
ref(q) = real(system(sprintf("awk -F'\t' '$1==\"%s\"{print $2}' frozen/field/reference.tsv", q)))
meta(f, k) = real(system(sprintf("sed -n 's/^# %s: //p' %s", k, f)))
col(f, arm, c) = real(system(sprintf("awk -F'\t' '$1==\"%s\"{print $%d}' %s", arm, c, f)))
target = ref("tree_mean_median_m")
elo = ref("elong_band_lo"); ehi = ref("elong_band_hi")
bfield = meta("frozen/field/heldout.tsv", "beta_field")
sp_c = col("frozen/field/heldout.tsv", "coupled", 8)
sp_u = col("frozen/field/heldout.tsv", "uncoupled", 8)
el_c = col("frozen/field/heldout.tsv", "coupled", 12)
el_u = col("frozen/field/heldout.tsv", "uncoupled", 12)
ntrees = col("frozen/field/heldout.tsv", "coupled", 6)
nst = col("frozen/field/heldout.tsv", "coupled", 4)

if (!exists("outdir")) outdir = 'figures'
do for [fmt in "png pdf"] {
  if (fmt eq "png") { set terminal pngcairo size 1500,480 font "DejaVu Sans,11"; set output outdir.'/field.png' } \
  else { set terminal pdfcairo size 7in,2.4in font "DejaVu Sans,7"; set output outdir.'/field.pdf' }
  K = (fmt eq "png") ? 1 : 0.5   # point sizes of the printed (pdf) figure
  set datafile separator "\t"
  set multiplot layout 1,3
  # ---- left: calibration
  unset label; unset arrow; unset object
  set title "Calibration (3 seeds): one scalar"
  set xtics autofreq   # the right panel's tics must not leak into this one on the second pass
  set xlabel "die-back fraction β"
  set ylabel "median tree-mean clearance (m)"
  set key top left Left reverse samplen 2
  set xrange [0:0.32]
  set yrange [0:1.5]
  set arrow 1 from bfield, graph 0 to bfield, graph 1 nohead dt 3 lc rgb "#555555"
  set label 1 sprintf("β_{field} = %.2f", bfield) at bfield, graph 0.08 offset 0.5,0
  plot "frozen/field/calibration.tsv" using (strcol(1) eq "coupled" ? $2 : NaN):7 with linespoints pt 7 ps 0.7*K lc rgb "#1f77b4" title "simulated (lattice, d = 4 m, L = 36 m)", \
       target with lines dt 2 lw 2 lc rgb "#d62728" title sprintf("field target %.3f m", target)
  # ---- centre: spread
  unset arrow; unset label
  set title "Held-out clearance spread (IQR of cardinal gaps)"
  set xlabel ""
  set ylabel "spread (m)"
  set logscale y
  set xrange [-0.7:1.7]
  set yrange [0.05:5]
  set xtics ("coupled" 0, "uncoupled twin" 1)
  # a log axis has no zero for a bar to start from: the values are drawn as points
  set label 2 "field spread: needs the raw field table\n(FIELD_TABLE=path, Dryad 10.5061/dryad.34tmpg4hk;\nnot on this machine) -> ratio band 0.5-2.0\nnot drawable: SpreadRatio, ControlSpread PENDING" at graph 0.03, graph 0.95 noenhanced font (fmt eq "png" ? "DejaVu Sans,9" : "DejaVu Sans,5.5") tc rgb "#b00000"
  set label 3 sprintf("%.3f m", sp_c) at 0, sp_c left offset 1.2,0
  set label 4 sprintf("%.3f m", sp_u) at 1, sp_u left offset 1.2,0
  unset key
  plot "+" using (0):(sp_c) every ::0::0 with points pt 7 ps 2*K lc rgb "#1f77b4", \
       "+" using (1):(sp_u) every ::0::0 with points pt 7 ps 2*K lc rgb "#999999"
  unset logscale y
  unset label
  # ---- right: elongation
  set title sprintf("Held-out crown elongation (%d stands, %d trees)", nst, ntrees)
  set ylabel "median elongation (longest / shortest axis)"
  set yrange [0.9:2.1]
  set xrange [-0.7:1.7]
  set xtics ("coupled" 0, "uncoupled twin" 1)
  set object 1 rect from graph 0, first elo to graph 1, first ehi fc rgb "#2ca02c" fs solid 0.2 noborder behind
  set label 5 sprintf("field band %.2f-%.2f", elo, ehi) at graph 0.03, first ehi offset 0,-0.8 tc rgb "#1a6b1a"
  set label 6 sprintf("%.3f", el_c) at 0, el_c offset 1.5,0
  set label 7 sprintf("%.3f", el_u) at 1, el_u offset 1.5,0
  plot "+" using (0):(el_c) every ::0::0 with points pt 7 ps 2*K lc rgb "#1f77b4", \
       "+" using (1):(el_u) every ::0::0 with points pt 6 ps 2*K lc rgb "#555555"
  unset object 1
  unset multiplot
  unset output
}
