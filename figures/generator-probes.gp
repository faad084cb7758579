# generator-probes.gp — what each generator reading uses (design.md §8.4;
# reference paper §5.1): a row per reading and arm, a column per probe; each
# cell the median over the frozen seeds (1-4) of the error under the probe
# (mean W1 over the unseen spacings of the unit's probe table) over the median
# error without it, as the Probe* claims; 1 (white) means the reading does not
# use what the probe removes, red that it does. A reading whose four seeds are
# not all frozen is drawn empty ("pending").
# Usage: gnuplot figures/generator-probes.gp   (dir='build/results' for unfrozen data)
# data: frozen/generator-probes/paper/probes_s*_*.tsv
# data: frozen/generator-probes/pair/probes_s*_*.tsv
# data: frozen/generator-probes/paper-fourier/probes_s*_*.tsv
# data: frozen/generator-probes/plain/probes_s*_*.tsv
if (!exists("dir")) dir = 'frozen'
if (!exists("outdir")) outdir = 'figures'
set datafile separator "\t"
set datafile columnheaders
NR = 4
array RD[NR] = ['paper', 'paper-fourier', 'plain', 'pair']
array NAME[NR] = ['paper', 'paper-fourier', 'plain', 'pair (extension)']
NP = 7
array PR[NP] = ['self', 'rot15', 'rot45', 'rot90', 'nnswap', 'dejitter', 'sizes']
array PNAME[NP] = ["self\nonly", "turn\n15°", "turn\n45°", "turn\n90°", "nearest\nswapped", "de-\njittered", "sizes\npermuted"]
NS = 4
have(f) = int(system(sprintf("test -f '%s' && echo 1 || echo 0", f)))
# the median of four values a, b, c, d: the mean of the middle two
med4(a, b, c, d) = (a + b + c + d - (a < b ? (a < c ? (a < d ? a : d) : (c < d ? c : d)) : (b < c ? (b < d ? b : d) : (c < d ? c : d))) \
                   - (a > b ? (a > c ? (a > d ? a : d) : (c > d ? c : d)) : (b > c ? (b > d ? b : d) : (c > d ? c : d)))) / 2
array V[NS]
array U[NS]
set print $D
do for [r = 1:NR] {
  do for [a = 1:2] {
    arm = a == 1 ? 'joint' : 'indep'
    row = (r - 1) * 2 + a
    ok = 1
    do for [s = 1:NS] { if (!have(sprintf("%s/generator-probes/%s/probes_s%02d_%s.tsv", dir, RD[r], s, arm))) { ok = 0 } }
    do for [p = 1:NP] {
      v = NaN
      if (ok) {
        do for [s = 1:NS] {
          f = sprintf("%s/generator-probes/%s/probes_s%02d_%s.tsv", dir, RD[r], s, arm)
          stats f using (strcol(2) eq PR[p] ? $3 : NaN) nooutput name "P"
          stats f using (strcol(2) eq "none" ? $3 : NaN) nooutput name "N"
          V[s] = P_mean
          U[s] = N_mean
        }
        v = med4(V[1], V[2], V[3], V[4]) / med4(U[1], U[2], U[3], U[4])
      }
      print sprintf("%d\t%d\t%.6g\t%s", p, row, v, ok ? sprintf("%.2f", v) : "pending")
    }
  }
}
set print
set datafile nocolumnheaders
do for [fmt in "png pdf"] {
  if (fmt eq "png") { set terminal pngcairo size 1100,660 font "DejaVu Sans,13"; set output outdir.'/generator-probes.png' } \
  else { set terminal pdfcairo size 7in,4.2in font "DejaVu Sans,9"; set output outdir.'/generator-probes.pdf' }
  set title "What each generator reading uses: error under a probe / error without it (median over 4 seeds)" noenhanced
  set xrange [0.5:NP + 0.5]
  set yrange [2 * NR + 0.5:0.5]
  set xtics () scale 0 nomirror
  do for [p = 1:NP] { set xtics add (PNAME[p] p) }
  unset x2tics
  set ytics () scale 0 nomirror noenhanced
  do for [r = 1:NR] { set ytics add (NAME[r].' joint' (2 * r - 1), NAME[r].' indep.' (2 * r)) }
  set palette defined (0 "#2166ac", 1 "#ffffff", 2 "#fddbc7", 3 "#d6604d", 4 "#67001f")
  set cbrange [-1:3]
  set cblabel "log2 of the ratio"
  set cbtics ("0.5" -1, "1" 0, "2" 1, "4" 2, "8" 3)
  unset key
  set tmargin 3
  set bmargin 4
  set lmargin 24
  plot $D using 1:2:(0.5):(0.5):($3 == $3 ? log($3) / log(2) : NaN) with boxxyerror fs solid 1.0 noborder fc palette, \
       "" using 1:2:4:(($3 == $3 && $3 > 4) ? 0xffffff : 0x111111) with labels font "DejaVu Sans,11" tc rgb variable
  unset output
}
