#!/usr/bin/env bash
# The documentation pages through verify (design.md §9): in a scratch copy of the
# package, each case makes one edit to README.md or a reference page; `crownshy
# verify` must exit 1 with a FAIL line naming the page and line (and the
# claim), and `crownshy numbers` must repair what it generates. The untouched
# copy passes. Prints cmocka-style lines so tests/run.sh counts the cases.
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
cli="$root/build/crownshy"
scratch="$root/build/docs-test"
pass=0; fail=0
ok()  { echo "[       OK ] $1"; pass=$((pass + 1)); }
bad() { echo "[  FAILED  ] $1: $2"; fail=$((fail + 1)); }

fresh() {
  rm -rf "$scratch"; mkdir -p "$scratch"
  (cd "$root" && tar cf - README.md LICENSE CITATION.cff src gates frozen audit paper figures tests 2>/dev/null) | (cd "$scratch" && tar xf -)
  mkdir -p "$scratch/build"
}
run() { (cd "$scratch" && "$cli" verify --no-figures 2>&1); }
# expect NAME PATTERN...: verify exits 1 and one FAIL line holds every pattern
expect() {
  local name=$1; shift
  local out rc lines
  out=$(run); rc=$?
  if [ $rc -ne 1 ]; then bad "$name" "verify exit $rc, expected 1"; return; fi
  lines=$(grep -E '^  FAIL ' <<<"$out")
  for p in "$@"; do lines=$(grep -F -- "$p" <<<"$lines"); done
  if [ -z "$lines" ]; then bad "$name" "no FAIL line naming all of: $*"; grep -E '^  FAIL ' <<<"$out" | head -3 | cut -c1-300; return; fi
  ok "$name"
}
# value of a claim in numbers.tex
val() { sed -n "s/^\\\\newcommand{\\\\$1}{\\(.*\\)}\$/\\1/p" "$root/paper/numbers.tex"; }

echo "[==========] Running documentation tests"
size=$(wc -c < "$root/README.md")
[ "$size" -le 8192 ] && ok "README.md is $size bytes (at most 8 KB)" || bad "README.md size" "$size bytes, over 8192"
fresh
out=$(run); rc=$?
if [ $rc -eq 0 ] && grep -qE '^  PASS +docs ' <<<"$out"; then ok "the untouched copy passes, docs included"
else bad "untouched copy" "verify exit $rc; $(grep -E '^  FAIL ' <<<"$out" | head -2 | cut -c1-200)"; fi

# a measured value typed by hand into the README, then into a reference page
v=$(val PairMainJoint)
printf '\nThe joint error is %s m.\n' "$v" >> "$scratch/README.md"
n=$(wc -l < "$scratch/README.md")
expect "a typed measured number in README.md fails naming it" "README.md:$n:" "'$v' typed by hand" "claim: PairMainJoint"
fresh
v=$(val PairMainRel)
sed -i "3s/\$/ It improves by $v %./" "$scratch/audit/README.md"
expect "a typed measured number in audit/README.md fails naming it" "audit/README.md:3:" "'$v' typed by hand" "claim: PairMainRel"
fresh
sed -i "5s/\$/ The paper reports 53.6 %./" "$scratch/src/README.md"
expect "a typed reference-paper value in src/README.md fails naming it" "src/README.md:5:" "'53.6'" "the reference paper's value" "MainRelPaper"

# a generated region edited by hand; crownshy numbers repairs it
fresh
l=$(grep -n 'reproduced, ' "$scratch/README.md" | head -1 | cut -d: -f1)
sed -i "${l}s/\*\*[0-9]* reproduced/**99 reproduced/" "$scratch/README.md"
expect "an edited findings block fails naming its line" "README.md:$l differs from a fresh generation"
(cd "$scratch" && "$cli" numbers >/dev/null 2>&1)
out=$(run); rc=$?
[ $rc -eq 0 ] && ok "crownshy numbers regenerates the findings block" || bad "numbers repairs the block" "verify exit $rc after crownshy numbers"
fresh
l=$(grep -n '<!--MainGeomRatio-->' "$scratch/paper/results.md" | head -1 | cut -d: -f1)
sed -i "${l}s/<!--MainGeomRatio-->[^<]*<!--\/-->/<!--MainGeomRatio-->9.99<!--\/-->/" "$scratch/paper/results.md"
expect "a stale inline region fails naming page, line and claim" "paper/results.md:$l differs from a fresh generation" "claim: MainGeomRatio"

# a marker naming no claim, an exemption comment, a broken link
fresh
echo 'x <!--NoSuchClaim-->1<!--/-->' >> "$scratch/tests/README.md"
expect "a marker naming no claim fails" "tests/README.md:" "names no claim"
fresh
echo '<!-- audit: nocheck -->' >> "$scratch/frozen/README.md"
(cd "$scratch" && "$cli" hash-frozen >/dev/null 2>&1)
expect "an exemption comment fails" "frozen/README.md:" "asks for an exemption"
fresh
rm "$scratch/tests/README.md"
expect "a page linked from README.md that is missing fails" "README.md:" "link to 'tests/README.md'"

# design constants: a row of audit/doc_numbers.tsv (value, "code FILE" holding it)
# admits a number a measured value rounds to; a row its source does not hold fails
fresh
v=$(val PairMainJoint)
printf '\nA constant that happens to equal a measured value: %s.\n' "$v" >> "$scratch/src/README.md"
n=$(wc -l < "$scratch/src/README.md")
expect "a constant equal to a measured value, with no row, fails" "src/README.md:$n:" "'$v' typed by hand"
printf '#define SOME_CONSTANT %s\n' "$v" > "$scratch/build/const.h"
printf '%s\tcode build/const.h\ta constant of the test\n' "$v" >> "$scratch/audit/doc_numbers.tsv"
out=$(run); rc=$?
[ $rc -eq 0 ] && ok "its row in audit/doc_numbers.tsv, held by its source, admits it" || bad "a row admits a constant" "verify exit $rc: $(grep -E '^  FAIL ' <<<"$out" | head -2 | cut -c1-200)"
printf '#define SOME_CONSTANT 1\n' > "$scratch/build/const.h"
expect "a row of audit/doc_numbers.tsv its source does not hold fails" "audit/doc_numbers.tsv:" "does not hold $v"

rm -rf "$scratch"
echo "[==========] $((pass + fail)) test(s) run."
echo "[  PASSED  ] $pass test(s)."
[ "$fail" -eq 0 ] || echo "[  FAILED  ] $fail test(s)."
[ "$fail" -eq 0 ]
