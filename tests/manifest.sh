#!/usr/bin/env bash
# What it catches: a new experiment that needs a file the "Adding an
# experiment" section does not name, or that make, the CLI, trace or verify
# do not pick up from the manifest alone.
# manifest.sh: a new experiment is added through the manifest alone. In a
# scratch copy of the package (build/manifest-test/repo, its own git), adds a
# toy experiment "toy" with exactly the files the "Adding an
# experiment" section of src/README.md names for a unit with the common
# options (manifest rows, the experiment, a claim function and its claim
# table, its interval row), then checks that
#  - the number of hand-written files equals the count src/README.md states;
#  - `crownshy claims-table` prints its claim into audit/claims.tsv (the
#    file is generated, never edited);
#  - make lists its unit (`make units`: reproduce and verify-deep) and
#    `make toy` runs it;
#  - `crownshy --help` lists its command and `crownshy toy-run --help` works;
#  - `make freeze` (after `crownshy pin`) writes the toy's table and no other
#    frozen file; its
#    claim is computed from its frozen table, `crownshy trace` names it,
#    the computing function's real file and the experiment, and
#    `crownshy verify --no-figures` says the package is consistent.
# Prints cmocka-style lines so tests/run.sh counts it like a test binary.
set -u
cd "$(dirname "$0")/.."
pass=0; fail=0
ok()  { echo "[       OK ] $1"; pass=$((pass + 1)); }
bad() { echo "[  FAILED  ] $1: $2"; fail=$((fail + 1)); }
finish() {
    echo "[==========] manifest tests run."
    echo "[  PASSED  ] $pass test(s)."
    [ $fail -eq 0 ] || echo "[  FAILED  ] $fail test(s)."
    [ $fail -eq 0 ]; exit $?
}

T=$PWD/build/manifest-test
R=$T/repo
rm -rf "$T"; mkdir -p "$R"
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    git ls-files -co --exclude-standard | grep -v '^build/' | tar -cf - -T - | tar -xf - -C "$R"
else
    tar --exclude=./build -cf - . | tar -xf - -C "$R"
fi
cd "$R"
G="git -c user.name=manifest-test -c user.email=manifest-test@localhost"
$G init -q . && $G add -A && $G commit -qm "package before the toy experiment" || { bad "scratch copy" "git init failed"; finish; }

# ---- the toy experiment, by src/README.md's list -------------------------------
cat >> src/base/manifest.h.new <<'EOF'
EXPERIMENT(toy, "E99", "src/exp/exp_toy.c", "-", "src/claims/claim_toy.c", "-", "rerun", "a toy: five numbers and their mean")
RUN(toy, "toy-run", exp_toy_run, "-", "toy: write five numbers")
UNIT(toy, "numbers.tsv", "", "$(CLI) toy-run --out @R@", "top")
CLAIMS(claim_table_toy)
EOF
# the rows go before the closing #undef lines
awk 'FNR == NR { add = add $0 "\n"; next } /^#undef EXPERIMENT/ && !done { printf "%s\n", add; done = 1 } { print }' \
    src/base/manifest.h.new src/base/manifest.h > src/base/manifest.h.tmp && mv src/base/manifest.h.tmp src/base/manifest.h
rm -f src/base/manifest.h.new

cat > src/exp/exp_toy.c <<'EOF'
/* exp_toy: a toy experiment (tests/manifest.sh): five numbers under DIR/toy/. */
#include "exp_common.h"
#include "unit_out.h"
#include <stdio.h>

cs_status exp_toy_run(const exp_opts *o)
{
    char path[512];
    snprintf(path, sizeof path, "%s/toy/numbers.tsv", o->out);
    prov p;
    exp_prov_begin(&p, "toy", &o->rd, o->argc, o->argv);
    tsv_writer *w;
    cs_status st = tsv_writer_open(&w, path);
    if (st) return st;
    if ((st = prov_write(w, &p))) { tsv_writer_abort(w); return st; }
    tsv_writer_columns(w, "k\tvalue");
    for (int k = 1; k <= 5; k++) {
        tsv_writer_long(w, k);
        tsv_writer_dbl(w, 0.5 * k);
        tsv_writer_endrow(w);
    }
    return unit_out_finish(w, &p, path);
}
EOF
cat > src/claims/claim_toy.c <<'EOF'
/* claim_toy: the toy experiment's claim, the mean of frozen/toy/numbers.tsv. */
#include "claims.h"
#include "tsv.h"
#include <stdio.h>

cs_status claim_toy_mean(const claim_row *row, claim_result *res)
{
    tsv *t;
    cs_status st = tsv_read(row->source, &t);
    if (st) return st;
    double sum = 0, v;
    size_t n = tsv_nrows(t);
    for (size_t r = 0; r < n && !st; r++)
        if (!(st = tsv_double(t, r, "value", &v))) sum += v;
    if (!st && !n) st = cs_err(CS_EINPUT, "%s: no rows", row->source);
    if (!st) {
        snprintf(res->where, sizeof res->where, "%s (%zu rows)", row->source, n);
        claim_set_value(row, res, sum / (double)n);
    }
    tsv_free(t);
    return st;
}

const claim_spec claim_table_toy[] = {
    {"ToyMean", "measured", "frozen/toy/numbers.tsv", "claim_toy_mean", "-", "-", "%.2f", "-", {0}},
};
CLAIM_TABLE_SIZE(claim_table_toy);
EOF
printf 'claim_toy_mean\tnumber\tnone\ta toy: five numbers, no replicate unit\n' >> audit/intervals.tsv

# ---- the count src/README.md states --------------------------------------------
want=$(sed -n 's/.*needs \*\*\([0-9]*\) files\*\*.*/\1/p' src/README.md | head -1)
have=$($G status --porcelain | wc -l)
if [ -n "$want" ] && [ "$have" = "$want" ]; then ok "the toy experiment takes the $want files the README names"
else bad "the toy experiment takes the files src/README.md names" "src/README.md says '${want:-?}', the toy needed $have: $($G status --porcelain | tr '\n' ' ')"; fi

# The scratch history holds one commit, not the package's: verify checks
# superseded pins against the history when there is one, so the copy goes on
# as a release does, without .git.
rm -rf .git

# ---- make, the CLI -----------------------------------------------------------
if ! make -s -j2 build/crownshy > "$T/build.log" 2>&1; then bad "the package builds with the toy" "$(tail -5 "$T/build.log")"; finish; fi
build/crownshy claims-table > "$T/claims.log" 2>&1
if tail -1 audit/claims.tsv | grep -q '^ToyMean	measured	frozen/toy/numbers.tsv	claim_toy_mean	-	tests/test_claims.c:claim_ToyMean	'; then
    ok "crownshy claims-table prints the toy's claim as the registry's last row"
else bad "crownshy claims-table prints the toy's claim" "$(cat "$T/claims.log"; tail -1 audit/claims.tsv)"; fi
units=$(make -s units 2>&1)
if grep -q '^reproduce: .*build/results/toy/numbers.tsv' <<<"$units" && grep -q '^verify-deep: .*build/results/toy/numbers.tsv' <<<"$units" \
   && grep -q '^experiments: .* toy' <<<"$units"; then ok "make lists the toy unit for reproduce and verify-deep"
else bad "make lists the toy unit for reproduce and verify-deep" "$units"; fi
if build/crownshy --help | grep -q '^  toy-run  *toy: write five numbers' && build/crownshy toy-run --help | grep -q 'usage: crownshy toy-run'; then
    ok "crownshy --help lists toy-run, which has its own --help"
else bad "crownshy --help lists toy-run" "$(build/crownshy --help | grep -n toy)"; fi
if make -s toy > "$T/run.log" 2>&1 && [ -f build/results/toy/numbers.tsv ] && grep -q '^# experiment: toy' build/results/toy/numbers.tsv; then
    ok "make toy runs the unit into build/results/toy/"
else bad "make toy runs the unit" "$(tail -5 "$T/run.log")"; finish; fi

# ---- freeze, the claim, trace, verify ----------------------------------------
# `make freeze` adds the toy's table and touches no other frozen file (the
# summaries of other experiments are remade only when their units were run)
snap() { (cd frozen && find . -type f -print0 | sort -z | xargs -0 sha256sum); }
before=$(snap)
build/crownshy pin > /dev/null
make -s freeze > "$T/numbers.log" 2>&1 || bad "make freeze" "$(tail -3 "$T/numbers.log")"
touched=$(diff <(echo "$before") <(snap) | sed -n 's/^[<>] [0-9a-f]*  //p' | sort -u | tr '\n' ' ')
if [ "$touched" = "./toy/numbers.tsv " ]; then ok "make freeze writes frozen/toy/ and touches no other frozen file"
else bad "make freeze touches only the toy's frozen files" "changed: $touched"; fi
if grep -q 'ToyMean}{1.50}' paper/numbers.tex; then ok "crownshy numbers computes the toy claim from frozen/toy/ (1.50)"
else bad "crownshy numbers computes the toy claim" "$(grep Toy paper/numbers.tex; tail -3 "$T/numbers.log")"; fi
tr=$(build/crownshy trace ToyMean 2>&1)
if grep -q '^source *frozen/toy/numbers.tsv' <<<"$tr" && grep -q '^function *claim_toy_mean (src/claims/claim_toy.c:[0-9]*)' <<<"$tr" \
   && grep -q '^table *claim_table_toy (src/claims/claim_toy.c:[0-9]*)' <<<"$tr" \
   && grep -q '^experiment *toy (E99)' <<<"$tr"; then ok "crownshy trace ToyMean names the table, src/claims/claim_toy.c (function and claim table) and the experiment"
else bad "crownshy trace ToyMean" "$tr"; fi
# the layout rules hold with the toy frozen, its row in src/README.md's generated table
bash src/base/manifest.sh readme-write
if bash tests/layout.sh > "$T/layout.log" 2>&1; then ok "the layout checks pass with the toy experiment in place"
else bad "the layout checks with the toy" "$(grep FAILED "$T/layout.log" | head -3)"; fi
build/crownshy verify --no-figures > "$T/verify.log" 2>&1; rc=$?
if [ $rc -eq 0 ] && grep -q '^package: consistent' "$T/verify.log" && grep -q 'PASS *ToyMean' "$T/verify.log"; then
    ok "crownshy verify: the toy claim passes and the package is consistent"
else bad "crownshy verify with the toy" "exit $rc: $(grep -E 'FAIL|ToyMean|package' "$T/verify.log" | head -5 | tr '\n' ' ')"; fi
finish
