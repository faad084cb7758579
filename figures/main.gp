# main.gp — Fig. main (reference paper §5.1-5.2): left, the error of every
# seed of both arms on the unseen spacings (W1 of focal nearest-neighbour
# clearances, mean over 4.0/5.0/6.0 m) with the direction-blind level, and the
# joint arm under the shuffled-geometry probe (preregistered) and the rotation
# probe (added after the first verdict, shifted left for legibility); right,
# the relative advantage of the joint arm (median over seeds) at the
# extrapolation spacings with the preregistered 20 % line.
# Usage: gnuplot figures/main.gp   (dir='build/results' to draw unfrozen data)
# data: frozen/main/runs.tsv
# data: frozen/main/baselines.tsv
# data: frozen/extrapolation/runs.tsv
if (!exists("dir")) dir = 'frozen'
if (!exists("outdir")) outdir = 'figures'
set datafile separator "\t"
set datafile columnheaders
runs = dir.'/main/runs.tsv'
base = dir.'/main/baselines.tsv'
ext = dir.'/extrapolation/runs.tsv'
stats base using (strcol(2) eq "unseen" ? $3 : NaN) nooutput name "BLIND"
stats ext using ((abs($3 - 3.0) < 1e-9 && strcol(2) eq "joint") ? $4 : NaN) nooutput name "J3"
stats ext using ((abs($3 - 3.0) < 1e-9 && strcol(2) eq "indep") ? $4 : NaN) nooutput name "I3"
stats ext using ((abs($3 - 7.5) < 1e-9 && strcol(2) eq "joint") ? $4 : NaN) nooutput name "J7"
stats ext using ((abs($3 - 7.5) < 1e-9 && strcol(2) eq "indep") ? $4 : NaN) nooutput name "I7"
stats runs using 1 nooutput name "S"
rel3 = 100.0 * (I3_median - J3_median) / I3_median
rel7 = 100.0 * (I7_median - J7_median) / I7_median
do for [term = 1:2] {
  if (term == 1) { set terminal pngcairo size 1400,560 font ",14"; set output outdir.'/main.png' }
  else { set terminal pdfcairo size 7in,2.8in font ",9"; set output outdir.'/main.pdf' }
  PS = (term == 1) ? 1.4 : 0.5
  set multiplot layout 1,2
  # the right panel's settings must not leak into the left one on the second pass
  unset style fill
  set key inside top left horizontal maxrows 3 opaque box
  set xlabel "seed"
  set xrange [0.5:S_max + 0.5]
  set ylabel "W1 error on unseen spacings (m)"
  set xtics 1
  set yrange [0:*]
  set offsets 0, 0, graph 0.4, 0   # room for the key above the points
  set title "joint vs independent, matched capacity"
  plot runs using ((strcol(2) eq "indep" && strcol(3) eq "generated") ? $1 : NaN):4 with points pt 5 ps PS lc rgb '#b2182b' title "independent", \
       runs using ((strcol(2) eq "joint" && strcol(3) eq "generated") ? $1 : NaN):4 with points pt 7 ps PS lc rgb '#2166ac' title "joint", \
       runs using ((strcol(2) eq "joint" && strcol(3) eq "shuffled") ? $1 : NaN):4 with points pt 6 ps PS lc rgb '#2166ac' title "joint, shuffled", \
       runs using ((strcol(2) eq "joint" && strcol(3) eq "rotated") ? $1 - 0.2 : NaN):4 with points pt 8 ps PS lc rgb '#4dac26' title "joint, rotated (added)", \
       BLIND_mean with lines dt 3 lw 2 lc rgb '#333333' title "direction-blind"
  set title "outside the training range"
  set xlabel "stem spacing (m)"
  set ylabel "relative advantage of joint (%)"
  set xtics ("3.0" 0, "7.5" 1)
  set xrange [-0.6:1.6]
  lo = rel3 < rel7 ? rel3 : rel7
  set yrange [(lo < 0 ? lo - 5 : 0):*]
  set offsets 0, 0, 5, 0
  set key inside top right box
  set style fill solid 0.8 border -1
  set boxwidth 0.5
  plot '+' using (0):(rel3) every ::0::0 with boxes lc rgb '#2166ac' notitle, \
       '+' using (1):(rel7) every ::0::0 with boxes lc rgb '#2166ac' notitle, \
       20 with lines dt 2 lw 2 lc rgb '#333333' title "20 % gate"
  unset multiplot
  unset output
}
