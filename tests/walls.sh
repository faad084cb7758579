#!/usr/bin/env bash
# Recorded wall times (design.md §10): a re-evaluation of frozen weights
# (main-eval) never records a training time of its own. Its `# wall_s:` is
# the evaluation's; its `# trained_wall_s:` is the one the training run
# recorded, carried unchanged through every re-evaluation, or absent. On
# frozen/: no table's trained_wall_s and trained_date are the wall_s and
# date of a re-evaluation table, and the tables naming one training run
# (trained_git_commit, trained_date) agree on its trained_wall_s. Through
# unit_walls (src/exp/unit_wall.sh, the reader of study_cost.sh and
# verify-deep): a training unit frozen as a re-evaluation counts at its
# trained_wall_s, a re-evaluation unit at its own wall_s, whose evaluation
# part is that wall_s. A copy where one re-evaluation carries a
# re-evaluation's wall time must fail (the check can fail).
# Prints cmocka-style lines so tests/run.sh counts the cases.
set -u
cd "$(dirname "$0")/.."
. src/exp/unit_wall.sh
pass=0; fail=0
ok()  { echo "[       OK ] $1"; pass=$((pass + 1)); }
bad() { echo "[  FAILED  ] $1: $2"; fail=$((fail + 1)); }

# trained_check ROOT: prints the first table whose training record is a
# re-evaluation's, or two tables disagreeing on one run's; returns 1, else 0
trained_check() {
    local files
    mapfile -t files < <(grep -rl --include='run_s*.tsv' '^# trained_wall_s: ' "$1" 2>/dev/null; grep -rl --include='run_s*.tsv' '^# command: crownshy main-eval ' "$1" 2>/dev/null)
    [ ${#files[@]} -gt 0 ] || return 0
    awk '
      FNR == 1 { f = FILENAME; cmd = "" }
      !/^#/ { nextfile }
      /^# command: crownshy main-eval / { ev[f] = 1 }
      /^# wall_s: / { W[f] = $3 } /^# date: / { D[f] = $3 }
      /^# trained_wall_s: / { TW[f] = $3 } /^# trained_date: / { TD[f] = $3 } /^# trained_git_commit: / { TC[f] = $3 }
      END {
        for (f in ev) if (f in W) reeval[W[f] SUBSEP D[f]] = f
        for (f in TW) {
          k = TW[f] SUBSEP TD[f]
          if (k in reeval) { printf "%s: trained_wall_s %s is the wall time of the re-evaluation %s\n", f, TW[f], reeval[k]; exit 1 }
          r = TC[f] SUBSEP TD[f]
          if ((r in run) && run[r] != TW[f]) { printf "%s: trained_wall_s %s, but %s records %s for the same training run\n", f, TW[f], who[r], run[r]; exit 1 }
          run[r] = TW[f]; who[r] = f
        }
      }' "${files[@]}"
}

if msg=$(trained_check frozen); then ok "no frozen re-evaluation records a training time of its own"
else bad "no frozen re-evaluation records a training time of its own" "$msg"; fi

# the check can fail: a copy of one re-evaluation whose training record is a
# re-evaluation's own wall time and date
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/a" "$tmp/b"
src=frozen/extension-pair-16-stands/main/run_s01_joint.tsv
if [ -f "$src" ]; then
    cp "$src" "$tmp/a/run_s01_joint.tsv"
    w=$(sed -n 's/^# wall_s: //p' "$src"); d=$(sed -n 's/^# date: //p' "$src")
    sed -e "s/^# trained_wall_s: .*/# trained_wall_s: $w/" -e "s/^# trained_date: .*/# trained_date: $d/" \
        frozen/extension-pair/main/run_s01_joint.tsv > "$tmp/b/run_s01_joint.tsv"
    if trained_check "$tmp" >/dev/null; then bad "a re-evaluation carrying a re-evaluation's wall time fails" "the check passed it"
    else ok "a re-evaluation carrying a re-evaluation's wall time fails"; fi
else
    bad "a re-evaluation carrying a re-evaluation's wall time fails" "$src missing"
fi

# the reader: a training unit frozen as a re-evaluation, and a re-evaluation unit
out=$(printf '%s\n' extension-pair-16-stands/main/run_s01_joint.tsv extension-pair/main/run_s01_joint.tsv | unit_walls frozen)
tw=$(sed -n 's/^# trained_wall_s: //p' frozen/extension-pair-16-stands/main/run_s01_joint.tsv)
ew=$(sed -n 's/^# wall_s: //p' frozen/extension-pair/main/run_s01_joint.tsv)
exp=$(printf '%s\t%s\t%s\t%s\n%s\t%s\t%s\t%s' extension-pair-16-stands/main/run_s01_joint.tsv "$tw" \
      "$(sed -n 's/^# wall_s: //p' frozen/extension-pair-16-stands/main/run_s01_joint.tsv)" trained \
      extension-pair/main/run_s01_joint.tsv "$ew" "$ew" recorded)
if [ "$out" = "$exp" ]; then ok "unit_walls: a training unit at its trained_wall_s, a re-evaluation at its own wall_s"
else bad "unit_walls: a training unit at its trained_wall_s, a re-evaluation at its own wall_s" "got '$(tr '\t\n' ' |' <<<"$out")'"; fi

echo "[==========] walls tests run."
echo "[  PASSED  ] $pass test(s)."
[ "$fail" -eq 0 ] || { echo "[  FAILED  ] $fail test(s)."; exit 1; }
