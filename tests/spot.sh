#!/usr/bin/env bash
# What it catches: a spot check that does not redraw its slice bit for bit,
# picks another slice for the same seed, or misses a changed value in it.
# The spot check of tier 1 (src/audit/spot.h): `crownshy verify --seed N`
# redraws the slice seed N picks (one frozen generator unit, one spacing, one
# probe) from the unit's weights and finds it bit-identical; the same seed
# picks the same slice again (printed, so a reviewer can repeat it); and in a
# copy whose frozen samples differ in that slice by one value, the spot check
# fails naming the file and the row. Prints cmocka-style lines.
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
cli="$root/build/crownshy"
pass=0; fail=0
ok()  { echo "[       OK ] $1"; pass=$((pass + 1)); }
bad() { echo "[  FAILED  ] $1: $2"; fail=$((fail + 1)); }
tmp=$(mktemp -d "$root/build/spot-test.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT
seed=7

line() { grep -E "^  [A-Z]+ +spot check SEED=$seed " "$1"; }
(cd "$root" && "$cli" verify --seed $seed > "$tmp/a.out" 2>&1)
l1=$(line "$tmp/a.out")
if grep -q '^  PASS ' <<<"$l1" && grep -q 'rows redrawn from its weights, bit-identical' <<<"$l1"; then ok "SEED=$seed: the slice redrawn from its weights, bit-identical"
else bad "spot check passes" "$l1"; fi
# the same seed again, in this tree, beside the altered copy below
(cd "$root" && "$cli" verify --seed $seed > "$tmp/b.out" 2>&1) &
again=$!

# the slice it picked, altered by one value in a copy
file=$(sed -n 's/.* \(frozen\/[^ ]*samples_s[0-9]*_[a-z]*\.tsv\), spacing \([0-9.]*\), probe \([a-z]*\).*/\1/p' <<<"$l1")
sp=$(sed -n 's/.*, spacing \([0-9.]*\), probe.*/\1/p' <<<"$l1")
pr=$(sed -n 's/.*, probe \([a-z]*\) .*/\1/p' <<<"$l1")
if [ -z "$file" ] || [ -z "$sp" ] || [ -z "$pr" ]; then bad "slice named" "cannot read the slice from: $l1"
else
  mkdir -p "$tmp/copy/build"
  (cd "$root" && tar cf - README.md LICENSE CITATION.cff src gates frozen audit paper figures tests) | (cd "$tmp/copy" && tar xf -)
  awk -F'\t' -v sp="$sp" -v pr="$pr" 'BEGIN{OFS="\t"} !/^#/ && $1 == sp && $3 == pr && $4 == "generated" && !d {$5 = $5 + 0.001; d = 1} {print}' \
    "$root/$file" > "$tmp/copy/$file"
  if cmp -s "$root/$file" "$tmp/copy/$file"; then bad "slice altered" "the edit did not apply"
  else
    (cd "$tmp/copy" && "$cli" verify --seed $seed > "$tmp/c.out" 2>&1); rc=$?
    l3=$(line "$tmp/c.out")
    [ $rc -eq 1 ] && grep -q '^  FAIL ' <<<"$l3" && grep -qF "$file" <<<"$l3" && grep -q 'differs at slice row' <<<"$l3" \
      && ok "one value changed in the slice: the spot check fails naming $file" || bad "altered slice" "exit $rc: $l3"
  fi
fi
wait $again
l2=$(line "$tmp/b.out")
[ -n "$l1" ] && [ "$l1" = "$l2" ] && ok "the same seed picks the same slice" || bad "repeatable" "'$l1' vs '$l2'"
echo "[==========] $((pass + fail)) test(s) run."
echo "[  PASSED  ] $pass test(s)."
[ "$fail" -eq 0 ] || echo "[  FAILED  ] $fail test(s)."
[ "$fail" -eq 0 ]
