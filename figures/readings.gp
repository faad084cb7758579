# data: frozen/readings/summary.tsv
# Figure readings (design.md §7 E0): every quantity of the readings table
# under each reading, as our value over the reference paper's value (1 = the
# paper's number; shaded: within 10 % and 25 %). Readings (readings.c):
# cardinal-one-sided-60m = teacher-1 on layout 5m-on-60m, cardinal elongation,
# Mech* on the lattice; cardinal-mutual-60m = the same with teacher-2;
# mutual-60m = + all-axis elongation and Mech* on the figure stand;
# one-sided-36m = teacher-1 on layout 4m-on-36m; mutual-36m = the adopted
# reading (teacher-2, 4m-on-36m); arc = mutual-36m with the contact arc
# s-1..s+1 dying back too (measured, not adopted).
# Rows of summary.tsv are quantity-major, six readings each (readings.c).
# Reads only frozen files. Run from the repository root: gnuplot figures/readings.gp
nr = 6
nq = real(system("awk -F'\t' '!/^#/ && $1!=\"quantity\"{n++} END{print n/6}' frozen/readings/summary.tsv"))
if (!exists("outdir")) outdir = 'figures'
do for [fmt in "png pdf"] {
  if (fmt eq "png") { set terminal pngcairo size 1000,900 font "DejaVu Sans,12"; set output outdir.'/readings.png' } \
  else { set terminal pdfcairo size 8in,7.2in font "DejaVu Sans,11"; set output outdir.'/readings.pdf' }
  set datafile separator "\t"
  set key autotitle columnhead
  set key inside right bottom vertical box opaque font "DejaVu Sans,11" width -2
  set title "E0 readings: each number relative to the reference paper's value"
  set xlabel "our value / paper's value"
  set xrange [0.2:2.2]
  set yrange [-nq+0.4:0.6]
  set ytics scale 0 font "DejaVu Sans,11"
  set grid xtics lc rgb "#cccccc"
  set object 1 rect from 0.75, graph 0 to 1.25, graph 1 fc rgb "#2ca02c" fs solid 0.10 noborder behind
  set object 2 rect from 0.90, graph 0 to 1.10, graph 1 fc rgb "#2ca02c" fs solid 0.20 noborder behind
  set arrow 1 from 1, graph 0 to 1, graph 1 nohead lw 1.5 lc rgb "#1a6b1a"
  yq(r) = -floor(r / nr)
  off(k) = 0.34 * (k - 2.5) / 2.5
  plot "frozen/readings/summary.tsv" using (strcol(2) eq "cardinal-one-sided-60m" ? 1 + $5 : NaN):(yq($0) + off(0)) with points pt 4 ps 1.5 lw 2 lc rgb "#7f7f7f" title "cardinal-one-sided-60m", \
       "" using (strcol(2) eq "cardinal-mutual-60m" ? 1 + $5 : NaN):(yq($0) + off(1)) with points pt 6 ps 1.5 lw 2 lc rgb "#ff7f0e" title "cardinal-mutual-60m", \
       "" using (strcol(2) eq "mutual-60m" ? 1 + $5 : NaN):(yq($0) + off(2)) with points pt 8 ps 1.5 lw 2 lc rgb "#9467bd" title "mutual-60m", \
       "" using (strcol(2) eq "one-sided-36m" ? 1 + $5 : NaN):(yq($0) + off(3)) with points pt 12 ps 1.5 lw 2 lc rgb "#1f77b4" title "one-sided-36m", \
       "" using (strcol(2) eq "arc" ? 1 + $5 : NaN):(yq($0) + off(5)) with points pt 2 ps 1.4 lw 2 lc rgb "#17becf" title "arc (mutual-36m, arc die-back)", \
       "" using (strcol(2) eq "mutual-36m" ? 1 + $5 : NaN):(strcol(2) eq "mutual-36m" ? yq($0) + off(4) : 1000):ytic(strcol(2) eq "mutual-36m" ? strcol(1) : "") with points pt 7 ps 1.6 lc rgb "#d62728" title "mutual-36m (adopted)"
  unset output
}
