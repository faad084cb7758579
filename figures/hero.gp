# hero.gp — Fig. hero (design.md §7 E9): teacher canopies on hard-core stems
# (c = 0.5, L = 36 m) at d = 3.0 ... 6.5 m, row beta_train (and row beta_field
# when the E5 calibration has produced it); crown draws shared within a column.
# Data: crownshy hero-figure [--beta B_field].
# Usage: gnuplot figures/hero.gp   (dir='build/results' to draw unfrozen data)
# data: frozen/hero/figure_poly_beta_train_3.0.tsv
# data: frozen/hero/figure_poly_beta_train_6.5.tsv
if (!exists("dir")) dir = 'frozen'
if (!exists("outdir")) outdir = 'figures'
load 'figures/canopy.gpi'
spacings = "3.0 3.5 4.0 4.5 5.0 5.5 6.0 6.5"
file(row, a) = sprintf("%s/hero/figure_poly_%s_%s.tsv", dir, row, word(spacings, a))
have_field = system(sprintf("test -f '%s' && echo 1 || echo 0", file("beta_field", 1))) + 0
nrows = have_field ? 2 : 1
rows = "beta_train beta_field"
do for [term = 1:2] {
  if (term == 1) { set terminal pngcairo size 2000,(nrows*270+40) font "DejaVu Sans,13"; set output outdir.'/hero.png' }
  else { set terminal pdfcairo size 7in,(nrows*1.35+0.2)*0.7in font "DejaVu Sans,7"; set output outdir.'/hero.pdf' }
  set multiplot layout nrows,8 margins 0.03,0.995,0.02,0.86 spacing 0.006,0.04
  do for [b = 1:nrows] {
    do for [a = 1:8] {
      f = file(word(rows, b), a)
      stats [*:*][*:*] f using 1 nooutput
      n = int(STATS_records / ROWS)
      set xrange [0:36]
      set yrange [0:36]
      set object 1 rectangle from 0,0 to 36,36 fillcolor rgb '#0b0f0b' fillstyle solid 1.0 behind
      set title (b == 1 ? sprintf("%s m", word(spacings, a)) : "")
      set ylabel (a == 1 ? (b == 1 ? "β_{train}" : "β_{field}") : "") offset 1,0
      SBX = 1.5; SBY = 1.5
      if (a == 1 && b == 1) { @scale_bar } else { @no_scale_bar }
      plot for [t = 0:n-1] f every ::(t*ROWS)::(t*ROWS+ROWS-1) using 2:3:4 with filledcurves closed lc palette notitle
    }
  }
  @no_scale_bar
  unset multiplot
  unset output
}
