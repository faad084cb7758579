# teaser.gp — Fig. teaser (reference paper §3.1): (a) lidar canopy height
# model, drawn only when a CHM is supplied (CHM=path; this machine has none,
# so the panel says so); (b)-(d) one 24-tree patch at 5.0 m stem spacing
# (unseen in training): the teacher, the joint model and the independent arm
# on the same stems, crowns shaded by height, gaps dark, crowns that run into
# a neighbour ringed in red. Data: crownshy comparison-run (src/exp/exp_comp.c).
# Usage: gnuplot figures/teaser.gp   (dir='build/results' to draw unfrozen data)
# data: frozen/comparison/patch_crowns.tsv
# data: frozen/comparison/patch.tsv
if (!exists("dir")) dir = 'frozen'
if (!exists("outdir")) outdir = 'figures'
load 'figures/canopy.gpi'
f = dir.'/comparison/patch_crowns.tsv'
p = dir.'/comparison/patch.tsv'
stats f using 1 nooutput
n = int(STATS_records / ROWS)
med(s) = real(system(sprintf("awk -F'\t' '$1==\"%s\"{print $4}' '%s'", s, p)))
ovl(s) = int(system(sprintf("awk -F'\t' '$1==\"%s\"{print $5}' '%s'", s, p)))
src = "teacher joint indep"
titles = "'(b) teacher' '(c) joint model' '(d) attention ablated'"
W = 15.0
do for [term = 1:2] {
  if (term == 1) { set terminal pngcairo size 1800,520 font ",14"; set output outdir.'/teaser.png' }
  else { set terminal pdfcairo size 7in,2.05in font ",8"; set output outdir.'/teaser.pdf' }
  set multiplot layout 1,4
  set title "(a) lidar canopy height model"
  unset xlabel   # panel d's label must not leak into this one on the second pass
  set xrange [-W:W]
  set yrange [-W:W]
  set object 1 rectangle from -W,-W to W,W fillcolor rgb '#f4f4f4' fillstyle solid 1.0 behind
  set label 1 "not on this machine:\nsupply CHM=path\n(ESRI ASCII grid)" at 0,0 center font ",12"
  plot NaN notitle
  unset label 1
  do for [a = 1:3] {
    x0 = 40.0 * (a - 1)
    set xrange [x0 - W:x0 + W]
    set yrange [-W:W]
    set object 1 rectangle from x0 - W,-W to x0 + W,W fillcolor rgb '#0b0f0b' fillstyle solid 1.0 behind
    set title word(titles, a)
    s = word(src, a)
    set xlabel sprintf("NN clearance %+.3f m; %d of 24 overlapping", med(s), ovl(s))
    plot for [t = 0:n-1] f every ::(t*ROWS)::(t*ROWS+ROWS-1) using ($2 >= x0 - 20 && $2 < x0 + 20 ? $2 : NaN):3:4 with filledcurves closed lc palette notitle, \
         for [t = 0:n-1] f every ::(t*ROWS)::(t*ROWS+ROWS-1) using ($2 >= x0 - 20 && $2 < x0 + 20 && $5 == 1 ? $2 : NaN):3 with lines lw 2 lc rgb '#e41a1c' notitle
  }
  unset multiplot
  unset output
}
