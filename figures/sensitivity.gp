# data: frozen/sensitivity/summary.tsv
# Figure sensitivity (design.md §7 E0 "sensitivity"): for every number of the
# sensitivity table, the span the unstated choices cover (bar: lowest to highest
# over the centre run and every choice's values, one choice at a time; the three
# die-back readings, not unstated choices, as their own marks) against
# the reference paper's value (the vertical line at 1), as our value over the
# paper's; the dot is the centre run (the design's choices at the sensitivity's
# stand counts; a number a choice leaves not computable, or without a paper value, is left out). At the bar's ends, the choice and value that give the lowest
# and highest number. A bar beyond the axis ends in an arrow with the value.
# Shaded: within 10 % and 25 % of the paper. Reads only frozen files.
# Run from the repository root: gnuplot figures/sensitivity.gp
if (!exists("outdir")) outdir = 'figures'
if (!exists("f")) f = 'frozen/sensitivity/summary.tsv'
# one line per quantity: index, name, centre/paper, lo/paper, hi/paper, lo label, hi label,
# and the three die-back readings (not unstated choices: drawn as their own marks)
# (ratios of values of the same sign; a value of the other sign is drawn at 0)
prep = "< awk -F'\\t' '!/^#/ && $1 != \"quantity\" && $4 !~ /nan/ && $5 !~ /nan/ { q = $1; r = ($5 != 0) ? $4 / $5 : 0; if (r < 0) r = 0; " . \
       "if (!(q in seen)) { seen[q] = 1; order[++n] = q; lo[q] = 1e9; hi[q] = -1e9; d1[q] = \"nan\"; d2[q] = \"nan\"; d3[q] = \"nan\" } " . \
       "lab = ($2 == \"centre\") ? \"ours\" : sprintf(\"%s %g\", $2, $3); " . \
       "if ($2 == \"centre\") c[q] = r; " . \
       "if ($2 == \"dieback\") { if ($3 == 1) d1[q] = r; else if ($3 == 2) d2[q] = r; else d3[q] = r; next } " . \
       "if (r < lo[q]) { lo[q] = r; ll[q] = lab } " . \
       "if (r > hi[q]) { hi[q] = r; hl[q] = lab } } " . \
       "END { for (i = 1; i <= n; i++) { q = order[i]; printf \"%d\\t%s\\t%.6g\\t%.6g\\t%.6g\\t%s\\t%s\\t%s\\t%s\\t%s\\n\", i - 1, q, c[q], lo[q], hi[q], ll[q], hl[q], d1[q], d2[q], d3[q] } }' " . f
nq = real(system("awk -F'\t' '!/^#/ && $1 != \"quantity\" && $5 !~ /nan/ && !($1 in s) {s[$1]; n++} END {print n}' " . f))
xmax = 2.6
clip(x) = x > xmax ? xmax : x
do for [fmt in "png pdf"] {
  if (fmt eq "png") { set terminal pngcairo size 1100,1500 font "DejaVu Sans,13"; set output outdir.'/sensitivity.png' } \
  else { set terminal pdfcairo size 7in,9.2in font "DejaVu Sans,9"; set output outdir.'/sensitivity.pdf' }
  set datafile separator "\t"
  set key outside bottom center horizontal noenhanced font "DejaVu Sans,9" samplen 1.5 maxrows 1
  set rmargin 17
  set ytics noenhanced
  set title "E0 sensitivity: the span the unstated choices cover, against the reference paper's value"
  set xlabel "our value / paper's value (1 = the paper's number)"
  set xrange [-0.45:xmax]
  set yrange [-nq + 0.4:0.6]
  set xtics 0, 0.25, xmax
  set ytics scale 0
  set grid xtics lc rgb "#dddddd"
  set object 1 rect from 0.75, graph 0 to 1.25, graph 1 fc rgb "#2ca02c" fs solid 0.10 noborder behind
  set object 2 rect from 0.90, graph 0 to 1.10, graph 1 fc rgb "#2ca02c" fs solid 0.20 noborder behind
  set arrow 1 from 1, graph 0 to 1, graph 1 nohead lw 1.5 lc rgb "#1a6b1a"
  plot prep using (clip($4)):(-$1):(clip($4)):(clip($5)):(-$1 - 0.22):(-$1 + 0.22) with boxxyerror fs solid 0.55 lc rgb "#4a7fb0" title "span of the unstated choices", \
       "" using (clip($3)):(-$1):ytic(2) with points pt 7 ps 1.1 lc rgb "#111111" title "ours (centre run)", \
       "" using (clip($8)):(-$1 + 0.30) with points pt 9 ps 1.2 lc rgb "#d62728" title "die-back: arc s±1", \
       "" using (clip($9)):(-$1 - 0.30) with points pt 11 ps 1.2 lc rgb "#8c564b" title "die-back: β of the target", \
       "" using (clip($10)):(-$1) with points pt 5 ps 1.0 lc rgb "#9467bd" title "die-back: one-sided", \
       "" using (clip($4)):(-$1):(strcol(6) . " ") with labels right noenhanced font "DejaVu Sans,9" tc rgb "#333333" notitle, \
       "" using (clip($5)):(-$1):(" " . strcol(7) . ($5 > xmax ? sprintf(" (%.1f)", $5) : "")) with labels left noenhanced font "DejaVu Sans,9" tc rgb "#333333" notitle, \
       "" using ($5 > xmax ? xmax - 0.12 : NaN):(-$1):(0.1):(0) with vectors head filled size 0.05,20 lc rgb "#4a7fb0" notitle
  unset output
}
