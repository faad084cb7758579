#!/usr/bin/env bash
# study_cost: what the whole study costs to reproduce (design.md §10), from
# the manifest's units and the wall times the units recorded. For each scale
# (full, and smoke so that the projection can be checked against a measured
# `make reproduce SCALE=smoke`), the unit list is the one `make
# reproduce-status` expands the manifest to, and each unit's time is read by
# unit_walls (unit_wall.sh, the reader verify_deep.sh uses too): at full scale
# from frozen/, at smoke scale from the smoke results and the wall times
# `make reproduce` recorded for them. A unit with no recorded time takes the
# median of its kind (the same path with the seed and arm left out), else of
# its experiment, else it is counted as unknown. Prints per experiment the
# units, how many have a recorded time, and the CPU-hours; then the scale's
# CPU-hours and its wall time with `make -j2` and on N two-core Slurm nodes
# (the units spread evenly over the cores: a lower bound that ignores the
# order the units depend on, and the same at both scales, so a measured smoke
# run checks it). Recorded times come from the machines and loads the units
# ran on: a measured figure of the study as run, not of this machine; so the
# full run is printed a second time with every model unit at this core's
# rates (model_cpu below: each unit's own recipe run with --cost).
# usage: src/exp/study_cost.sh [NODES...]   (default nodes: 4 8)
#   env: SMOKE_ROOT (default build/smoke), SMOKE_STATE (build/reproduce/smoke)
set -u
cd "$(dirname "$0")/../.."
. src/exp/unit_wall.sh
nodes=${*:-4 8}
smoke_root=${SMOKE_ROOT:-build/smoke}
smoke_state=${SMOKE_STATE:-build/reproduce/smoke}

units_at() {  # the unit paths (under the results root) of one scale
    make -s --no-print-directory reproduce-status SCALE="$1" 2>/dev/null |
        awk '$1 ~ /^(done|missing|queued|running|failed)$/ { print $2 }'
}

# cost SCALE TITLE: the per-experiment table and the totals of one scale, from
# "path unit_s how" lines on stdin
cost() {
    awk -F'\t' -v nodes="$nodes" -v scale="$1" -v title="$2" '
  function kind(path,   k) { k = path; gsub(/_s[0-9][0-9]_(joint|indep)/, "_s%_ARM", k); gsub(/_s[0-9][0-9]\./, "_s%.", k); return k }
  function median(list,   n, a, i, j, t) {
    n = split(list, a, " "); if (!n) return ""
    for (i = 1; i <= n; i++) for (j = i + 1; j <= n; j++) if (a[j] + 0 < a[i] + 0) { t = a[i]; a[i] = a[j]; a[j] = t }
    return n % 2 ? a[(n + 1) / 2] : (a[n / 2] + a[n / 2 + 1]) / 2
  }
  { path = $1; ex = path; sub(/\/.*/, "", ex)
    n++; E[n] = ex; K[n] = kind(path); W[n] = $2; H[n] = $3
    if ($2 != "") { byk[K[n]] = byk[K[n]] " " $2; bye[ex] = bye[ex] " " $2 }
    units[ex]++ }
  END {
    printf "study cost, %s\n", title
    if (!n) { printf "  no unit listed at SCALE=%s\n", scale; exit }
    for (i = 1; i <= n; i++) {
      w = W[i]; src = "recorded"
      if (w == "") { w = median(byk[K[i]]); src = "kind" }
      if (w == "") { w = median(bye[E[i]]); src = "experiment" }
      if (w == "") { unknown[E[i]]++; totunknown++; continue }
      cpu[E[i]] += w; total += w; if (src == "recorded") { rec[E[i]]++; totrec++ }
      if (H[i] == "measured") { meas[E[i]]++; totmeas++ }
      if (H[i] == "trained") trained++
    }
    if (!totrec) { printf "  none of its %d units has a recorded wall time here: no projection (make reproduce SCALE=%s records them)\n", n, scale; exit }
    printf "%-24s %6s %9s %10s\n", "experiment", "units", "recorded", "CPU-hours"
    for (e in units) printf "%-24s %6d %9d %10.2f%s\n", e, units[e], rec[e], cpu[e] / 3600, unknown[e] ? sprintf("  (%d with no time of their kind)", unknown[e]) : ""
    printf "whole study at SCALE=%s: %d units (%d with a recorded time%s), %.2f CPU-hours%s\n", scale, n, totrec,
           totmeas ? sprintf(", %d of them measured here", totmeas) : "", total / 3600,
           totunknown ? sprintf(" (%d units with no recorded time of their kind left out)", totunknown) : ""
    if (trained) printf "(%d training units are frozen as re-evaluations of their weights: each is counted at the wall time its training run recorded, trained_wall_s)\n", trained
    printf "  make -j2 on one two-core machine: about %.2f h (%.1f min)\n", total / 3600 / 2, total / 60 / 2
    k = split(nodes, N, " ")
    for (i = 1; i <= k; i++) printf "  Slurm, %d two-core nodes: about %.2f h (units spread evenly; dependencies ignored)\n", N[i], total / 3600 / (2 * N[i])
  }'
}

# model_cpu SCALE ROOT < paths: "path <TAB> cpu_s" for each unit whose recipe
# runs `crownshy main-run`: its recipe as make expands it (make -n), run with
# --cost (the unit's model FLOPs at this core's rates now, thread CPU time;
# its teacher stands left out), both cores at a time
model_cpu() {
    local scale=$1 root=$2
    sed "s|^|$root/|" | xargs -r env -u MAKEFLAGS -u MAKELEVEL make -s -n -B -o "$cli" --no-print-directory \
        SCALE="$scale" RESULTS="$root" 2>/dev/null |
        sed -n "s|.*\($cli main-run .*\)\$|\1|p" |
        xargs -r -d '\n' -P 2 -I{} bash -c 'c="{}"; o=${c##*--out }; o=${o%% *}; OPENBLAS_NUM_THREADS=1 $c --cost |
            awk -F"\t" -v p="${o#'"$root"'/}" '"'"'$1 == "unit_cost" { sub(/^cpu_s /, "", $6); print p "\t" $6 }'"'"''
}
cli=build/crownshy

full_units=$(units_at full) || { echo "study_cost: make reproduce-status failed" >&2; exit 4; }
full=$(unit_walls frozen <<<"$full_units")
cut -f1,2,4 <<<"$full" | cost full "the full run, from the manifest and the frozen units' recorded wall times"
# the same with every model unit at this core's rates now (the recorded
# times of the model units are those of a loaded machine)
if [ -x "$cli" ]; then
    measured=$(model_cpu full build/results <<<"$full_units")
    awk -F'\t' -v OFS='\t' 'FNR == NR { M[$1] = $2; next } ($1 in M) { $2 = M[$1]; $4 = "measured" } { print }' \
        <(printf '%s\n' "$measured") <(printf '%s\n' "$full") |
        cut -f1,2,4 | cost full "the full run, its $(grep -c . <<<"$measured") model units (crownshy main-run) at this core's rates measured now (main-run --cost: model FLOPs over the training and sampling rates of a fresh model of the unit's configuration; a unit's teacher stands left out), the other units at their recorded wall times"
fi

# the same projection at smoke scale: the units' wall times of the smoke run
# in $smoke_root, else those `make reproduce` recorded for it
smoke_units=$(units_at smoke)
smoke=$(unit_walls "$smoke_root" <<<"$smoke_units")
if [ -f "$smoke_state/walltimes.tsv" ]; then
    smoke=$(awk -F'\t' 'FNR == NR { R[$1] = $2; next } { if ($2 == "" && ($1 in R)) { $2 = R[$1]; $4 = "recorded" } print }' OFS='\t' \
            "$smoke_state/walltimes.tsv" - <<<"$smoke")
fi
cut -f1,2,4 <<<"$smoke" | cost smoke "the smoke run, from the wall times its units recorded in $smoke_root (projected the same way; compare a measured make -j2 reproduce SCALE=smoke)"
if [ -f "$smoke_state/runs.tsv" ]; then
    awk -F'\t' 'END { if (NR) printf "  measured: the last make reproduce SCALE=smoke made %s units with -j%s in %.1f min (%s)\n", $2, $3, $4 / 60, $1 }' "$smoke_state/runs.tsv"
else
    echo "  measured: no make reproduce SCALE=smoke has finished in this tree ($smoke_state/runs.tsv)"
fi
