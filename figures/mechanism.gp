# mechanism.gp — Fig. mechanism (reference paper §3.2): coupling off,
# abrasion off, both on; identical hard-core stems (c = 0.5, 3.5 m, L = 36 m)
# and crown draws in the three panels; the median nearest-neighbour clearance
# of the stand shown under each panel. Data: crownshy mechanism-figure.
# Usage: gnuplot figures/mechanism.gp   (dir='build/results' to draw unfrozen data)
# data: frozen/mechanism/figure_poly_coupling_off_3.5.tsv
# data: frozen/mechanism/figure_poly_abrasion_off_3.5.tsv
# data: frozen/mechanism/figure_poly_both_on_3.5.tsv
if (!exists("dir")) dir = 'frozen'
if (!exists("outdir")) outdir = 'figures'
load 'figures/canopy.gpi'
arms = "coupling_off abrasion_off both_on"
titles = "'coupling off' 'abrasion off' 'both on'"
file(a) = sprintf("%s/mechanism/figure_poly_%s_3.5.tsv", dir, word(arms, a))
k1(a) = real(system(sprintf("sed -n 's/^# k1_median_m: //p' '%s'", file(a))))
do for [term = 1:2] {
  if (term == 1) { set terminal pngcairo size 1500,560 font "DejaVu Sans,14"; set output outdir.'/mechanism.png' }
  else { set terminal pdfcairo size 7.5in,2.8in font "DejaVu Sans,9"; set output outdir.'/mechanism.pdf' }
  set multiplot layout 1,3
  do for [a = 1:3] {
    f = file(a)
    stats [*:*][*:*] f using 1 nooutput
    n = int(STATS_records / ROWS)
    set xrange [0:36]
    set yrange [0:36]
    set object 1 rectangle from 0,0 to 36,36 fillcolor rgb '#0b0f0b' fillstyle solid 1.0 behind
    set title sprintf("%s", word(titles, a))
    set xlabel sprintf("NN clearance %+.3f m", k1(a))
    plot for [t = 0:n-1] f every ::(t*ROWS)::(t*ROWS+ROWS-1) using 2:3:4 with filledcurves closed lc palette notitle
  }
  unset multiplot
  unset output
}
