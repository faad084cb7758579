#!/usr/bin/env bash
# verify_deep.sh: the second tier of verification (design.md §9),
# behind `make verify-deep`. Reruns every teacher experiment unit (E1, E2, the
# teacher figure data, E5, E6, the E0 readings and sensitivity) into $DEEP with make -j$JOBS,
# printing progress (units done of total, elapsed, ETA), then compares every
# table it wrote with its frozen/ counterpart bit for bit: the data rows (the
# header and every row after the "# key: value" lines); provenance lines
# (date, wall time, git commit, command paths) are expected to differ.
# The model part: for each frozen weights file, `crownshy main-redraw`
# redraws the unit's clearance samples and they are compared the same way.
# Exit 0: every rerun table equals frozen/; 1: a difference, a missing model or a
# failed unit. The last line is always the summary, with the exit status.
# Called from the Makefile with DEEP, JOBS, CLI, MAKE, DEEP_UNITS and READING_NSEEDS set.
set -uo pipefail
: "${DEEP:?}" "${CLI:?}" "${DEEP_UNITS:?}"
JOBS=${JOBS:-2}
MAKE=${MAKE:-make}
t0=$SECONDS
status=0
units=($DEEP_UNITS)
total=${#units[@]}
mkdir -p "$DEEP"
# Every unit reruns: a teacher unit depends on the gates, not on the code, so
# make would take a table an earlier tier 2 left in $DEEP as up to date.
rm -f "${units[@]}"
log="$DEEP/make.log"
nseeds=$(awk '$1 == "seeds" {print $2}' gates/main.gate 2>/dev/null)
absent=0 redrawn=0 redraw_bad=0 jobs_list=() designed=0
rows=$(bash src/base/manifest.sh rows)
sets=$(awk -F'\t' '$1 == "EXPERIMENT" && $8 == "redraw" {r[$2] = 1}
  $1 == "UNIT" && r[$2] && $3 ~ /run_s%_joint\.tsv$/ {d = $3; sub(/\/?run_s%_joint\.tsv$/, "", d); print $2 "\t" d}
  $1 == "UNIT" && r[$2] && $3 ~ /runs\.tsv$/ && $4 ~ /READING_SEED_LIST/ {d = $3; sub(/\/runs\.tsv$/, "", d); print $2 "\t" d "\treading"}' <<<"$rows")
if [ -z "$nseeds" ]; then
    echo "  FAIL    gates/main.gate: no 'seeds' line: the model part cannot be listed"; status=1
fi
while IFS=$'\t' read -r exp sub kind; do
    [ -n "$exp" ] && [ -z "$kind" ] || continue
    dir="frozen/$exp${sub:+/$sub}"
    n=${nseeds:-0}
    grep -qxF "$exp"$'\t'"$sub"$'\t'reading <<<"$sets" && n=${READING_NSEEDS:?}
    for ((s = 1; s <= n; s++)); do
        for a in joint indep; do
            designed=$((designed + 1))
            t=$(printf '%s/run_s%02d_%s.tsv' "$dir" "$s" "$a")
            if [ ! -f "$t" ]; then echo "  FAIL    $t: missing (the design has seed $s, arm $a)"; absent=$((absent + 1)); continue; fi
            w=$(sed -n 's/^# weights: \([^ ]*\) .*/\1/p' "$t" | head -n 1)
            if [ -n "$w" ]; then w="$dir/$w"
            else
                # no weights beside it: the unit's --weights in the manifest,
                # under frozen/ (a command line is a record of where the run
                # that made the table found them, not where they are frozen)
                w=$(awk -F'\t' -v e="$exp" -v u="${sub:+$sub/}run_s%_$a.tsv" '$1 == "UNIT" && $2 == e && $3 == u && match($5, /--weights [^ ]+/) {
                      print substr($5, RSTART + 10, RLENGTH - 10); exit }' <<<"$rows")
                w=${w//@R@/frozen}; w=${w//\$\*/$(printf '%02d' "$s")}
            fi
            v=$(sed -n 's/^# eval: \(volume [^:]*: \)\{0,1\}\([0-9][0-9]*\) teacher stands per spacing.*/\2-stands/p' "$t" | head -n 1)
            [ -n "$v" ] || v=unstated  # main-redraw then fails naming the valid volumes
            jobs_list+=("$w $s $a $v $dir $exp${sub:+/$sub}")
        done
    done
done <<<"$sets"
# ---- the projected time ----
# The teacher part at the wall times its frozen units recorded (unit_walls,
# unit_wall.sh, the reader study_cost.sh uses; on the machines and loads
# that made them, so an upper bound more than a forecast): the rerun makes
# every unit of the experiments whose manifest row says "rerun", the units
# the registered ones need included. The model part measured here and now:
# `crownshy main-redraw --cost` gives each redraw's model FLOPs and this
# core's sampling rate for that model (a few timed Euler steps, thread CPU
# time), JOBS at a time; the teacher stands and estimator of a redraw are
# left out (a few per cent).
. src/exp/unit_wall.sh
rerun_re=$(awk -F'\t' '$1 == "EXPERIMENT" && $8 == "rerun" { r = r (r == "" ? "" : "|") $2 } END { print "^(" r ")/" }' <<<"$rows")
teach_s=$(env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL "$MAKE" -s --no-print-directory reproduce-status SCALE=full 2>/dev/null |
          awk -v re="$rerun_re" '$1 ~ /^(done|missing|queued|running|failed)$/ && $2 ~ re { print $2 }' |
          unit_walls frozen | awk -F'\t' '{ s += $2 } END { print s + 0 }')
cost_one() { [ -f "$1" ] && "$CLI" main-redraw --weights "$1" --seed "$2" --arm "$3" --volume "$4" --cost 2>/dev/null; }
export -f cost_one; export CLI
model_s=$(printf '%s\n' "${jobs_list[@]}" | xargs -r -P "$JOBS" -L 1 bash -c 'cost_one "$@"' _ |
          awk -F'\t' '$1 == "redraw_cost" { sub(/^cpu_s /, "", $4); s += $4 } END { print s + 0 }')
awk -v t="$teach_s" -v m="$model_s" -v j="$JOBS" -v nt="$total" -v nm="${#jobs_list[@]}" 'BEGIN {
    printf "verify-deep: projected %.0f min on %d cores: %d teacher units (%.0f CPU-min at the wall times the frozen units recorded, with the units they need) and %d model redraws (%.0f CPU-min at this core'"'"'s sampling rate measured now)\n",
           (t + m) / j / 60, j, nt, t / 60, nm, m / 60 }'
echo "verify-deep: rerunning $total teacher experiment units into $DEEP/ (make -j$JOBS; log $log)"
unset MAKEFLAGS MFLAGS MAKELEVEL MAKEOVERRIDES
nice $MAKE --no-print-directory -j"$JOBS" RESULTS="$DEEP" SCALE=full "${units[@]}" > "$log" 2>&1 &
pid=$!
# progress PID TOTAL WHAT COUNT...: while PID runs, a line each time the count
# the command COUNT prints changes (done of TOTAL, elapsed since now, ETA)
progress() {
    local pid=$1 total=$2 what=$3 t=$SECONDS last=-1 n el eta
    shift 3
    while kill -0 "$pid" 2>/dev/null; do
        n=$("$@")
        if [ "$n" != "$last" ]; then
            el=$((SECONDS - t)); eta="?"
            [ "$n" -gt 0 ] && eta="$(( el * (total - n) / n )) s"
            echo "verify-deep: $n of $total $what, ${el} s elapsed, ETA $eta"
            last=$n
        fi
        sleep 5
    done
}
done_units() { local n=0 u; for u in "${units[@]}"; do [ -f "$u" ] && n=$((n + 1)); done; echo $n; }
progress "$pid" "$total" "units done" done_units
wait "$pid"; rc=$?
echo "verify-deep: units finished in $((SECONDS - t0)) s (make exit $rc)"
if [ $rc -ne 0 ]; then
    echo "verify-deep: FAIL: a unit failed (see $log):"; tail -n 5 "$log" | sed 's/^/  /'
    status=1
fi

# ---- compare every rerun table with frozen/ (data rows, bit for bit) ----
same=0 differ=0 missing=0 skipped=0
while IFS= read -r f; do
    rel=${f#"$DEEP"/}
    fz="frozen/$rel"
    if [ ! -f "$fz" ]; then
        # make freeze leaves out the readings' and sensitivity units' figure tables: nothing to compare
        case "$rel" in readings/*/*/figure_crowns*|readings/*/*/figure_poly*|sensitivity/*/*/figure_crowns*|sensitivity/*/*/figure_poly*) skipped=$((skipped + 1)); continue ;; esac
        echo "  FAIL    $fz: rerun made $f but frozen/ has no such table"; missing=$((missing + 1)); continue
    fi
    # a table that names its input folder (readings/summary.tsv) names frozen/ once frozen
    if cmp -s <(grep -v '^#' "$f" | sed "s|$DEEP/|frozen/|g") <(grep -v '^#' "$fz"); then same=$((same + 1))
    else
        line=$(diff <(grep -v '^#' "$fz") <(grep -v '^#' "$f" | sed "s|$DEEP/|frozen/|g") | head -n 3 | tr '\n' ' ')
        echo "  FAIL    $fz: data rows differ from the rerun $f: $line"
        differ=$((differ + 1))
    fi
done < <(find "$DEEP" -path "$DEEP/model" -prune -o -name '*.tsv' ! -name '*.tmp*' ! -name '.*' -print | sort)
echo "verify-deep: teacher part: $same tables bit-identical to frozen/, $differ differ, $missing not frozen, $skipped figure tables not frozen by design"
[ $((differ + missing)) -eq 0 ] || status=1

# ---- the model part: redraw samples from the frozen weights ----
# Every frozen model of every experiment whose manifest row says "redraw"
# (src/base/manifest.h): each UNIT row of such an experiment that writes
# run_s%_joint.tsv names a set of units (extension-pair-16-stands/main/: the
# pair runs at volume 16-stands; paper-reading/main/, extension-pair/main/,
# model-readings/*/main/: the readings at 96-stands). For every seed x arm of the design the unit's frozen run
# table must be there; its "# weights:" line names the weights beside it, or
# else the unit's --weights in the manifest, under frozen/ (a re-evaluation,
# whose weights are another experiment's frozen file); its "# eval:" line gives the volume by the
# teacher stands per spacing it states (src/exp/mainrun.h: 16 or 96).
# `crownshy main-redraw` draws the unit's clearance samples again (no training)
# into $DEEP/model/<set>/ and each must equal the frozen samples_s<seed>_<arm>.tsv
# (data rows). The list comes from the design (gates/main.gate seeds, or
# READING_NSEEDS for a set whose summary reads READING_SEED_LIST, x the two
# arms), not from the files that happen to exist: a deleted unit fails.
if [ ${#jobs_list[@]} -gt 0 ]; then
    echo "verify-deep: redrawing the samples of ${#jobs_list[@]} frozen models ($JOBS at a time)"
    redraw() {
        local w=$1 s=$2 a=$3 v=$4 dir=$5 set=$6 out ss
        ss=$(printf '%02d' "$s")
        mkdir -p "$DEEP/model/$set"
        out="$DEEP/model/$set/samples_s${ss}_${a}.tsv"
        local fz="$dir/samples_s${ss}_${a}.tsv"
        if [ ! -f "$w" ]; then echo "  FAIL    $w: missing (the weights of $dir/run_s${ss}_${a}.tsv)"; return 1; fi
        if [ ! -f "$fz" ]; then echo "  FAIL    $fz: missing beside $dir/run_s${ss}_${a}.tsv"; return 1; fi
        if ! "$CLI" main-redraw --weights "$w" --seed "$s" --arm "$a" --volume "$v" --out "$out" > "$out.log" 2>&1; then
            echo "  FAIL    $w: crownshy main-redraw failed (see $out.log)"; return 1; fi
        if ! cmp -s <(grep -v '^#' "$out") <(grep -v '^#' "$fz"); then echo "  FAIL    $fz: redrawn samples differ ($out)"; return 1; fi
        echo "  PASS    $fz: redrawn from $w (volume $v), bit-identical"
    }
    export -f redraw; export DEEP CLI
    # The redraws' own samples, never a teacher table: an earlier tier 2's are removed.
    # Each verdict goes to a file of its place in the list, moved there whole, so the
    # progress counts finished redraws and the verdicts print in the list's order,
    # whichever finished first.
    rm -rf "$DEEP/model"; mkdir -p "$DEEP/model/.verdict"
    nm=${#jobs_list[@]} k=0
    for j in "${jobs_list[@]}"; do printf '%06d %s\n' $k "$j"; k=$((k + 1)); done |
        xargs -P "$JOBS" -L 1 bash -c 'v="$DEEP/model/.verdict/$1"; shift; redraw "$@" > "$v.tmp"; mv "$v.tmp" "$v"' _ &
    pid=$!
    done_redraws() { find "$DEEP/model/.verdict" -type f ! -name '*.tmp' | wc -l; }
    progress "$pid" "$nm" "models redrawn" done_redraws
    wait "$pid"
    for ((k = 0; k < nm; k++)); do
        v=$(printf '%s/model/.verdict/%06d' "$DEEP" $k)
        if [ -f "$v" ]; then cat "$v"; else echo "  FAIL    ${jobs_list[$k]%% *}: its redraw gave no verdict"; fi
    done | tee "$DEEP/model/redraw.log"
    redrawn=$(grep -c '^  PASS ' "$DEEP/model/redraw.log" || true)
    redraw_bad=$(( ${#jobs_list[@]} - redrawn ))
fi
[ $((absent + redraw_bad)) -eq 0 ] || status=1
failed_units=$([ $rc -ne 0 ] && echo "a unit failed (make exit $rc, $log)" || echo "every unit ran")
verdict=PASS; [ $status -eq 0 ] || verdict=FAIL
echo "verify-deep: measured $(( (SECONDS - t0 + 30) / 60 )) min on $JOBS cores ($(awk -F: '/model name/ {sub(/^ +/, "", $2); print $2; exit}' /proc/cpuinfo 2>/dev/null))"
echo "verify-deep: $verdict: teacher part $same of $((same + differ + missing)) tables bit-identical ($differ differ, $missing not frozen; $failed_units); model part $redrawn of $designed models redrawn bit-identical ($redraw_bad differ or failed, $absent missing); $((SECONDS - t0)) s; exit $status"
exit $status
