#!/usr/bin/env bash
# reproduce.sh: the engines behind `make reproduce` (design.md §13).
#
#   make reproduce [ENGINE=local] [SCALE=smoke]   make -jN on the units, with progress and ETA
#   make reproduce ENGINE=slurm [SLURM_ARGS=...]  one Slurm job per unit that is not up to date
#   make reproduce-status                         per-unit state: done, queued, running, failed, missing
#   make reproduce-graph                          each unit and the units it needs
#
# The pipeline is defined once, in make (src/exp/experiments.mk). This script never lists
# units: it asks make for its database (`make -pn` on the registered units,
# REPRODUCE_UNITS) and takes every target under the results directory reachable from
# them, with its prerequisites that are units themselves. Whether a unit is done is
# `make -q <unit>` (the binary, an order-only prerequisite, is not rebuilt for the
# question). A Slurm job runs the very make target a local run would:
# `make -C <repo> SCALE=... <unit file>`.
#
# Called from the Makefile with REPRODUCE_RESULTS, REPRODUCE_UNITS, REPRODUCE_STATE,
# REPRODUCE_CLI, REPRODUCE_VARS (the make variables a job passes: SCALE=..., and B=,
# RESULTS= when given on the command line), SCALE, SLURM_ARGS and MAKE set.
# Bookkeeping lives in REPRODUCE_STATE (build/reproduce/<results dir name>/):
#   walltimes.tsv   last wall time seen per unit (for the ETA)
#   runs.tsv        per local run that made every unit: date, units, -j, seconds
#   slurm/jobs.tsv  one line per submission: unit, job id, log, submit time (last wins)
#   slurm/logs/     one log per job; slurm/rc/<job id> the exit status of its make
set -euo pipefail

die() { echo "reproduce: $*" >&2; exit 1; }

# ---- a Slurm job (sbatch runs a copy of this file): job RCDIR MAKE-COMMAND... -----
if [ "${1:-}" = job ]; then
    rcdir=$2; shift 2
    # The submitting make's flags (jobserver, command-line variables) must not leak in.
    unset MAKEFLAGS MFLAGS MAKELEVEL MAKEOVERRIDES
    echo "reproduce: job ${SLURM_JOB_ID:-?} on $(hostname) at $(date -u +%FT%TZ): $*"
    set +e; "$@"; rc=$?; set -e
    mkdir -p "$rcdir" && echo "$rc" > "$rcdir/${SLURM_JOB_ID:-unknown}"
    echo "reproduce: job ${SLURM_JOB_ID:-?} exit $rc at $(date -u +%FT%TZ)"
    exit "$rc"
fi

mode=${1:-}
[ -n "$mode" ] || die "usage: reproduce.sh local|slurm|status|graph (run through make: make reproduce [ENGINE=local|slurm])"
RESULTS=${REPRODUCE_RESULTS:?reproduce.sh: REPRODUCE_RESULTS not set (run it through make)}
STATE=${REPRODUCE_STATE:?reproduce.sh: REPRODUCE_STATE not set (run it through make)}
CLI=${REPRODUCE_CLI:?reproduce.sh: REPRODUCE_CLI not set (run it through make)}
MAKE_BIN=${MAKE:-make}
SCALE=${SCALE:-full}
read -r -a TOP <<< "${REPRODUCE_UNITS:-}"
read -r -a VARS <<< "${REPRODUCE_VARS:-SCALE=$SCALE}"
[ "${#TOP[@]}" -gt 0 ] || die "no unit registered (REPRODUCE_UNITS is empty)"
REPO=$(pwd -P)
SELF=$(realpath "$0")  # submitted as the batch script of every job (its `job` mode)
case $STATE in /*) ;; *) STATE=$REPO/$STATE ;; esac
SL=$STATE/slurm
mkdir -p "$STATE"

# make for questions: no inherited flags, no jobserver, the job's variables.
qmake() { env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL "$MAKE_BIN" --no-print-directory "${VARS[@]}" "$@"; }
rel() { printf '%s' "${1#"$RESULTS"/}"; }

# ---- the unit graph, from make's own database ------------------------------------
# ORDER: units in dependency order; PRE[u]: its prerequisite units.
declare -a ORDER=()
declare -A PRE=()
load_graph() {
    local db err edges
    db=$(mktemp) err=$(mktemp) edges=$(mktemp)
    if ! qmake -pn -o "$CLI" "${TOP[@]}" > "$db" 2> "$err"; then
        cat "$err" >&2; rm -f "$db" "$err" "$edges"
        die "make -pn on the registered units failed (above); cannot derive the unit graph"
    fi
    # "# Files" section: "target: prereqs | order-only" lines, except after "# Not a target:".
    awk -v R="$RESULTS/" '
        /^# Files/ { f = 1; next }
        /^# files hash-table stats/ { f = 0 }
        !f { next }
        /^# Not a target:/ { skip = 1; next }
        /^$/ || /^#/ || /^\t/ { next }
        {
            if (skip) { skip = 0; next }
            i = index($0, ":"); if (i == 0) next
            t = substr($0, 1, i - 1); rest = substr($0, i + 1)
            if (substr(rest, 1, 1) == "=" || substr(rest, 1, 1) == ":") next
            if (index(t, R) != 1) next
            j = index(rest, "|"); if (j) rest = substr(rest, 1, j - 1)
            printf "%s", t; n = split(rest, p, " ")
            for (k = 1; k <= n; k++) if (index(p[k], R) == 1) printf "\t%s", p[k]
            printf "\n"
        }' "$db" > "$edges"
    rm -f "$db" "$err"
    local -A target=() seen=()
    local line t p
    while IFS= read -r line; do
        t=${line%%$'\t'*}; target[$t]=1
        if [[ $line == *$'\t'* ]]; then PRE[$t]=${line#*$'\t'}; PRE[$t]=${PRE[$t]//$'\t'/ }; else PRE[$t]=""; fi
    done < "$edges"
    rm -f "$edges"
    # closure from the registered units; prerequisites without a rule are inputs, not units
    local -a stack=("${TOP[@]}")
    while [ "${#stack[@]}" -gt 0 ]; do
        t=${stack[-1]}; unset 'stack[-1]'
        [ -n "${seen[$t]:-}" ] && continue
        [ -n "${target[$t]:-}" ] || die "registered unit $t has no rule in make's database"
        seen[$t]=1
        local keep=""
        for p in ${PRE[$t]}; do if [ -n "${target[$p]:-}" ]; then keep+=" $p"; stack+=("$p"); fi; done
        PRE[$t]=${keep# }
    done
    mapfile -t ORDER < <(for t in "${!seen[@]}"; do echo "$t $t"; for p in ${PRE[$t]}; do echo "$p $t"; done; done | tsort)
    [ "${#ORDER[@]}" -eq "${#seen[@]}" ] || die "the unit graph has a cycle (tsort)"
}

# make -q: 0 up to date, 1 to be made; anything else is an error in the makefile.
declare -A UPTODATE=()
check_units() {
    local u rc
    for u in "${ORDER[@]}"; do
        set +e; qmake -q -o "$CLI" "$u" > /dev/null 2>&1; rc=$?; set -e
        case $rc in
            0) UPTODATE[$u]=1 ;;
            1) UPTODATE[$u]="" ;;
            *) qmake -q -o "$CLI" "$u" || true; die "make -q $u failed (exit $rc)" ;;
        esac
    done
}

wall_of() { [ -f "$1" ] && sed -n '/^#/!q; s/^# wall_s: *//p' "$1" | head -n 1 || true; }

fmt_s() {  # seconds (float) -> "1 h 02 min", "3 min 05 s", "12 s"
    awk -v s="$1" 'BEGIN { s = int(s + 0.5);
        if (s >= 3600) printf "%d h %02d min", s / 3600, (s % 3600) / 60;
        else if (s >= 60) printf "%d min %02d s", s / 60, s % 60; else printf "%d s", s }'
}

# ---- local: make -jN with a progress line per finished unit --------------------------
declare -A EXPECT=()
# One line whenever the number of finished units changes (runs in the background of
# run_local, whose todo, ntodo, total, j, stamp, t_start, EXPECT, WEIGHTS it reads). The ETA
# is the recorded wall time of the units still to make at this run's pace so far
# (elapsed time over the recorded time of the units it finished); before the first
# one finishes, that time shared by j workers, never less than its longest unit.
progress() {
    local last=-1 n remain longest unknown num den line u w
    while :; do
        n=0 num=0 den=0
        for u in "${todo[@]}"; do
            [ "$u" -nt "$stamp" ] || continue
            n=$((n + 1))
            if [ -n "${EXPECT[$u]:-}" ]; then den=$(awk -v a="$den" -v b="${EXPECT[$u]}" 'BEGIN { print a + b }'); fi
        done
        if [ "$n" -ne "$last" ]; then
            last=$n remain=0 longest=0 unknown=0
            num=$(awk -v a="$(date +%s.%N)" -v b="$t_start" 'BEGIN { print a - b }')
            for u in "${todo[@]}"; do
                [ "$u" -nt "$stamp" ] && continue
                w=${EXPECT[$u]:-}
                if [ -z "$w" ]; then unknown=$((unknown + 1)); continue; fi
                remain=$(awk -v a="$remain" -v b="$w" 'BEGIN { print a + b }')
                longest=$(awk -v a="$longest" -v b="$w" 'BEGIN { print (b > a) ? b : a }')
            done
            line="reproduce: $((total - ntodo + n))/$total units done"
            if [ "$n" -lt "$ntodo" ]; then
                if [ -n "$WEIGHTS" ] && ! awk -v d="$den" 'BEGIN { exit !(d > 0) }'; then
                    line+=", ETA once a unit has finished (no wall times recorded at SCALE=$SCALE yet)"
                elif [ "$unknown" -lt "$((ntodo - n))" ]; then
                    w=$(awk -v a="$remain" -v j="$j" -v l="$longest" -v t="$num" -v d="$den" \
                        'BEGIN { if (d > 0) print a * t / d; else { e = a / j; print (l > e) ? l : e } }')
                    line+=", ETA ~$(fmt_s "$w")"
                    [ "$unknown" -gt 0 ] && line+=" + $unknown unit(s) with no recorded wall time"
                else
                    line+=", no ETA: no wall time recorded for these units"
                fi
            fi
            echo "$line"
        fi
        [ "$n" -ge "$ntodo" ] && return 0
        sleep 2
    done
}

run_local() {
    load_graph; check_units
    local total=${#ORDER[@]} todo=() u
    for u in "${ORDER[@]}"; do [ -n "${UPTODATE[$u]}" ] || todo+=("$u"); done
    local ntodo=${#todo[@]} j=1
    if [[ " ${MAKEFLAGS:-} " =~ \ -j([0-9]+) ]]; then j=${BASH_REMATCH[1]};
    elif [[ " ${MAKEFLAGS:-} " =~ \ -j\  ]]; then j=$(nproc); fi
    if [ "$ntodo" -eq 0 ]; then echo "reproduce: all $total units up to date in $RESULTS"; return 0; fi
    # Expected wall time of each unit to run, from recorded `# wall_s:` provenance lines:
    # the (out-of-date) result itself, else the last run at this scale (walltimes.tsv),
    # else the frozen result (frozen/<experiment>/, full scale). At another scale, unless
    # every unit has a record at that scale, the frozen times serve as relative weights
    # only (WEIGHTS=1): no ETA until this run's pace is measured on a finished unit.
    local rec=$STATE/walltimes.tsv w r
    local -A REC=() OWN=()
    WEIGHTS=""
    if [ -f "$rec" ]; then while IFS=$'\t' read -r r w; do REC[$r]=$w; done < "$rec"; fi
    for u in "${todo[@]}"; do
        r=$(rel "$u"); w=$(wall_of "$u"); [ -n "$w" ] || w=${REC[$r]:-}
        if [ -n "$w" ]; then OWN[$u]=$w; else WEIGHTS=1; fi
    done
    if [ "$SCALE" = full ] || [ -z "$WEIGHTS" ]; then
        WEIGHTS=""
        for u in "${!OWN[@]}"; do EXPECT[$u]=${OWN[$u]}; done
    fi
    for u in "${todo[@]}"; do
        if [ -z "${EXPECT[$u]:-}" ]; then
            w=$(wall_of "frozen/$(rel "$u")"); if [ -n "$w" ]; then EXPECT[$u]=$w; fi
        fi
    done
    local stamp=$STATE/local.start t_start
    : > "$stamp"; t_start=$(date +%s.%N)
    echo "reproduce: $((total - ntodo)) of $total units up to date in $RESULTS; making $ntodo with -j$j"
    progress &
    local mon=$! rc t0=$SECONDS
    trap 'kill "$mon" 2>/dev/null || true' EXIT
    set +e; "$MAKE_BIN" --no-print-directory "${TOP[@]}"; rc=$?; set -e
    kill "$mon" 2>/dev/null || true; wait "$mon" 2>/dev/null || true
    trap - EXIT
    # the wall times of this run, for the next run's ETA (last entry per unit wins)
    local -A DONE=()
    for u in "${todo[@]}"; do
        [ "$u" -nt "$stamp" ] || continue
        DONE[$u]=1; w=$(wall_of "$u"); if [ -n "$w" ]; then REC[$(rel "$u")]=$w; fi
    done
    for r in "${!REC[@]}"; do printf '%s\t%s\n' "$r" "${REC[$r]}"; done | sort > "$rec.tmp" && mv "$rec.tmp" "$rec"
    if [ "$rc" -ne 0 ]; then
        echo "reproduce: make failed (exit $rc) after $((total - ntodo + ${#DONE[@]})) of $total units; rerun to resume" >&2
        return "$rc"
    fi
    echo "reproduce: $total/$total units up to date in $RESULTS (${#DONE[@]} made in $(fmt_s $((SECONDS - t0))))"
    # a run that made every unit: its measured wall time, against which
    # study_cost.sh's projection of the same units can be checked
    if [ "$ntodo" -eq "$total" ]; then
        printf '%s\t%s\t%s\t%s\n' "$(date -u +%FT%TZ)" "${#DONE[@]}" "$j" "$((SECONDS - t0))" >> "$STATE/runs.tsv"
    fi
}

# ---- Slurm bookkeeping ---------------------------------------------------------------
declare -A JOB=() JOBLOG=() LIVE=()
load_jobs() {
    local r id log at
    [ -f "$SL/jobs.tsv" ] || return 0
    while IFS=$'\t' read -r r id log at; do JOB[$RESULTS/$r]=$id; JOBLOG[$RESULTS/$r]=$log; done < "$SL/jobs.tsv"
}
# LIVE[id] = "STATE reason" for this user's jobs still known to the queue.
load_queue() {
    local out id st reason
    out=$(squeue -h -u "$(id -un)" -o '%i %T %r' 2>&1) || die "squeue failed: $out"
    while read -r id st reason; do if [ -n "$id" ]; then LIVE[$id]="$st $reason"; fi; done <<< "$out"
}
ended_state() {  # how a job that left the queue ended, if Slurm still knows
    local s
    s=$(scontrol show job "$1" 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p' | head -n 1) || true
    if [ -z "$s" ] && command -v sacct > /dev/null; then
        s=$(sacct -n -X -P -j "$1" -o State 2>/dev/null | head -n 1 | awk '{print $1}') || true
        [[ $s =~ ^[A-Z_]+$ ]] || s=""
    fi
    printf '%s' "$s"
}

run_slurm() {
    local c
    for c in sbatch squeue scontrol scancel; do
        command -v "$c" > /dev/null || die "ENGINE=slurm needs the Slurm client commands on PATH ($c not found; Debian: apt-get install slurm-client)"
    done
    mkdir -p "$SL/logs" "$SL/rc"
    # the queue first, then make -q: a job ending in between is seen as done, never twice
    load_queue; load_graph; load_jobs; check_units
    unset MAKEFLAGS MFLAGS MAKELEVEL MAKEOVERRIDES  # sbatch exports the environment
    local -a extra=()
    read -r -a extra <<< "${SLURM_ARGS:-}"
    local -A JOBFOR=() NEW=()
    local u r id st why deps p log out ndone=0 nkept=0 nsub=0
    for u in "${ORDER[@]}"; do
        r=$(rel "$u")
        if [ -n "${UPTODATE[$u]}" ]; then ndone=$((ndone + 1)); continue; fi
        id=${JOB[$u]:-}
        if [ -n "$id" ] && [ -n "${LIVE[$id]:-}" ]; then
            st=${LIVE[$id]} why=""
            [[ $st == *DependencyNeverSatisfied* ]] && why="its dependency failed"
            for p in ${PRE[$u]}; do if [ -n "${NEW[$p]:-}" ]; then why="${p#"$RESULTS"/} is resubmitted"; fi; done
            if [ -n "$why" ]; then
                scancel "$id" || die "scancel $id failed (job of $r: $why)"
                echo "reproduce: cancelled job $id of $r ($why)"
            else
                JOBFOR[$u]=$id; nkept=$((nkept + 1))
                echo "reproduce: kept $r: job $id ${st%% *}"
                continue
            fi
        fi
        deps=""
        for p in ${PRE[$u]}; do if [ -n "${JOBFOR[$p]:-}" ]; then deps+=":${JOBFOR[$p]}"; fi; done
        log=$SL/logs/${r//\//__}
        log=${log%.tsv}.%j.log
        local -a dep_arg=()
        [ -n "$deps" ] && dep_arg=("--dependency=afterok$deps" "--kill-on-invalid-dep=yes")
        if ! out=$(sbatch --parsable -J "crownshy:${r%.tsv}" -D "$REPO" -o "$log" -n 1 -c 1 \
                     "${dep_arg[@]}" "${extra[@]}" \
                     "$SELF" job "$SL/rc" "$MAKE_BIN" -C "$REPO" --no-print-directory "${VARS[@]}" "$u" 2>&1); then
            die "sbatch failed for unit $r: $out"
        fi
        id=${out##*$'\n'}; id=${id%%;*}
        [[ $id =~ ^[0-9]+$ ]] || die "sbatch for unit $r printed no job id: $out"
        log=${log//%j/$id}
        printf '%s\t%s\t%s\t%s\n' "$r" "$id" "$log" "$(date -u +%FT%TZ)" >> "$SL/jobs.tsv"
        JOBFOR[$u]=$id; NEW[$u]=1; nsub=$((nsub + 1))
        echo "reproduce: submitted $r: job $id${deps:+ after ${deps#:}}"
    done
    echo "reproduce: ${#ORDER[@]} units in $RESULTS: $ndone up to date, $nkept already queued or running, $nsub submitted"
    echo "reproduce: follow with: make reproduce-status ${VARS[*]}; logs in ${SL#"$REPO"/}/logs/"
}

# ---- status --------------------------------------------------------------------------
status() {
    local have_q=""
    if command -v squeue > /dev/null && [ -f "$SL/jobs.tsv" ]; then
        if out=$(squeue -h -u "$(id -un)" -o '%i %T %r' 2>&1); then
            have_q=1
            while read -r id st reason; do if [ -n "$id" ]; then LIVE[$id]="$st $reason"; fi; done <<< "$out"
        else
            echo "reproduce-status: squeue failed ($out); queue state unknown" >&2
        fi
    fi
    load_graph; load_jobs; check_units
    local u r id log st rc n_done=0 n_q=0 n_run=0 n_fail=0 n_miss=0 n_unk=0 state detail out reason
    for u in "${ORDER[@]}"; do
        r=$(rel "$u"); id=${JOB[$u]:-}; log=${JOBLOG[$u]:-}; detail=""
        if [ -n "${UPTODATE[$u]}" ]; then
            state=done; n_done=$((n_done + 1))
            w=$(wall_of "$u"); [ -n "$w" ] && detail="wall ${w} s"
        elif [ -n "$id" ] && [ -n "${LIVE[$id]:-}" ]; then
            st=${LIVE[$id]%% *}; reason=${LIVE[$id]#* }
            case $st in
                RUNNING|COMPLETING) state=running; n_run=$((n_run + 1)); detail="job $id, log $log" ;;
                PENDING) if [ "$reason" = DependencyNeverSatisfied ]; then
                             state=failed; n_fail=$((n_fail + 1)); detail="job $id waits on a failed dependency (make reproduce resubmits)"
                         else state=queued; n_q=$((n_q + 1)); detail="job $id ($reason)"; fi ;;
                *) state=queued; n_q=$((n_q + 1)); detail="job $id $st ($reason)" ;;
            esac
        elif [ -n "$id" ]; then
            if [ -f "$SL/rc/$id" ]; then
                rc=$(cat "$SL/rc/$id")
                if [ "$rc" != 0 ]; then state=failed; n_fail=$((n_fail + 1)); detail="job $id, make exit $rc, log $log"
                else state=missing; n_miss=$((n_miss + 1)); detail="job $id succeeded but the unit is out of date again"; fi
            elif [ -z "$have_q" ]; then
                state=unknown; n_unk=$((n_unk + 1)); detail="job $id; no queue to ask"
            else
                st=$(ended_state "$id")
                if [ -f "$log" ]; then
                    state=failed; n_fail=$((n_fail + 1))
                    detail="job $id ended without an exit status${st:+ ($st)}: cancelled, killed or out of time; log $log"
                else
                    state=missing; n_miss=$((n_miss + 1))
                    detail="job $id never started${st:+ ($st)}: cancelled, or a unit it needs failed"
                fi
            fi
        else
            state=missing; n_miss=$((n_miss + 1))
            [ -e "$u" ] && detail="out of date" || detail="not made"
        fi
        printf '%-8s %-40s %s\n' "$state" "$r" "$detail"
    done
    local s="reproduce-status: ${#ORDER[@]} units in $RESULTS: $n_done done, $n_run running, $n_q queued, $n_fail failed, $n_miss missing"
    [ "$n_unk" -gt 0 ] && s+=", $n_unk unknown"
    echo "$s"
}

case $mode in
    local) run_local ;;
    slurm) run_slurm ;;
    status) status ;;
    graph) load_graph; for u in "${ORDER[@]}"; do printf '%s\t%s\n' "$u" "${PRE[$u]}"; done ;;
    *) die "unknown ENGINE or mode '$mode' (ENGINE=local or ENGINE=slurm; reproduce.sh status|graph)" ;;
esac
