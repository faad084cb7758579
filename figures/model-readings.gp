# model-readings.gp — the generator readings (design.md §8 "Readings of the
# generator"; reference paper §4.2, §5.1): per reading, the error of every
# frozen seed of both arms on the unseen spacings (W1 of focal nearest-neighbour
# clearances, mean over 4.0/5.0/6.0 m of each run table's generated rows), the
# joint arm under the shuffled-geometry probe, and the direction-blind level of
# the reading's evaluation volume. Drawn from the per-run tables alone, so a
# reading shows the seeds frozen so far; a reading with none says "not run".
# paper: the reading the preregistered gates judge; pair: the extension (its
# models re-evaluated); paper-fourier, plain: descriptive (4 seeds); all at 96-stands.
# Usage: gnuplot figures/model-readings.gp   (dir='build/results' for unfrozen data)
# data: frozen/paper-reading/main/run_s*_*.tsv
# data: frozen/paper-reading/main/baselines.tsv
# data: frozen/extension-pair/main/run_s*_*.tsv
# data: frozen/extension-pair/main/baselines.tsv
# data: frozen/model-readings/paper-fourier/main/run_s*_*.tsv
# data: frozen/model-readings/plain/main/run_s*_*.tsv
if (!exists("dir")) dir = 'frozen'
if (!exists("outdir")) outdir = 'figures'
set datafile separator "\t"
set datafile columnheaders
NR = 4
array RD[NR] = ['paper-reading/main', 'extension-pair/main', 'model-readings/paper-fourier/main', 'model-readings/plain/main']
array NAME[NR] = ['paper', 'pair (extension)', 'paper-fourier', 'plain']
array WANT[NR] = [12, 12, 4, 4]
NS = 12
# E[((r - 1) * NS + s - 1) * 3 + k]: k 1 joint, 2 independent, 3 joint shuffled
array E[NR * NS * 3]
array NF[NR]
array BL[NR]
have(f) = int(system(sprintf("test -f '%s' && echo 1 || echo 0", f)))
do for [r = 1:NR] {
  NF[r] = 0
  BL[r] = NaN
  do for [s = 1:NS] {
    fj = sprintf("%s/%s/run_s%02d_joint.tsv", dir, RD[r], s)
    fi = sprintf("%s/%s/run_s%02d_indep.tsv", dir, RD[r], s)
    do for [k = 1:3] { E[((r - 1) * NS + s - 1) * 3 + k] = NaN }
    if (s <= WANT[r] && have(fj) && have(fi)) {
      NF[r] = NF[r] + 1
      stats fj using ((strcol(4) eq "unseen" && strcol(5) eq "generated") ? $6 : NaN) nooutput name "J"
      stats fi using ((strcol(4) eq "unseen" && strcol(5) eq "generated") ? $6 : NaN) nooutput name "I"
      stats fj using ((strcol(4) eq "unseen" && strcol(5) eq "shuffled") ? $6 : NaN) nooutput name "H"
      E[((r - 1) * NS + s - 1) * 3 + 1] = J_mean
      E[((r - 1) * NS + s - 1) * 3 + 2] = I_mean
      E[((r - 1) * NS + s - 1) * 3 + 3] = H_mean
    }
  }
  fb = sprintf("%s/%s/baselines.tsv", dir, RD[r])
  if (have(fb)) {
    stats fb using (strcol(2) eq "unseen" ? $3 : NaN) nooutput name "B"
    BL[r] = B_mean
  }
}
# the array E is plotted as data: it has no header line
set datafile nocolumnheaders
set datafile separator whitespace
# the descriptive readings share the paper reading's volume and baselines
BL[3] = BL[1]
BL[4] = BL[1]
do for [term = 1:2] {
  if (term == 1) { set terminal pngcairo size 1400,620 font "DejaVu Sans,14"; set output outdir.'/model-readings.png' }
  else { set terminal pdfcairo size 7in,3.1in font "DejaVu Sans,9"; set output outdir.'/model-readings.pdf' }
  PS = (term == 1) ? 1.3 : 0.45
  set bmargin 4.5
  set xrange [0.4:NR + 0.6]
  set yrange [0:1.25]
  set ylabel "W1 error on unseen spacings (m)"
  set xtics () scale 0
  do for [r = 1:NR] { set xtics add (sprintf("%s\n%d of %d seeds%s", NAME[r], NF[r], WANT[r], NF[r] ? "" : ": not run") r) }
  set key inside top right horizontal maxrows 2 opaque box
  set title "generator readings: joint and independent arms, every frozen seed"
  set for [r = 1:NR] arrow r from r - 0.4, BL[r] to r + 0.4, BL[r] nohead dt 3 lw 2 lc rgb '#333333'
  plot E using (i = int($1) - 1, r = i / (NS * 3) + 1, s = (i % (NS * 3)) / 3 + 1, k = i % 3 + 1, \
                k == 2 ? r + 0.12 + 0.01 * (s - 6.5) : NaN):2 with points pt 5 ps PS lc rgb '#b2182b' title "independent", \
       E using (i = int($1) - 1, r = i / (NS * 3) + 1, s = (i % (NS * 3)) / 3 + 1, k = i % 3 + 1, \
                k == 1 ? r - 0.12 + 0.01 * (s - 6.5) : NaN):2 with points pt 7 ps PS lc rgb '#2166ac' title "joint", \
       E using (i = int($1) - 1, r = i / (NS * 3) + 1, s = (i % (NS * 3)) / 3 + 1, k = i % 3 + 1, \
                k == 3 ? r - 0.3 + 0.01 * (s - 6.5) : NaN):2 with points pt 6 ps PS lc rgb '#2166ac' title "joint, shuffled", \
       NaN with lines dt 3 lw 2 lc rgb '#333333' title "direction-blind"
  unset for [r = 1:NR] arrow r
  unset output
}
