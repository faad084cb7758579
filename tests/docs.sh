#!/usr/bin/env bash
# The documentation pages through verify (design.md §9). What it catches: a
# measured number typed by hand into README.md or a reference page, a generated
# region edited by hand or gone stale, a marker naming no claim, an exemption
# comment, a broken link, or a design-constant row its source does not hold,
# any of which `crownshy verify` would let through; and a `crownshy numbers`
# that no longer repairs what it generates. Each case edits a copy of the
# package of its own and verify must exit 1 with a FAIL line naming the page
# and line (and the claim); the untouched copy passes. The package is copied
# once (build/docs-test/base); each case starts from a copy of it with frozen/
# hard-linked (own breaks the link before an edit in place), cases run
# TEST_JOBS at a time (default 2), and every case must report. Prints
# cmocka-style lines so tests/run.sh counts the cases.
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
cli="$root/build/crownshy"
work="$root/build/docs-test"
base="$work/base"
jobs=${TEST_JOBS:-2}
ok()  { echo "[       OK ] $1"; }
bad() { echo "[  FAILED  ] $1: $2"; }

# fresh: $scratch as a copy of the base, frozen/ hard-linked
fresh() {
  local e
  rm -rf "$scratch"; mkdir -p "$scratch"
  for e in "$base"/*; do case ${e##*/} in frozen) cp -al "$e" "$scratch/" ;; *) cp -a "$e" "$scratch/" ;; esac; done
  mkdir -p "$scratch/build"
}
# own FILE...: a private copy of a hard-linked file, before an edit in place
own() { local f; for f; do cp -p "$f" "$f.own" && mv "$f.own" "$f"; done; }
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

d_size() {
  local size
  size=$(wc -c < "$root/README.md")
  [ "$size" -le 8192 ] && ok "README.md is $size bytes (at most 8 KB)" || bad "README.md size" "$size bytes, over 8192"
}
# the harness itself: a harmless sentence through expect is reported undetected
d_harness() {
  fresh
  printf '\nA sentence that states nothing measured.\n' >> "$scratch/tests/README.md"
  local out; out=$(expect "harmless edit")
  if grep -q '^\[  FAILED  \] harmless edit: verify exit 0, expected 1$' <<<"$out"; then ok "the harness reports a harmless edit as undetected"
  else bad "the harness reports a harmless edit as undetected" "$out"; fi
}
d_untouched() {
  fresh
  local out rc
  out=$(run); rc=$?
  if [ $rc -eq 0 ] && grep -qE '^  PASS +docs ' <<<"$out"; then ok "the untouched copy passes, docs included"
  else bad "untouched copy" "verify exit $rc; $(grep -E '^  FAIL ' <<<"$out" | head -2 | cut -c1-200)"; fi
}

# a measured value typed by hand into the README, then into a reference page
d_typed_readme() {
  fresh
  local v n
  v=$(val PairMainJoint)
  printf '\nThe joint error is %s m.\n' "$v" >> "$scratch/README.md"
  n=$(wc -l < "$scratch/README.md")
  expect "a typed measured number in README.md fails naming it" "README.md:$n:" "'$v' typed by hand" "claim: PairMainJoint"
}
d_typed_audit() {
  fresh
  local v
  v=$(val PairMainRel)
  sed -i "3s/\$/ It improves by $v %./" "$scratch/audit/README.md"
  expect "a typed measured number in audit/README.md fails naming it" "audit/README.md:3:" "'$v' typed by hand" "claim: PairMainRel"
}
d_typed_ref() {
  fresh
  sed -i "5s/\$/ The paper reports 53.6 %./" "$scratch/src/README.md"
  expect "a typed reference-paper value in src/README.md fails naming it" "src/README.md:5:" "'53.6'" "the reference paper's value" "MainRelPaper"
}

# a generated region edited by hand; crownshy numbers repairs it
d_findings() {
  fresh
  local l out rc
  l=$(grep -n 'reproduced, ' "$scratch/README.md" | head -1 | cut -d: -f1)
  sed -i "${l}s/\*\*[0-9]* reproduced/**99 reproduced/" "$scratch/README.md"
  expect "an edited findings block fails naming its line" "README.md:$l differs from a fresh generation"
  (cd "$scratch" && "$cli" numbers >/dev/null 2>&1)
  out=$(run); rc=$?
  [ $rc -eq 0 ] && ok "crownshy numbers regenerates the findings block" || bad "numbers repairs the block" "verify exit $rc after crownshy numbers"
}
d_inline() {
  fresh
  local l
  l=$(grep -n '<!--MainGeomRatio-->' "$scratch/paper/results.md" | head -1 | cut -d: -f1)
  sed -i "${l}s/<!--MainGeomRatio-->[^<]*<!--\/-->/<!--MainGeomRatio-->9.99<!--\/-->/" "$scratch/paper/results.md"
  expect "a stale inline region fails naming page, line and claim" "paper/results.md:$l differs from a fresh generation" "claim: MainGeomRatio"
}

# a marker naming no claim, an exemption comment, a broken link
d_marker() {
  fresh
  echo 'x <!--NoSuchClaim-->1<!--/-->' >> "$scratch/tests/README.md"
  expect "a marker naming no claim fails" "tests/README.md:" "names no claim"
}
d_exemption() {
  fresh
  own "$scratch/frozen/README.md"
  echo '<!-- audit: nocheck -->' >> "$scratch/frozen/README.md"
  (cd "$scratch" && "$cli" hash-frozen >/dev/null 2>&1)
  expect "an exemption comment fails" "frozen/README.md:" "asks for an exemption"
}
d_link() {
  fresh
  rm "$scratch/tests/README.md"
  expect "a page linked from README.md that is missing fails" "README.md:" "link to 'tests/README.md'"
}

# design constants: a row of audit/doc_numbers.tsv (value, "code FILE" holding it)
# admits a number a measured value rounds to; a row its source does not hold fails
d_constant() {
  fresh
  local v n out rc
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
}

# the longest first, so that the lanes end together
cases="d_constant d_findings d_untouched d_typed_readme d_typed_audit d_typed_ref d_inline d_marker d_exemption d_link d_harness d_size"
echo "[==========] Running documentation tests"
rm -rf "$work"; mkdir -p "$base"
(cd "$root" && tar cf - README.md LICENSE CITATION.cff src gates frozen audit paper figures tests 2>/dev/null) | (cd "$base" && tar xf -)
for c in $cases; do
  while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do wait -n; done
  ( scratch="$work/$c"; "$c" > "$work/$c.out" 2>&1; rm -rf "$scratch" ) &
done
wait
# every case reports; the shared copy of frozen/ unchanged by the cases
for c in $cases; do
  if grep -qE '^\[ +(OK|FAILED) +\]' "$work/$c.out" 2>/dev/null; then cat "$work/$c.out"; else bad "case $c" "printed no result"; fi
done > "$work/all.out"
if diff -rq "$root/frozen" "$base/frozen" >/dev/null 2>&1; then ok "the shared copy of frozen/ is unchanged by the cases"
else bad "the shared copy of frozen/ is unchanged by the cases" "$(diff -rq "$root/frozen" "$base/frozen" 2>&1 | head -3)"; fi >> "$work/all.out"
cat "$work/all.out"
pass=$(grep -c '^\[       OK \]' "$work/all.out")
fail=$(grep -c '^\[  FAILED  \]' "$work/all.out")
rm -rf "$work"
echo "[==========] $((pass + fail)) test(s) run."
echo "[  PASSED  ] $pass test(s)."
[ "$fail" -eq 0 ] || echo "[  FAILED  ] $fail test(s)."
[ "$fail" -eq 0 ]
