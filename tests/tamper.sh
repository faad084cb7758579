#!/usr/bin/env bash
# Tamper tests (design.md §9): on a scratch copy of the
# repository, make one class of edit per case; each must make `crownshy verify`
# exit 1 with a FAIL line naming the culprit file and the claims it feeds.
# The untampered copy must exit 0 (a failing preregistered gate is a finding,
# NOTREP) and 1 with --strict when a gate fails. Prints cmocka-style summary
# lines so tests/run.sh counts the cases.
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
cli="$root/build/crownshy"
scratch="$root/build/tamper"
pass=0; fail=0
ok()   { echo "[       OK ] $1"; pass=$((pass + 1)); }
bad()  { echo "[  FAILED  ] $1: $2"; fail=$((fail + 1)); }

fresh() {
  rm -rf "$scratch"; mkdir -p "$scratch"
  (cd "$root" && tar cf - README.md LICENSE CITATION.cff src gates frozen audit paper figures tests 2>/dev/null) | (cd "$scratch" && tar xf -)
  mkdir -p "$scratch/build"
}

# expect NAME PATTERN...: verify in the scratch copy exits 1 and one FAIL line
# prints every pattern (the file and the claims); VERIFY_ARGS picks the tier
VERIFY_ARGS=--no-figures
expect() {
  local name=$1; shift
  local out rc lines d same=1
  # a case whose edit did not apply (a pattern that no longer matches) tests nothing
  for d in README.md LICENSE CITATION.cff src gates frozen audit paper figures tests; do
    if ! diff -rq "$root/$d" "$scratch/$d" >/dev/null 2>&1; then same=0; break; fi
  done
  if [ $same = 1 ]; then bad "$name" "the tamper edit did not apply: the scratch copy equals the repository"; return; fi
  out=$(cd "$scratch" && "$cli" verify $VERIFY_ARGS 2>&1); rc=$?
  if [ $rc -ne 1 ]; then bad "$name" "verify exit $rc, expected 1"; return; fi
  lines=$(grep -E '^  FAIL ' <<<"$out")
  for p in "$@"; do lines=$(grep -F -- "$p" <<<"$lines"); done
  if [ -z "$lines" ]; then bad "$name" "no FAIL line naming all of: $*"; grep -E '^  FAIL ' <<<"$out" | head -3 | cut -c1-300; return; fi
  ok "$name"
}
reseal() { (cd "$scratch" && "$cli" hash-frozen >/dev/null 2>&1); }

echo "[==========] Running tamper tests"
fresh
out=$(cd "$scratch" && "$cli" verify 2>&1); rc=$?
# A failing preregistered gate is a finding (NOTREP), not an inconsistency: exit 0.
if [ $rc -eq 0 ] && ! grep -qE '^  FAIL ' <<<"$out" && grep -q '^package: consistent' <<<"$out"; then ok "untampered copy verifies (exit 0, figures byte-identical)"
else bad "untampered copy verifies" "exit $rc: $(grep -E '^  FAIL ' <<<"$out" | head -3)"; fi
if grep -q '^  NOTREP ' <<<"$out"; then
  (cd "$scratch" && "$cli" verify --strict --no-figures >/dev/null 2>&1); rc=$?
  if [ $rc -eq 1 ]; then ok "--strict fails on a failing gate"; else bad "--strict fails on a failing gate" "exit $rc"; fi
fi

# numbers --check compares paper/numbers.tex with a fresh generation only
out=$(cd "$scratch" && "$cli" numbers --check 2>&1); rc=$?
if [ $rc -eq 0 ] && grep -q '^PASS ' <<<"$out"; then ok "numbers --check passes on the untampered copy"
else bad "numbers --check passes on the untampered copy" "exit $rc: $out"; fi

# 1. one gate threshold
fresh
sed -i 's/^seeds                           12/seeds                           11/' "$scratch/gates/main.gate"
expect "gate threshold" "gates/main.gate" "MainSeeds"

# 2. one line of the estimator source
fresh
if [ -f "$scratch/src/forest/estimator.c" ]; then
  printf '/* tampered */\n' >> "$scratch/src/forest/estimator.c"
  expect "estimator source" "src/forest/estimator.c" "claims affected"
else bad "estimator source" "src/forest/estimator.c missing"; fi

# 3. one macro value of numbers.tex
fresh
sed -i 's/^\\newcommand{\\MechRows}{16}/\\newcommand{\\MechRows}{17}/' "$scratch/paper/numbers.tex"
expect "numbers.tex macro" "paper/numbers.tex" "MechRows"
out=$(cd "$scratch" && "$cli" numbers --check 2>&1); rc=$?
if [ $rc -eq 1 ] && grep -q '^FAIL .*paper/numbers.tex:[0-9]* differs' <<<"$out"; then ok "numbers --check names the edited line"
else bad "numbers --check names the edited line" "exit $rc: $out"; fi

# 4. one frozen number (the first numeric data cell of the first hashed table)
# (named with the claims of the file, or "(no claim)" for a figure-only table)
fresh
f=$(awk '$2 ~ /[.]tsv$/ {print $2; exit}' "$scratch/audit/frozen.sha256" 2>/dev/null)
if [ -n "$f" ] && [ -f "$scratch/$f" ]; then
  # change the last digit of the first number in the first data row
  awk 'BEGIN{done=0} /^#/ || NR==hdr {print; next} { if (!seen) { seen=1; print; next } if (!done && match($0, /[0-9]/)) { n=split($0, a, "\t"); for (i=1;i<=n;i++) if (!done && a[i] ~ /^-?[0-9.]+(e-?[0-9]+)?$/) { c=substr(a[i], length(a[i]), 1); a[i]=substr(a[i],1,length(a[i])-1) ((c=="9")?"8":(c+1)); done=1 } s=a[1]; for(i=2;i<=n;i++) s=s "\t" a[i]; print s; next } print }' "$scratch/$f" > "$scratch/$f.new" && mv "$scratch/$f.new" "$scratch/$f"
  expect "frozen number" "$f"
else
  echo "[  SKIPPED ] frozen number: nothing frozen yet"
fi
# 5. the record of a superseded reading: without it, tables that reading made fail
# A table whose provenance names another teacher source (its hashes resealed)
# fails; recorded as a superseded reading in audit/pins_superseded.tsv, it is
# reported pending with its folder and claims, and verify stays consistent.
fresh
f=frozen/mechanism/figure_stats.tsv
fake=00000000000000000000000000000000000000000000000000000000000000ab
sed -i "s/^# teacher_sha256: .*/# teacher_sha256: $fake/" "$scratch/$f"
(cd "$scratch" && "$cli" hash-frozen >/dev/null 2>&1)
expect "superseded reading unrecorded" "$f" "does not match the current pin"
printf 'teacher_sha256\t%s\tsrc/forest/teacher.c\ttamper-test\n' "$fake" >> "$scratch/audit/pins_superseded.tsv"
(cd "$scratch" && "$cli" pin >/dev/null 2>&1) # the record is pinned: a deliberate act (no .git here to show the hash is real)
(cd "$scratch" && "$cli" numbers >/dev/null 2>&1) # its claims now pending: the generated README findings say so
out=$(cd "$scratch" && "$cli" verify --no-figures 2>&1); rc=$?
if [ $rc -eq 0 ] && grep -q 'PENDING .*frozen/mechanism/: 1 tables made by a superseded reading.*MechOn' <<<"$out"; then ok "superseded reading recorded: pending, named"
else bad "superseded reading recorded: pending, named" "exit $rc: $(grep -E 'provenance|FAIL' <<<"$out" | head -3)"; fi

# ---- every editable input of a number or a picture ----
# 6. the registry's gate column (and numbers.tex regenerated): the pinned map decides
fresh
awk -F'\t' 'BEGIN{OFS="\t"} $1=="MainGeomRatio"{$5="-"} {print}' "$scratch/audit/claims.tsv" > "$scratch/x" && mv "$scratch/x" "$scratch/audit/claims.tsv"
(cd "$scratch" && "$cli" numbers >/dev/null 2>&1)
expect "registry gate column" "audit/claims.tsv" "MainGeomRatio"
# 7. the claim-to-gate map itself: dropping a verdict changes a pinned file
fresh
grep -v '^MainGeomRatio' "$scratch/audit/gate_map.tsv" > "$scratch/x" && mv "$scratch/x" "$scratch/audit/gate_map.tsv"
(cd "$scratch" && "$cli" numbers >/dev/null 2>&1)
expect "gate map" "audit/gate_map.tsv" "MainGeomRatio"
# 8. the claim-computing code
fresh
printf '/* tampered */\n' >> "$scratch/src/claims/claim_main.c"
expect "claim code" "src/claims/claim_main.c" "MainRel"
# 9. comparison.tex, not a fresh generation
fresh
sed -i 's/^\(\\texttt{MainRel} & [^&]*& [^&]*& \)[^&]*&/\1 99.9 \&/' "$scratch/paper/comparison.tex"
expect "comparison.tex" "paper/comparison.tex" "MainRel"
# 10. a committed PNG (figures redrawn into build/ and byte-compared)
VERIFY_ARGS=
fresh
printf 'x' >> "$scratch/figures/main.png"
before=$(sha256sum < "$scratch/figures/main.png")
expect "committed PNG" "figures/main.png" "MainRel"
if [ "$(sha256sum < "$scratch/figures/main.png")" = "$before" ]; then ok "verify never overwrites a committed figure"
else bad "verify never overwrites a committed figure" "figures/main.png changed"; fi
# 11. a figure script
fresh
sed -i 's/font "DejaVu Sans,11"/font "DejaVu Sans,12"/' "$scratch/figures/field.gp"
expect "figure script" "figures/field.png" "Elong"
VERIFY_ARGS=--no-figures
# 12. a measured number typed in another rounding than numbers.tex's
fresh
v=$(cd "$scratch" && "$cli" trace MechOn | sed -n 's/.*(k1_m) = \([0-9.]*\);.*/\1/p' | head -1)
printf '\nThe clearance was %s~m.\n' "$v" >> "$scratch/paper/main.tex"
expect "number typed in another rounding ($v)" "paper/main.tex" "MechOn"
# 13. a claim macro redefined in the text
fresh
sed -i 's/^\\input{numbers.tex}$/\\input{numbers.tex}\n\\renewcommand{\\MainGeomRatioGate}{PASS}/' "$scratch/paper/main.tex"
expect "claim macro redefined" "paper/main.tex" "MainGeomRatio"
# 14. a self-exemption comment (not honoured)
fresh
sed -i "1i % GENERATED: audit exempt" "$scratch/paper/main.tex"
printf '\nThe clearance was %s~m.\n' "$v" >> "$scratch/paper/main.tex"
expect "self-exemption comment" "paper/main.tex" "exemption"
expect "self-exemption not honoured" "paper/main.tex" "MechOn"
# 15. a paper subfolder
fresh
mkdir -p "$scratch/paper/sections"
printf 'The clearance was %s~m.\n' "$v" > "$scratch/paper/sections/extra.tex"
expect "paper subfolder" "paper/sections/extra.tex" "MechOn"
# 16. a failing experiment's frozen files deleted and re-sealed: a failure, never PENDING
fresh
rm -f "$scratch"/frozen/extension-pair-16-stands/main/*.tsv
reseal
expect "failing experiment deleted and resealed" "frozen/extension-pair-16-stands/main/runs.tsv" "MainGeomRatio"
# 17. an aggregate against its per-run tables (one per-run number changed, resealed)
fresh
awk -F'\t' 'BEGIN{OFS="\t"} !/^#/ && $4=="unseen" && $5=="generated" && !d {$6=$6+0.001; d=1} {print}' "$scratch/frozen/extension-pair-16-stands/main/run_s01_joint.tsv" > "$scratch/x" && mv "$scratch/x" "$scratch/frozen/extension-pair-16-stands/main/run_s01_joint.tsv"
reseal
expect "aggregate vs per-run" "frozen/extension-pair-16-stands/main/run_s01_joint.tsv" "MainRel"
# 18. provenance stripped (resealed)
fresh
grep -v '^#' "$scratch/frozen/mechanism/sweep.tsv" > "$scratch/x" && mv "$scratch/x" "$scratch/frozen/mechanism/sweep.tsv"
reseal
expect "provenance stripped" "frozen/mechanism/sweep.tsv" "MechHits"
# 19. a *.tmp* file and a dotfile in frozen/: never invisible
fresh
cp "$scratch/frozen/extension-pair-16-stands/main/runs.tsv" "$scratch/frozen/extension-pair-16-stands/main/runs.tsv.tmp.99.1"
expect "*.tmp file in frozen/" "frozen/extension-pair-16-stands/main/runs.tsv.tmp.99.1" "MainRel"
if (cd "$scratch" && "$cli" hash-frozen >/dev/null 2>&1); then bad "hash-frozen refuses a *.tmp file" "exit 0"; else ok "hash-frozen refuses a *.tmp file"; fi
fresh
cp "$scratch/frozen/field/heldout.tsv" "$scratch/frozen/field/.heldout.tsv"
expect "dotfile in frozen/" "frozen/field/.heldout.tsv" "Elong"
# 20. per-tree tables name the claims they feed (through their aggregate)
fresh
sed -i '$ d' "$scratch/frozen/field/heldout_trees.tsv"
expect "per-tree table" "frozen/field/heldout_trees.tsv" "Elong"

# ---- what a number rests on (design.md §9) ----
# fresh_git: the scratch copy as a git clone of this repository's history
# (sharing its objects) with the working tree's files laid over it
fresh_git() {
  rm -rf "$scratch"
  git clone -q --shared "$root" "$scratch" 2>/dev/null || return 1
  (cd "$root" && tar cf - src gates frozen audit paper figures tests 2>/dev/null) | (cd "$scratch" && tar xf -)
  mkdir -p "$scratch/build"
  (cd "$scratch" && git add -A >/dev/null 2>&1 && git -c user.name=t -c user.email=t@t commit -qm "working tree" >/dev/null 2>&1)
  return 0
}
# the dishonest author's whole chain after an edit: re-pin, rewrite the gates
# hash in every frozen provenance, reseal, regenerate the paper files
launder() {
  (cd "$scratch" && "$cli" pin >/dev/null 2>&1)
  local g; g=$(awk -F'\t' '$1=="gates_sha256"{print $2}' "$scratch/audit/pins.tsv")
  find "$scratch/frozen" -name '*.tsv' -exec sed -i "s/^# gates_sha256: .*/# gates_sha256: $g/" {} +
  reseal; (cd "$scratch" && "$cli" numbers >/dev/null 2>&1)
}
have_git=0; git -C "$root" rev-parse --git-dir >/dev/null 2>&1 && have_git=1
# 21. a preregistered threshold changed, laundered: no .git (the pinned copy of
# the gates' hashes), then with .git (the preregistration commit) even with
# the pinned copy rewritten and everything committed
fresh
sed -i 's/^rel_improvement_min             0.20/rel_improvement_min             0.10/' "$scratch/gates/main.gate"
launder
expect "gate changed, laundered (no .git)" "gates/main.gate" "differs from its pinned preregistered hash" "MainRel"
if [ $have_git = 1 ] && fresh_git; then
  sed -i 's/^rel_improvement_min             0.20/rel_improvement_min             0.10/' "$scratch/gates/main.gate"
  h=$(sha256sum < "$scratch/gates/main.gate" | cut -d' ' -f1)
  sed -i "s|^[0-9a-f]*  gates/main.gate|$h  gates/main.gate|" "$scratch/audit/gates_prereg.sha256"
  launder
  (cd "$scratch" && git add -A && git -c user.name=t -c user.email=t@t commit -qm "threshold" >/dev/null 2>&1)
  expect "gate changed, laundered and committed (.git)" "gates/main.gate" "preregistration commit" "MainRel"
else echo "[  SKIPPED ] gate changed (.git): no git history here"; fi
# 21b. unit identities: a seed's joint and independent units swapped, and a
# seed copied as another, each resealed
fresh
d="$scratch/frozen/paper-reading/main"
for f in run samples weights; do
  e=tsv; [ $f = weights ] && e=ckpt
  mv "$d/${f}_s03_joint.$e" "$d/x"; mv "$d/${f}_s03_indep.$e" "$d/${f}_s03_joint.$e"; mv "$d/x" "$d/${f}_s03_indep.$e"
done
reseal
expect "joint and independent units swapped" "unit identities" "run_s03_indep.tsv" "MainRel"
fresh
d="$scratch/frozen/paper-reading/main"
for f in run samples weights; do e=tsv; [ $f = weights ] && e=ckpt; cp "$d/${f}_s04_joint.$e" "$d/${f}_s05_joint.$e"; done
reseal
expect "seed 4 copied as seed 5" "unit identities" "run_s05_joint.tsv" "seed"
# 22. the evidence of E3/E4, each edit resealed
fresh
printf '\x01' | dd of="$scratch/frozen/extension-pair-16-stands/main/weights_s01_joint.ckpt" bs=1 seek=200 conv=notrunc status=none
reseal
expect "weights byte" "frozen/extension-pair-16-stands/main/weights_s01_joint.ckpt" "MainRel"
fresh
f="$scratch/frozen/extension-pair-16-stands/main/samples_s01_joint.tsv"
awk -F'\t' 'BEGIN{OFS="\t"} !/^#/ && $4=="generated" && !d && $5+0==$5 {$5=$5+0.25; d=1} {print}' "$f" > "$scratch/x" && mv "$scratch/x" "$f"
h=$(sha256sum < "$f" | cut -d' ' -f1)
sed -i "s/^# samples: samples_s01_joint.tsv sha256 [0-9a-f]*/# samples: samples_s01_joint.tsv sha256 $h/" "$scratch/frozen/extension-pair-16-stands/main/run_s01_joint.tsv"
reseal
expect "samples value (provenance hash rewritten too)" "W1 from samples" "run_s01_joint.tsv" "MainRel"
fresh
awk '!/^#/ && n++==1 {print} {print}' "$scratch/frozen/extension-pair-16-stands/main/run_s02_joint.tsv" > "$scratch/x" && mv "$scratch/x" "$scratch/frozen/extension-pair-16-stands/main/run_s02_joint.tsv"
reseal
expect "extra run-table row" "frozen/extension-pair-16-stands/main/run_s02_joint.tsv" "repeats the grid point" "MainRel"
fresh
rm -f "$scratch/frozen/extension-pair-16-stands/main/weights_s03_indep.ckpt" "$scratch/frozen/extension-pair-16-stands/main/samples_s03_indep.tsv"
reseal
expect "weights and samples deleted together" "frozen/extension-pair-16-stands/main/weights_s03_indep.ckpt" "missing" "MainRel"
# a whole unit of a complete reading deleted and the rest resealed: its frozen
# summary (an aggregate of the units) names it; with the summary deleted too,
# the design grid of the summary fails; never pending
fresh
rm -f "$scratch"/frozen/paper-reading/main/{run,samples,weights}_s05_joint.*
reseal
expect "a complete reading's unit deleted (resealed)" "frozen/paper-reading/main/runs.tsv" "run_s05_joint.tsv" "MainRel"
rm -f "$scratch/frozen/paper-reading/main/runs.tsv"
reseal
expect "a complete reading's unit and summary deleted (resealed)" "frozen/paper-reading/main/runs.tsv" "design grids"
# a summary table recomputed by verify, one cell changed and resealed: the
# readings table (paper/readings.tex) and the generator readings table
fresh
awk -F'\t' 'BEGIN{OFS="\t"} !/^#/ && $1 != "quantity" && !done {$4 = $4 + 0.25; done = 1} {print}' "$scratch/frozen/readings/summary.tsv" > "$scratch/x" && mv "$scratch/x" "$scratch/frozen/readings/summary.tsv"
reseal
expect "readings summary cell (resealed)" "frozen/readings/summary.tsv"
fresh
awk -F'\t' 'BEGIN{OFS="\t"} !/^#/ && $1 == "plain" {$7 = $7 + 0.01} {print}' "$scratch/frozen/model-readings/summary.tsv" > "$scratch/x" && mv "$scratch/x" "$scratch/frozen/model-readings/summary.tsv"
reseal
expect "generator readings table cell (resealed)" "frozen/model-readings/summary.tsv" "field 'joint'" "reading plain"
# 23. a table's rows against its design grid: a duplicated sweep row
fresh
awk '!/^#/ && n++==3 {print} {print}' "$scratch/frozen/mechanism/sweep.tsv" > "$scratch/x" && mv "$scratch/x" "$scratch/frozen/mechanism/sweep.tsv"
reseal
expect "duplicated sweep row (17 of a 4 x 4 design)" "frozen/mechanism/sweep.tsv" "repeats the grid point" "MechHits"
# 24. superseded pins: the record is pinned; a made-up superseded teacher hash
# is no past version (.git); a table of a superseded reading never counts as reproduced
fake=00000000000000000000000000000000000000000000000000000000000000cd
fresh
printf 'teacher_sha256\t%s\tsrc/forest/teacher.c\ttamper-test\n' "$fake" >> "$scratch/audit/pins_superseded.tsv"
expect "superseded record edited, not re-pinned" "audit/pins_superseded.tsv" "superseded reading"
if [ $have_git = 1 ] && fresh_git; then
  printf 'teacher_sha256\t%s\tsrc/forest/teacher.c\ttamper-test\n' "$fake" >> "$scratch/audit/pins_superseded.tsv"
  find "$scratch/frozen/extension-pair-16-stands/main" -name '*.tsv' -exec sed -i "s/^# teacher_sha256: .*/# teacher_sha256: $fake/" {} +
  launder
  expect "made-up superseded hash in frozen/extension-pair-16-stands/main, re-pinned (.git)" "audit/pins_superseded.tsv" "no past version of src/forest/teacher.c"
  out=$(cd "$scratch" && "$cli" verify --no-figures 2>&1)
  if grep -q '^  PENDING PairSixteenStandsMainRel .*superseded reading' <<<"$out" && ! grep -q '^  PASS    PairSixteenStandsMainRel ' <<<"$out"; then ok "claims of a superseded table are pending, never reproduced"
  else bad "claims of a superseded table are pending, never reproduced" "$(grep -E '^  [A-Z]+ +PairSixteenStandsMainRel ' <<<"$out" | head -2)"; fi
else echo "[  SKIPPED ] made-up superseded hash (.git): no git history here"; fi
# 24b. a pin row deleted: every part of the instrument the code pins must be
# pinned (the last rows too: the set of pins grows with the registry)
fresh
grep -v '^claim_test_sha256.*tests/tamper.sh$' "$scratch/audit/pins.tsv" > "$scratch/x" && mv "$scratch/x" "$scratch/audit/pins.tsv"
expect "last pin row deleted" "tests/tamper.sh is not pinned"
# 25. a design constant (no gate carries it)
fresh
sed -i 's/^#define DESIGN_FIELD_SPACING_M 4.0/#define DESIGN_FIELD_SPACING_M 5.0/' "$scratch/src/base/design.h"
expect "design constant" "src/base/design.h" "design constants"
# 26. the paper read as TeX reads it
fresh
sed -i 's/^\\input{numbers.tex}$/\\input{numbers.tex}\n\\expandafter\\def\\csname MainRelGate\\endcsname{PASS}/' "$scratch/paper/main.tex"
expect "\\expandafter\\def\\csname" "paper/main.tex" "MainRel"
fresh
sed -i 's/^\\input{numbers.tex}$/\\input{numbers.tex}\n\\renewcommand\n  {\\MainPGate}{PASS}/' "$scratch/paper/main.tex"
expect "definer split over two lines" "paper/main.tex" "MainP"
fresh
printf '\\def\\MechHits{13}\n' > "$scratch/paper/local.sty"
sed -i 's/^\\input{numbers.tex}$/\\input{numbers.tex}\n\\usepackage{local}/' "$scratch/paper/main.tex"
expect "a local .sty pulled in" "paper/local.sty" "MechHits"
fresh
printf 'Of the sweep, 14 of 16 rows pass.\n' > "$scratch/paper/extra.txt"
sed -i 's/^\\input{summary.tex}$/\\input{summary.tex}\n\\input{extra.txt}/' "$scratch/paper/main.tex"
expect "an \\input file not *.tex, a wrong typed integer" "paper/extra.txt:1" "'14'"
fresh
printf '\nThe median clearance was 0.37~m.\n' >> "$scratch/paper/main.tex"
expect "a typed decimal that rounds no measured value" "paper/main.tex" "'0.37'"
fresh
printf '\nThe learning gate: \\verdict{PASS}.\n' >> "$scratch/paper/main.tex"
expect "a literal \\verdict{PASS}" "paper/main.tex" "verdict{PASS}"
# 26b. the paper as TeX renders it, every generated value hidden: what TeX
# prints from means the static reading does not follow
fresh
sed -i 's/^\\end{document}$/The shuffle gate: \\uppercase{pass}.\n\\end{document}/' "$scratch/paper/main.tex"
expect "a verdict typed as \\uppercase{pass}" "paper render" "'PASS'"
fresh
sed -i 's/^\\end{document}$/The shuffle gate: P{}ASS.\n\\end{document}/' "$scratch/paper/main.tex"
expect "a verdict typed as P{}ASS" "paper render" "'PASS'"
fresh
sed -i 's/^\\end{document}$/Of the sweep, \\relax13 rows meet the gate.\n\\end{document}/' "$scratch/paper/main.tex"
expect "digits after a control word" "paper render" "'13'"
fresh
printf 'Of the sweep, 14 of 16 rows meet the gate.\n' > "$scratch/paper/extra.txt"
sed -i 's/^\\end{document}$/\\input extra.txt\n\\end{document}/' "$scratch/paper/main.tex"
expect "a braceless \\input of a file not *.tex" "paper render" "'14'"
fresh
sed -i 's/^\\end{document}$/The run ended in \\the\\year.\n\\end{document}/' "$scratch/paper/main.tex"
expect "a number TeX computes" "paper render" "paper/main.tex"
fresh
sed -i 's/^\\end{document}$/\\let\\mydef=\\def \\mydef\\MainRel{45.0}The improvement: \\MainRel\\%.\n\\end{document}/' "$scratch/paper/main.tex"
expect "a claim redefined through an alias of \\def" "paper render" "45.0"
# 27. the claim tests are pinned: one that returns early
fresh
sed -i 's/^    const claim_row \*row = \*state;$/    const claim_row *row = *state;\n    if (row) return;/' "$scratch/tests/test_claims.c"
expect "claim test returns early" "tests/test_claims.c" "every claim whose test"
# 28. regular files only in frozen/: a symlink (to a file, to a folder)
fresh
ln -s runs.tsv "$scratch/frozen/extension-pair-16-stands/main/runs_link.tsv"
expect "symlink in frozen/" "frozen/extension-pair-16-stands/main/runs_link.tsv" "non-regular"
if (cd "$scratch" && "$cli" hash-frozen >/dev/null 2>&1); then bad "hash-frozen refuses a symlink" "exit 0"; else ok "hash-frozen refuses a symlink"; fi
fresh
ln -s ../../mechanism "$scratch/frozen/extension-pair-16-stands/main/mech"
expect "symlinked folder in frozen/" "frozen/extension-pair-16-stands/main/mech" "non-regular"
rm -rf "$scratch"
echo "[==========] tamper tests run."
echo "[  PASSED  ] $pass test(s)."
[ $fail -eq 0 ] || echo "[  FAILED  ] $fail test(s)."
[ $fail -eq 0 ]
