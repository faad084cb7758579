#!/usr/bin/env bash
# The second tier's own behaviour (src/exp/verify_deep.sh, design.md §9),
# without its two hours of work: the crownshy binary and make are replaced by
# stubs that copy the frozen table a unit or a redraw would write, and the
# stub's redraws finish out of the list's order (one arm sleeps). Checks that
# the results are printed in one fixed order (the design's list, whatever
# order the redraws finish in), that a second tier 2 over the leftovers of a
# first passes (a redrawn sample is never taken for a teacher table), and
# that a redraw differing from frozen/ still fails, naming the file.
# Prints cmocka-style lines so tests/run.sh counts the cases.
set -u
cd "$(dirname "$0")/.."
pass=0; fail=0
ok()  { echo "[       OK ] $1"; pass=$((pass + 1)); }
bad() { echo "[  FAILED  ] $1: $2"; fail=$((fail + 1)); }
tmp=$(mktemp -d "${TMPDIR:-/tmp}/crownshy-deep.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT
deep=$tmp/deep

# crownshy main-redraw: --cost prints a cost line; else the frozen samples
# its --out names are copied there, the arm $SLOW_ARM after a pause, and the
# seed $BAD_SEED's joint arm with one value changed
cat > "$tmp/cli" <<'EOF'
#!/usr/bin/env bash
out="" cost=0 arm="" seed=""
while [ $# -gt 0 ]; do
    case $1 in --out) out=$2; shift ;; --arm) arm=$2; shift ;; --seed) seed=$2; shift ;; --cost) cost=1 ;; esac
    shift
done
if [ $cost = 1 ]; then printf 'redraw_cost\tflops 1\tgflops 1\tcpu_s 1\n'; exit 0; fi
[ "$arm" = "${SLOW_ARM:-}" ] && sleep 0.05
cp "frozen/${out#"$DEEP"/model/}" "$out" || exit 3
if [ "$seed" = "${BAD_SEED:-}" ] && [ "$arm" = joint ]; then
    awk 'BEGIN { FS = OFS = "\t" } !/^#/ && ++n == 2 { $NF = $NF "1" } { print }' "$out" > "$out.x" && mv "$out.x" "$out"
fi
EOF
# make: every argument under $DEEP is a unit, copied from frozen/
cat > "$tmp/make" <<'EOF'
#!/usr/bin/env bash
for a in "$@"; do
    case $a in "$DEEP"/*) mkdir -p "$(dirname "$a")" && cp "frozen/${a#"$DEEP"/}" "$a" ;; esac
done
EOF
chmod +x "$tmp/cli" "$tmp/make"
nseeds=$(sed -n 's/^READING_NSEEDS := //p' src/exp/experiments.mk | tail -n 1)

# tier NAME SLOW_ARM [BAD_SEED]: one tier 2 into $deep; its output in $tmp/NAME, its exit in $tmp/NAME.rc
tier() {
    DEEP=$deep CLI=$tmp/cli MAKE=$tmp/make JOBS=2 READING_NSEEDS=$nseeds SLOW_ARM=$2 BAD_SEED=${3:-} \
        DEEP_UNITS="$deep/field/calibration.tsv $deep/mechanism/sweep.tsv" \
        bash src/exp/verify_deep.sh > "$tmp/$1" 2>&1
    echo $? > "$tmp/$1.rc"
}
results() { grep -E '^  (PASS|FAIL) ' "$tmp/$1"; }

tier first joint
if [ "$(cat "$tmp/first.rc")" = 0 ] && tail -n 1 "$tmp/first" | grep -q '^verify-deep: PASS: '; then
    ok "a tier 2 whose every table equals frozen/ passes"
else bad "a tier 2 whose every table equals frozen/ passes" "exit $(cat "$tmp/first.rc"): $(tail -n 3 "$tmp/first" | tr '\n' '|')"; fi

n=$(results first | grep -c '^  PASS ')
if [ "$n" -gt 2 ] && [ "$(results first)" = "$(cat "$deep/model/redraw.log")" ]; then
    ok "the redraws' verdicts are printed as they are logged ($n)"
else bad "the redraws' verdicts are printed as they are logged" "$n PASS lines; the log differs or is missing"; fi

# the design's list: per set, seeds in ascending order, the joint arm then the independent one
in_list_order() {
    awk '{ f = $2; sub(/:$/, "", f); n = split(f, p, "/"); d = substr(f, 1, length(f) - length(p[n]))
           if (!match(p[n], /_s[0-9]+_(joint|indep)\.tsv$/)) { print "unparsed: " f; exit 1 }
           s = substr(p[n], RSTART + 2) + 0; a = p[n] ~ /_joint\.tsv$/ ? 0 : 1; k = s * 2 + a
           if (d == pd && k != pk + 1) { print "after " pf ": " f; exit 1 }
           if (d != pd && k != 2) { print "a set opening with " f; exit 1 }
           pd = d; pk = k; pf = f }'
}
if why=$(results first | in_list_order); then ok "the results come in the design's order though the joint arms finish last"
else bad "the results come in the design's order though the joint arms finish last" "$why"; fi

tier second indep
if [ "$(results first)" = "$(results second)" ]; then
    ok "the results come in one order whichever arm's redraws finish first"
else bad "the results come in one order whichever arm's redraws finish first" \
    "$(diff <(results first) <(results second) | head -n 4 | tr '\n' '|')"; fi
if [ "$(cat "$tmp/second.rc")" = 0 ]; then ok "a second tier 2 over the leftovers of the first passes"
else bad "a second tier 2 over the leftovers of the first passes" "exit $(cat "$tmp/second.rc"): $(grep -m 2 FAIL "$tmp/second" | tr '\n' '|')"; fi

tier bad '' 1
if [ "$(cat "$tmp/bad.rc")" = 1 ] && grep -q '^  FAIL .*samples_s01_joint\.tsv: redrawn samples differ' "$tmp/bad"; then
    ok "a redrawn sample that differs fails, naming its file"
else bad "a redrawn sample that differs fails, naming its file" "exit $(cat "$tmp/bad.rc"): $(grep -m 2 FAIL "$tmp/bad" | tr '\n' '|')"; fi

echo "[==========] deep tests run."
echo "[  PASSED  ] $pass test(s)."
[ "$fail" -eq 0 ] || { echo "[  FAILED  ] $fail test(s)."; exit 1; }
