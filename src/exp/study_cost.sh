#!/usr/bin/env bash
# study_cost: what the whole study costs to reproduce (design.md §10), from
# the manifest's units and the wall times the frozen units recorded. Reads
# the full run's unit list (`make reproduce-status`: every unit the manifest
# expands to at SCALE=full) and, for each unit, the `# wall_s:` of its frozen
# table; a unit not frozen yet takes the median of the frozen units of its
# kind (the same path with the seed and arm left out), else of its experiment,
# else it is counted as unknown. Prints per experiment the units, how many
# have a recorded time, and the CPU-hours; then the whole study's CPU-hours
# and its wall time with `make -j2` and on N two-core Slurm nodes (the units
# spread evenly: a lower bound that ignores the order the units depend on).
# Recorded times come from the machines and loads the units ran on, so this
# is a measured figure of the study as run, not of this machine.
# usage: src/exp/study_cost.sh [NODES...]   (default nodes: 4 8)
set -u
cd "$(dirname "$0")/../.."
nodes=${*:-4 8}
status=$(make -s --no-print-directory reproduce-status SCALE=full 2>/dev/null) || { echo "study_cost: make reproduce-status failed" >&2; exit 4; }
# every frozen table's recorded wall time: "path wall" (path under frozen/)
walls=$(grep -m1 -r --include='*.tsv' '^# wall_s: ' frozen 2>/dev/null | sed -E 's|^frozen/([^:]*):# wall_s: ([0-9.]+).*|\1 \2|')
# tables frozen from a re-evaluation of earlier weights record the evaluation's time only
reeval=$(grep -l -m1 -r --include='run_s*.tsv' '^# trained_wall_s: ' frozen 2>/dev/null | wc -l)
awk -v nodes="$nodes" -v reeval="$reeval" '
  FNR == NR { T[$1] = $2; next }
  # a unit that writes unit.tsv last (a sensitivity unit) ran every table of its folder
  function walls(path,   d, p, sum, any) {
    if (path !~ /\/unit\.tsv$/) return (path in T) ? T[path] : ""
    d = path; sub(/unit\.tsv$/, "", d); sum = 0; any = 0
    for (p in T) if (index(p, d) == 1) { sum += T[p]; any = 1 }
    return any ? sum : ""
  }
  function kind(path,   k) { k = path; gsub(/_s[0-9][0-9]_(joint|indep)/, "_s%_ARM", k); gsub(/_s[0-9][0-9]\./, "_s%.", k); return k }
  function median(list,   n, a, i, j, t) {
    n = split(list, a, " "); if (!n) return ""
    for (i = 1; i <= n; i++) for (j = i + 1; j <= n; j++) if (a[j] + 0 < a[i] + 0) { t = a[i]; a[i] = a[j]; a[j] = t }
    return n % 2 ? a[(n + 1) / 2] : (a[n / 2] + a[n / 2 + 1]) / 2
  }
  $1 !~ /^(done|missing|queued|running|failed)$/ { next }
  { path = $2; ex = path; sub(/\/.*/, "", ex)
    n++; P[n] = path; E[n] = ex; K[n] = kind(path)
    w = walls(path); W[n] = w
    if (w != "") { byk[K[n]] = byk[K[n]] " " w; bye[ex] = bye[ex] " " w }
    units[ex]++ }
  END {
    printf "study cost (the full run, from the manifest and the frozen units\x27 recorded wall times)\n"
    printf "%-24s %6s %9s %10s\n", "experiment", "units", "recorded", "CPU-hours"
    for (i = 1; i <= n; i++) {
      w = W[i]; src = "recorded"
      if (w == "") { w = median(byk[K[i]]); src = "kind" }
      if (w == "") { w = median(bye[E[i]]); src = "experiment" }
      if (w == "") { unknown[E[i]]++; totunknown++; continue }
      cpu[E[i]] += w; total += w; if (src == "recorded") rec[E[i]]++
    }
    for (e in units) printf "%-24s %6d %9d %10.2f%s\n", e, units[e], rec[e], cpu[e] / 3600, unknown[e] ? sprintf("  (%d with no time of their kind)", unknown[e]) : ""
    printf "whole study: %d units, %.1f CPU-hours%s\n", n, total / 3600, totunknown ? sprintf(" (%d units with no recorded time of their kind left out)", totunknown) : ""
    if (reeval) printf "(%d of the recorded tables are re-evaluations of earlier weights: they record the evaluation, not the training, so a run that retrains them costs more)\n", reeval
    printf "make -j2 on one two-core machine: about %.1f h\n", total / 3600 / 2
    k = split(nodes, N, " ")
    for (i = 1; i <= k; i++) printf "Slurm, %d two-core nodes: about %.1f h (units spread evenly; dependencies ignored)\n", N[i], total / 3600 / (2 * N[i])
  }' <(printf '%s\n' "$walls") <(printf '%s\n' "$status")
