# hardcore-canopies.gp — the E8 stands drawn top-down (design.md §7 E8): the
# teacher canopies on hard-core stems (c = 0.5, L = 36 m) at 5, 4 and 3 m
# (beta_train), and the uncoupled twin at 3 m (same stems and crown draws).
# Stems are marked; each panel's caption gives the share of interior crowns
# that made contact during growth and the median NN clearance.
# Data: crownshy pointcloud-figure.
# Usage: gnuplot figures/hardcore-canopies.gp   (dir='build/results' for unfrozen data)
# data: frozen/pointcloud/figure_poly_coupled_5.0.tsv
# data: frozen/pointcloud/figure_poly_coupled_4.0.tsv
# data: frozen/pointcloud/figure_poly_coupled_3.0.tsv
# data: frozen/pointcloud/figure_poly_uncoupled_3.0.tsv
# data: frozen/pointcloud/stats.tsv
# data: frozen/pointcloud/figure_crowns.tsv
if (!exists("dir")) dir = 'frozen'
if (!exists("outdir")) outdir = 'figures'
load 'figures/canopy.gpi'
panels = "coupled_5.0 coupled_4.0 coupled_3.0 uncoupled_3.0"
file(a) = sprintf("%s/pointcloud/figure_poly_%s.tsv", dir, word(panels, a))
fs = dir.'/pointcloud/stats.tsv'
fc = dir.'/pointcloud/figure_crowns.tsv'
pname(a) = (a <= 3) ? "coupled" : "uncoupled"
pd(a) = real(word("5.0 4.0 3.0 3.0", a))
# stats.tsv rows: 5, 4, 3 m; columns 3 = contact share, 6/7 = k1 coupled/uncoupled
val(row, col) = real(system(sprintf("awk -F'\t' '!/^#/ && n++ == %d {print $%d}' '%s'", row, col, fs)))
do for [term = 1:2] {
  if (term == 1) { set terminal pngcairo size 1800,520 font "DejaVu Sans,14"; set output outdir.'/hardcore-canopies.png' }
  else { set terminal pdfcairo size 7in,2.05in font "DejaVu Sans,8"; set output outdir.'/hardcore-canopies.pdf' }
  set multiplot layout 1,4
  do for [a = 1:4] {
    f = file(a)
    stats [*:*][*:*] f using 1 nooutput
    n = int(STATS_records / ROWS)
    set xrange [0:36]
    set yrange [0:36]
    set object 1 rectangle from 0,0 to 36,36 fillcolor rgb '#0b0f0b' fillstyle solid 1.0 behind
    row = (a <= 3) ? a : 3
    if (a <= 3) {
      set title sprintf("coupled, %s m", substr(word(panels, a), 9, 11))
      set xlabel sprintf("contact %.0f%%, NN clearance %+.2f m", 100 * val(row, 3), val(row, 6))
    } else {
      set title "uncoupled twin, 3.0 m"
      set xlabel sprintf("NN clearance %+.2f m", val(3, 7))
    }
    SBX = 1.5; SBY = 1.5
    if (a == 1) { @scale_bar } else { @no_scale_bar }
    plot for [t = 0:n-1] f every ::(t*ROWS)::(t*ROWS+ROWS-1) using 2:3:4 with filledcurves closed lc palette notitle, \
         fc using ((strcol(1) eq pname(a) && abs(column(2) - pd(a)) < 1e-9) ? column(4) : NaN):5 with points pt 7 ps 0.35 lc rgb '#f0e0a0' notitle
  }
  @no_scale_bar
  unset multiplot
  unset output
}
