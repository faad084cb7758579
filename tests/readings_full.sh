#!/usr/bin/env bash
# What it catches: a reading whose full set of seeds would leave a gated
# claim unjudged, make the package inconsistent or mix the pair extension into
# the reference paper's tally; and pending claims that stop naming their
# missing units.
# The paper reading's verdict with its full set of seeds (design.md §8 "Which
# claims read which reading"): in a scratch copy of the package, the units of
# frozen/paper-reading/main/ still missing are fabricated from seed 1's tables
# (seed column set, every W1 scaled by 1 + s/1000: a test fixture, never
# frozen), the copy re-sealed and its paper files regenerated. verify must then
# judge every E3/E4 gated claim of the paper reading (none pending), stay
# consistent, and tally the pair extension apart; the untouched copy keeps them
# pending with the missing units named. Prints cmocka-style lines for tests/run.sh.
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
cli="$root/build/crownshy"
scratch="$root/build/readings-full-test"
pass=0; fail=0
ok()  { echo "[       OK ] $1"; pass=$((pass + 1)); }
bad() { echo "[  FAILED  ] $1: $2"; fail=$((fail + 1)); }
echo "[==========] Running the paper reading with a fabricated full set"
rm -rf "$scratch"; mkdir -p "$scratch/build"
(cd "$root" && tar cf - README.md LICENSE CITATION.cff src gates frozen audit paper figures tests 2>/dev/null) | (cd "$scratch" && tar xf -)
d="$scratch/frozen/paper-reading/main"
gated='^  [A-Z]+ +(Main(Rel|P|GeomRatio|Iso)|Extrap(LowRel|HighRel|P)) '
out=$(cd "$scratch" && "$cli" verify --no-figures 2>&1); rc=$?
missing=0
for s in $(seq -w 2 12); do for a in joint indep; do [ -f "$d/run_s${s}_$a.tsv" ] || missing=$((missing + 1)); done; done
if [ $missing -eq 0 ]; then echo "[  SKIPPED ] the frozen paper reading is complete: nothing pending to check"
elif [ $rc -eq 0 ] && grep -E "$gated" <<<"$out" | grep -q PENDING && grep -q "units not yet frozen\|seeds frozen (both arms)" <<<"$out"; then ok "as frozen: the paper reading's gated claims pending, the missing units named"
else bad "as frozen" "verify exit $rc; $(grep -E "$gated" <<<"$out" | head -2 | cut -c1-200)"; fi
for s in $(seq -w 2 12); do
  for a in joint indep; do
    f="$d/run_s${s}_$a.tsv"
    [ -f "$f" ] && continue
    awk -F'\t' -v s=$((10#$s)) 'BEGIN{OFS="\t"} /^#/ || $1=="seed" {print; next} {$1=s; $6=$6*(1+0.001*s); print}' "$d/run_s01_$a.tsv" > "$f"
  done
done
(cd "$scratch" && "$cli" hash-frozen >/dev/null && "$cli" numbers >/dev/null) || bad "re-seal and regenerate" "crownshy hash-frozen/numbers failed"
out=$(cd "$scratch" && "$cli" verify --no-figures 2>&1); rc=$?
[ $rc -eq 0 ] && ok "full set: the package stays consistent" || bad "full set: consistent" "verify exit $rc: $(grep -E '^  FAIL ' <<<"$out" | head -2 | cut -c1-200)"
n=$(grep -E "$gated" <<<"$out" | grep -cE '^  (PASS|NOTREP) ')
[ "$n" -eq 7 ] && ok "full set: all 7 gated E3/E4 claims of the paper reading judged" || bad "full set: judged" "$n of 7; $(grep -E "$gated" <<<"$out" | grep -v -E '^  (PASS|NOTREP) ' | head -2 | cut -c1-200)"
grep -qE '^  PASS +MainFrozenSeeds +12 ' <<<"$out" && ok "full set: the seeds-so-far row counts 12" || bad "full set: seeds so far" "$(grep MainFrozenSeeds <<<"$out" | cut -c1-160)"
grep -q '^extension claims .*: 7 meet' <<<"$out" && ok "full set: the pair extension tallied apart" || bad "full set: extension tally" "$(grep '^extension claims' <<<"$out" | cut -c1-200)"
rm -rf "$scratch"
echo "[==========] $((pass + fail)) test(s) run."
echo "[  PASSED  ] $pass test(s)."
[ "$fail" -eq 0 ] || echo "[  FAILED  ] $fail test(s)."
[ "$fail" -eq 0 ]
