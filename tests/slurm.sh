#!/usr/bin/env bash
# What it catches: the Slurm engine submitting the wrong units (after a
# cancelled job, or again when nothing is left) or giving results that differ
# from a local run.
# tests/slurm.sh: `make reproduce ENGINE=slurm` on a real single-node Slurm (design.md §13).
#
# Run as root from the repository (CI does: .ci/run). It
#   1. installs slurm-wlm and munge with apt-get when missing;
#   2. starts munged (unless one already answers), then slurmctld and slurmd with a
#      slurm.conf written under build/slurm-test/ that puts controller and node on
#      127.0.0.1 (SlurmctldHost=<host>(127.0.0.1), NodeAddr=127.0.0.1; the daemons also
#      bind only to it when the host name resolves to a loopback address), and stops
#      what it started by pid at exit;
#   3. runs SCALE=smoke locally (B=build/slurm-test/local) and through Slurm
#      (B=build/slurm-test/slurm; the node drained until the first pass has submitted
#      every unit, so no job ends before it), cancels one running training job of the Slurm run,
#      waits for the rest, checks that the re-invocation resubmits exactly the cancelled
#      unit and the units that need it, and that a third invocation submits nothing;
#   4. compares every result file of the two runs, `# ...` provenance lines aside.
# When Slurm cannot be brought up it says why and fails; it never skips.
# Ends with one line "N passed, N failed".
set -euo pipefail
cd "$(dirname "$0")/.."
REPO=$(pwd -P)
T=build/slurm-test
TA=$REPO/$T
passed=0 failed=0
ok()   { passed=$((passed + 1)); echo "ok   $*"; }
bad()  { failed=$((failed + 1)); echo "FAIL $*"; }
finish() { echo "$passed passed, $failed failed"; [ "$failed" -eq 0 ]; }
fatal() { echo "slurm test: $*" >&2; bad "$1"; finish || exit 1; exit 1; }

[ "$(id -u)" = 0 ] || fatal "must run as root (it installs slurm-wlm and munge and starts their daemons)"

# ---- 1. packages -----------------------------------------------------------------
need=""
for c in slurmctld slurmd sbatch squeue scontrol scancel sinfo munged munge unmunge; do
    command -v "$c" > /dev/null || need=1
done
if [ -n "$need" ]; then
    echo "slurm test: installing slurm-wlm munge (apt-get)"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -q > /dev/null || fatal "apt-get update failed"
    apt-get install -y -q --no-install-recommends slurm-wlm munge > /dev/null \
        || fatal "apt-get install slurm-wlm munge failed"
fi

rm -rf "$T"
mkdir -p "$T"/state "$T"/spool "$T"/log

# ---- 2. daemons ----------------------------------------------------------------------
pid_munged="" pid_ctld="" pid_slurmd=""
stop_pid() {  # stop_pid NAME PID: TERM, wait up to 10 s, then KILL
    local name=$1 pid=$2 i
    [ -n "$pid" ] && kill -0 "$pid" 2> /dev/null || return 0
    kill "$pid" 2> /dev/null || true
    for i in $(seq 50); do kill -0 "$pid" 2> /dev/null || return 0; sleep 0.2; done
    echo "slurm test: $name (pid $pid) did not stop on TERM; killing it" >&2
    kill -9 "$pid" 2> /dev/null || true
}
cleanup() {
    set +e
    if [ -n "$pid_ctld" ] && kill -0 "$pid_ctld" 2> /dev/null; then
        scancel -u "$(id -un)" 2> /dev/null   # only this test's private controller
        sleep 1
    fi
    stop_pid slurmd "$pid_slurmd"
    stop_pid slurmctld "$pid_ctld"
    stop_pid munged "$pid_munged"
}
trap cleanup EXIT

logs_tail() { local f; for f in "$@"; do [ -f "$f" ] && { echo "--- $f (last lines)"; tail -n 15 "$f"; }; done >&2; }

if munge -n 2> /dev/null | unmunge > /dev/null 2>&1; then
    echo "slurm test: using the munged already running"
else
    # munged insists on its directories belonging to the munge user
    mkdir -p /run/munge /var/log/munge /var/lib/munge
    chmod 755 /run/munge
    chown munge:munge /run/munge /etc/munge /var/log/munge /var/lib/munge
    [ -f /etc/munge/munge.key ] || fatal "munge: no key /etc/munge/munge.key (the munge package creates it)"
    runuser -u munge -- munged || { logs_tail /var/log/munge/munged.log; fatal "munge: munged did not start"; }
    pid_munged=$(cat /run/munge/munged.pid 2> /dev/null || true)
    munge -n | unmunge | grep -q 'STATUS: *Success' \
        || { logs_tail /var/log/munge/munged.log; fatal "munge: munge -n | unmunge does not report Success"; }
    echo "slurm test: munged started (pid $pid_munged)"
fi

port_free() { ! (exec 3<> "/dev/tcp/127.0.0.1/$1") 2> /dev/null; }
port=16817
while ! port_free "$port" || ! port_free $((port + 1)); do
    port=$((port + 2)); [ "$port" -lt 16917 ] || fatal "no two free TCP ports on 127.0.0.1 in 16817-16916"
done
host=$(hostname -s)
bind_note="daemons listen on all addresses; every Slurm address is 127.0.0.1"
comm=""
if getent hosts "$host" | awk '{print $1}' | grep -qE '^(127\.|::1$)'; then
    comm="CommunicationParameters=NoCtldInAddrAny,NoInAddrAny"
    bind_note="daemons bound to $host = loopback"
fi
export SLURM_CONF=$TA/slurm.conf
cat > "$SLURM_CONF" << EOF
# written by tests/slurm.sh: a private single-node cluster on the loopback address
ClusterName=crownshy-test
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
$comm
AuthType=auth/munge
CryptoType=crypto/munge
SlurmUser=root
SlurmdUser=root
MpiDefault=none
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
ReturnToService=2
KillWait=5
MinJobAge=600
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/none
StateSaveLocation=$TA/state
SlurmdSpoolDir=$TA/spool
SlurmctldPidFile=$TA/slurmctld.pid
SlurmdPidFile=$TA/slurmd.pid
SlurmctldLogFile=$TA/log/slurmctld.log
SlurmdLogFile=$TA/log/slurmd.log
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
wait_for() {  # wait_for SECONDS COMMAND...: poll every 0.5 s
    local t=$1 i; shift
    for i in $(seq $((t * 2))); do "$@" > /dev/null 2>&1 && return 0; sleep 0.5; done
    return 1
}
slurmctld || { logs_tail "$TA/log/slurmctld.log"; fatal "slurmctld did not start"; }
wait_for 10 test -s "$TA/slurmctld.pid" && pid_ctld=$(cat "$TA/slurmctld.pid")
wait_for 30 sh -c 'scontrol ping | grep -q UP' \
    || { logs_tail "$TA/log/slurmctld.log"; fatal "slurmctld does not answer scontrol ping on 127.0.0.1:$port"; }
nice -n 10 slurmd || { logs_tail "$TA/log/slurmd.log"; fatal "slurmd did not start"; }   # jobs inherit the nice
wait_for 10 test -s "$TA/slurmd.pid" && pid_slurmd=$(cat "$TA/slurmd.pid")
node_idle() { sinfo -h -n "$host" -o %t | grep -q '^idle'; }
wait_for 60 node_idle \
    || { sinfo >&2 || true; logs_tail "$TA/log/slurmctld.log" "$TA/log/slurmd.log"; fatal "node $host did not become idle"; }
ok "slurm up: slurmctld (pid $pid_ctld) on 127.0.0.1:$port, slurmd (pid $pid_slurmd), node $host idle, $bind_note"
if command -v ss > /dev/null; then
    ss -ltnp 2> /dev/null | awk -v a=":$port" -v b=":$((port + 1))" '/slurm/ && ($4 ~ a "$" || $4 ~ b "$") {print "    listening: " $4}' || true
fi

# ---- 3. local smoke run, then the Slurm one ------------------------------------------
LOCAL=(SCALE=smoke B=$T/local)
SLURM=(SCALE=smoke B=$T/slurm)
make --no-print-directory deps || fatal "make deps failed (the Debian build packages)"
echo "slurm test: building both CLIs"
nice make -j2 --no-print-directory "${LOCAL[@]}" "$T/local/crownshy" > "$T/build-local.log" 2>&1 \
    || { tail -20 "$T/build-local.log" >&2; fatal "build for the local run failed (log $T/build-local.log)"; }
nice make -j2 --no-print-directory "${SLURM[@]}" "$T/slurm/crownshy" > "$T/build-slurm.log" 2>&1 \
    || { tail -20 "$T/build-slurm.log" >&2; fatal "build for the Slurm run failed (log $T/build-slurm.log)"; }

t0=$SECONDS
if nice make -j2 --no-print-directory reproduce "${LOCAL[@]}" > "$T/local.log" 2>&1; then
    t_local=$((SECONDS - t0))
    ok "local smoke run: $t_local s with -j2 (log $T/local.log)"
else
    tail -20 "$T/local.log" >&2; fatal "local smoke run failed (log $T/local.log)"
fi
if grep -q '^reproduce: [0-9]*/[0-9]* units done, ETA' "$T/local.log" && grep -q '^reproduce: \([0-9]*\)/\1 units up to date' "$T/local.log"; then
    ok "local run showed progress with an ETA: $(grep -c '^reproduce: [0-9]*/[0-9]* units done' "$T/local.log") progress lines"
else
    bad "local run printed no progress line with an ETA (log $T/local.log)"
fi

# graph: unit -> units it needs, as the engine derives it from make
mapfile -t GRAPH < <(make -s --no-print-directory reproduce-graph "${SLURM[@]}")
total=${#GRAPH[@]}
[ "$total" -gt 10 ] || fatal "make reproduce-graph listed $total units"
RS=$T/slurm/smoke
dependents() {  # the unit and every unit that needs it, transitively (sorted)
    local -A in=([$1]=1); local changed=1 line u p
    while [ -n "$changed" ]; do
        changed=""
        for line in "${GRAPH[@]}"; do
            u=${line%%$'\t'*}; [ -n "${in[$u]:-}" ] && continue
            for p in ${line#*$'\t'}; do [ -n "${in[$p]:-}" ] && { in[$u]=1; changed=1; break; }; done
        done
    done
    printf '%s\n' "${!in[@]}" | sed "s|^$RS/||" | sort
}
jobs_live() { squeue -h -u "$(id -un)" -o %i | grep -q .; }
wait_drained() {  # wait_drained SECONDS
    local i
    for i in $(seq $(($1 * 2))); do jobs_live || return 0; sleep 0.5; done
    return 1
}
submitted() { sed -n 's/^reproduce: submitted \([^:]*\): job .*/\1/p' "$1" | sort; }

# The node is drained while the first pass submits: at smoke scale a training job can
# start and end in the seconds that 164 submissions take, leaving none to cancel. The
# jobs wait in the queue (as on a busy cluster) and start when the node is resumed.
node_state() { scontrol update NodeName="$host" State="$1" ${2:+"Reason=$2"}; }
node_state DRAIN "tests/slurm.sh: held while the first pass submits" \
    || fatal "scontrol could not drain node $host before the first pass"
t0=$SECONDS
make --no-print-directory reproduce ENGINE=slurm "${SLURM[@]}" > "$T/slurm-1.log" 2>&1 \
    || { cat "$T/slurm-1.log" >&2; fatal "make reproduce ENGINE=slurm failed (log $T/slurm-1.log)"; }
n1=$(submitted "$T/slurm-1.log" | wc -l)
if [ "$n1" -eq "$total" ]; then ok "first Slurm pass submitted all $total units, one job each"
else bad "first Slurm pass submitted $n1 of $total units (log $T/slurm-1.log)"; fi

node_state RESUME || fatal "scontrol could not resume node $host after the first pass"

# Cancel one training job (extension-pair-16-stands/main/run_*) in the middle of its training; if it finishes
# before the cancel lands, try the next. Its checkpoint (build/.../ckpt/) stays, so the
# resubmitted job resumes from it, and must still give the local run's results.
JOBS=$TA/slurm/reproduce/smoke/slurm/jobs.tsv
cancelled=""
mapfile -t cands < <(awk -F'\t' '$1 ~ /^extension-pair-16-stands\/main\/run_s/ {print $1 "\t" $2 "\t" $3}' "$JOBS")
deadline=$((SECONDS + 600))
while [ -z "$cancelled" ] && [ "$SECONDS" -lt "$deadline" ]; do
    # a failed squeue (a busy controller can time out) says nothing about the queue:
    # ask again rather than read it as empty
    if ! q=$(squeue -h -u "$(id -un)" -o '%i %T' 2>&1); then
        echo "slurm test: squeue failed ($q); asking again"; sleep 0.5; continue
    fi
    left=0
    for c in "${cands[@]}"; do
        IFS=$'\t' read -r unit id log <<< "$c"
        [ -f "$RS/$unit" ] && continue
        st=$(awk -v id="$id" '$1 == id {print $2}' <<< "$q")
        [ -n "$st" ] && left=$((left + 1))
        if [ "$st" = RUNNING ]; then
            # cancel it mid-training: once the first training step is in its log
            for i in $(seq 250); do grep -q '^epoch' "$log" 2> /dev/null && break; sleep 0.02; done
            scancel "$id"
            sleep 0.3
            if [ -f "$RS/$unit" ]; then echo "slurm test: $unit (job $id) finished before the cancel landed; trying another"
            else cancelled=$unit cancelled_id=$id; break; fi
        fi
    done
    [ -n "$cancelled" ] || [ "$left" -gt 0 ] || break
    sleep 0.1
done
if [ -z "$cancelled" ]; then
    ndone=0; for c in "${cands[@]}"; do [ -f "$RS/${c%%$'\t'*}" ] && ndone=$((ndone + 1)); done
    fatal "could not cancel a running training job: ${#cands[@]} candidates in $JOBS, $ndone finished first, the rest not in the queue (last squeue: $(wc -l <<< "$q") lines; log $T/slurm-1.log)"
fi
sleep 1
echo "slurm test: cancelled job $cancelled_id ($cancelled) while it was running; its log ends:"
tail -n 3 "$log" | sed 's/^/    /'
ck=$T/slurm/ckpt/smoke/extension-pair-16-stands_${cancelled#extension-pair-16-stands/main/run_}; ck=${ck%.tsv}.ckpt
if [ -f "$ck" ]; then echo "slurm test: its checkpoint $ck is left for the resubmitted job"; fi
wait_drained 600 || fatal "jobs still queued after 10 min (squeue; logs in $T/slurm/reproduce/smoke/slurm/logs)"
t_slurm1=$((SECONDS - t0))

make -s --no-print-directory reproduce-status "${SLURM[@]}" > "$T/status-1.log" 2>&1 || true
mapfile -t expect < <(dependents "$RS/$cancelled")
mapfile -t missing < <(awk '$1 != "done" && $1 != "reproduce-status:" {print $2}' "$T/status-1.log" | sort)
if [ "${expect[*]}" = "${missing[*]}" ]; then
    ok "after the cancel exactly ${#expect[@]} units are not done: $cancelled and the units that need it (${expect[*]})"
else
    bad "after the cancel, not done: ${missing[*]}; expected ${expect[*]} (status in $T/status-1.log)"
fi
line=$(awk -v u="$cancelled" '$2 == u' "$T/status-1.log")
log=$(sed -n 's/.*log \(\/[^ ]*\.log\).*/\1/p' <<< "$line")
if [[ $line == failed* ]] && [ -n "$log" ] && [ -f "$log" ]; then
    ok "reproduce-status shows the cancelled unit failed with its log: $line"
else
    bad "reproduce-status line of the cancelled unit: '$line' (expected 'failed ... log <existing file>')"
fi

t0=$SECONDS
make --no-print-directory reproduce ENGINE=slurm "${SLURM[@]}" > "$T/slurm-2.log" 2>&1 \
    || { cat "$T/slurm-2.log" >&2; fatal "second make reproduce ENGINE=slurm failed (log $T/slurm-2.log)"; }
mapfile -t resub < <(submitted "$T/slurm-2.log")
if [ "${resub[*]}" = "${expect[*]}" ]; then
    ok "the re-invocation resubmitted only the missing units: ${resub[*]} (${#resub[@]} of $total)"
else
    bad "the re-invocation resubmitted: ${resub[*]}; expected: ${expect[*]} (log $T/slurm-2.log)"
fi
# at once again, while those jobs are queued or running: nothing is submitted twice
make --no-print-directory reproduce ENGINE=slurm "${SLURM[@]}" > "$T/slurm-2b.log" 2>&1 || true
kept=$(grep -c '^reproduce: kept ' "$T/slurm-2b.log" || true)
if [ -z "$(submitted "$T/slurm-2b.log")" ] && grep -q ', 0 submitted$' "$T/slurm-2b.log"; then
    ok "re-invoking while they are queued or running submits nothing (kept $kept live jobs)"
else
    bad "re-invoking while jobs are live submitted: $(submitted "$T/slurm-2b.log" | tr '\n' ' ')(log $T/slurm-2b.log)"
fi
wait_drained 600 || fatal "resubmitted jobs still queued after 10 min"
t_slurm2=$((SECONDS - t0))
relog=$(awk -F'\t' -v u="$cancelled" '$1 == u {l = $3} END {print l}' "$JOBS")
if grep -q 'resuming at step' "$relog" 2> /dev/null; then
    echo "slurm test: the resubmitted job of $cancelled: $(grep -m1 'resuming at step' "$relog")"
fi
make -s --no-print-directory reproduce-status "${SLURM[@]}" > "$T/status-2.log" 2>&1 || true
if tail -n 1 "$T/status-2.log" | grep -q ": $total done, 0 running, 0 queued, 0 failed, 0 missing"; then
    ok "after the resume all $total units are done"
else
    bad "after the resume: $(tail -n 1 "$T/status-2.log") (status in $T/status-2.log)"
fi
make --no-print-directory reproduce ENGINE=slurm "${SLURM[@]}" > "$T/slurm-3.log" 2>&1 || true
if grep -q "^reproduce: $total units in .*: $total up to date, 0 already queued or running, 0 submitted" "$T/slurm-3.log"; then
    ok "a third invocation submits nothing"
else
    bad "a third invocation: $(tail -n 2 "$T/slurm-3.log" | head -n 1) (log $T/slurm-3.log)"
fi

# ---- 4. every result file, bit for bit, provenance lines aside -------------------------
RL=$T/local/smoke
if diff <(cd "$RL" && find . -type f ! -name '*.tmp' | sort) <(cd "$RS" && find . -type f ! -name '*.tmp' | sort) > "$T/files.diff"; then
    nf=0 nd=0 first=""
    while IFS= read -r f; do
        nf=$((nf + 1))
        # the E3/E4 weights files are binary: byte for byte
        if case "$f" in *.ckpt) ! cmp -s "$RL/$f" "$RS/$f";; *) ! cmp -s <(grep -v '^#' "$RL/$f") <(grep -v '^#' "$RS/$f");; esac; then
            nd=$((nd + 1)); [ -n "$first" ] || first=$f
        fi
    done < <(cd "$RL" && find . -type f ! -name '*.tmp' | sort)
    if [ "$nd" -eq 0 ]; then ok "all $nf result files identical to the local run's, provenance lines aside"
    else bad "$nd of $nf result files differ from the local run's (first: $first)"; fi
else
    bad "the two runs wrote different sets of files ($T/files.diff)"
fi

echo "slurm test: local smoke $t_local s; Slurm smoke $t_slurm1 s (submission to the last job, one job cancelled); resume $t_slurm2 s; under load $(cut -d' ' -f1-3 /proc/loadavg)"
finish
