#!/usr/bin/env bash
# What it catches: `make paper` on a partial texlive failing without naming
# what to install (the .sty, its Debian package, the command), or speaking
# when nothing is missing.
# make paper's TeX set-up (src/cli/paper_deps.sh): with every package present it
# passes silently; with a package missing (a kpsewhich that does not find it,
# as on a machine with only part of texlive) and no install allowed, it exits 1
# naming the .sty, its Debian package and the exact command. It also names a
# missing pdflatex. Prints cmocka-style lines so tests/run.sh counts the cases.
set -u
cd "$(dirname "$0")/.."
pass=0; fail=0
ok()  { echo "[       OK ] $1"; pass=$((pass + 1)); }
bad() { echo "[  FAILED  ] $1: $2"; fail=$((fail + 1)); }
tmp=$(mktemp -d build/paper-deps.XXXXXX) || exit 1
trap 'rm -rf "$tmp"' EXIT

# fake tools: kpsewhich finds every .sty except booktabs and xcolor
mkdir -p "$tmp/bin"
printf '#!/bin/sh\ncase "$1" in booktabs.sty|xcolor.sty) exit 1;; *) echo "/tex/$1";; esac\n' > "$tmp/bin/kpsewhich"
printf '#!/bin/sh\nexit 0\n' > "$tmp/bin/pdflatex"
printf '#!/bin/sh\necho /tex/$1\n' > "$tmp/bin/kpsewhich-all"
chmod +x "$tmp/bin/"*

out=$(PATH="$tmp/bin:$PATH" PAPER_DEPS_NOINSTALL=1 bash src/cli/paper_deps.sh paper/main.tex 2>&1); st=$?
if [ $st -eq 1 ] && grep -q 'missing booktabs.sty (Debian package texlive-latex-recommended)' <<<"$out" \
   && grep -q 'missing xcolor.sty' <<<"$out" && grep -q 'apt-get install -y texlive-latex-recommended' <<<"$out" \
   && ! grep -q 'missing geometry.sty' <<<"$out"; then ok "a missing .sty is named with its Debian package and command"
else bad "a missing .sty is named" "status $st: $out"; fi

cp "$tmp/bin/kpsewhich-all" "$tmp/bin/kpsewhich"
out=$(PATH="$tmp/bin:$PATH" PAPER_DEPS_NOINSTALL=1 bash src/cli/paper_deps.sh paper/main.tex 2>&1); st=$?
[ $st -eq 0 ] && [ -z "$out" ] && ok "every package present: silent, status 0" || bad "every package present" "status $st: $out"

out=$(PATH="$tmp/bin:$PATH" PDFLATEX=no-such-pdflatex PAPER_DEPS_NOINSTALL=1 bash src/cli/paper_deps.sh paper/main.tex 2>&1); st=$?
[ $st -eq 1 ] && grep -q 'missing no-such-pdflatex (Debian package texlive-latex-base)' <<<"$out" && ok "a missing pdflatex is named" || bad "a missing pdflatex" "status $st: $out"

echo "[==========] $((pass + fail)) test(s) run."
echo "[  PASSED  ] $pass test(s)."
[ "$fail" -eq 0 ] || echo "[  FAILED  ] $fail test(s)."
[ "$fail" -eq 0 ]
