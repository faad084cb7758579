#!/usr/bin/env bash
# What it catches: a CITATION.cff a citation tool would refuse (a required
# key missing), a version or licence that disagrees with `make dist` or
# LICENSE, a reference without a year.
# LICENSE and CITATION.cff (design.md §9): CITATION.cff is Citation File
# Format 1.2.0 with the keys the format requires (cff-version, message, title,
# authors; each reference: type, title, authors), its version is the one
# `make dist` names the archive with, its licence is the code licence LICENSE
# states, and every reference carries a year. No Debian package ships a CFF
# validator (cffconvert is not packaged), so the required keys are checked
# here; when python3 with PyYAML is present the file is also parsed as YAML.
# A copy missing a required key must fail (the check can fail).
# Prints cmocka-style lines so tests/run.sh counts the cases.
set -u
cd "$(dirname "$0")/.."
pass=0; fail=0
ok()  { echo "[       OK ] $1"; pass=$((pass + 1)); }
bad() { echo "[  FAILED  ] $1: $2"; fail=$((fail + 1)); }

# cff_check FILE: prints the first problem and returns 1, or returns 0
cff_check() {
  awk '
    function top(k) { return $0 ~ ("^" k ":") }
    /^[a-z-]+:/ { sect = $1; sub(/:$/, "", sect); seen[sect] = 1; val[sect] = $0; sub(/^[a-z-]+: */, "", val[sect]) }
    sect == "authors" && /^  - (name|family-names|given-names):/ { nauth++ }
    sect == "references" && /^  - type:/ { nref++; rtype[nref] = 1 }
    sect == "references" && /^    title:/ { rtitle[nref] = 1 }
    sect == "references" && /^    authors:/ { rauth[nref] = 1 }
    sect == "references" && /^    year: *[0-9][0-9][0-9][0-9] *$/ { ryear[nref] = 1 }
    END {
      split("cff-version message title authors version license", req, " ")
      for (i = 1; i in req; i++) if (!(req[i] in seen)) { print "missing required key " req[i]; exit 1 }
      v = val["cff-version"]; gsub(/["'\'' ]/, "", v)
      if (v != "1.2.0") { print "cff-version is " v ", not 1.2.0"; exit 1 }
      if (val["title"] == "" ) { print "empty title"; exit 1 }
      if (nauth < 1) { print "authors has no entry with a name"; exit 1 }
      for (r = 1; r <= nref; r++) {
        if (!(r in rtitle)) { print "reference " r " has no title"; exit 1 }
        if (!(r in rauth)) { print "reference " r " has no authors"; exit 1 }
        if (!(r in ryear)) { print "reference " r " has no year"; exit 1 }
      }
      if (nref < 1) { print "no reference to the reproduced paper"; exit 1 }
      print "version " val["version"] " license " val["license"] " references " nref
    }' "$1"
}

echo "[==========] Running LICENSE and CITATION.cff checks"
if out=$(cff_check CITATION.cff); then ok "CITATION.cff has the required keys ($out)"; else bad "CITATION.cff" "$out"; fi

lic=$(sed -n 's/^license: *//p' CITATION.cff)
if [ -f LICENSE ] && grep -q "SPDX: $lic)" LICENSE && grep -q "^$lic License$" LICENSE; then ok "LICENSE states the code licence $lic that CITATION.cff names"
else bad "LICENSE" "absent, or it does not state the licence '$lic' of CITATION.cff"; fi
if grep -q "CC-BY-4.0" LICENSE && grep -q "doi:10.5061/dryad.34tmpg4hk" LICENSE && grep -q "CC0" LICENSE; then ok "LICENSE states the terms of the results (CC BY 4.0) and cites the CC0 field data"
else bad "LICENSE" "the terms of the results or the field-data citation are missing"; fi

ver=$(sed -n 's/^version: *//p' CITATION.cff)
mver=$(make -s --no-print-directory dist-version 2>/dev/null)
if [ -n "$ver" ] && [ "$ver" = "$mver" ]; then ok "the archive version (make dist-version) is CITATION.cff's $ver"
else bad "version" "CITATION.cff says '$ver', make dist-version says '$mver'"; fi

if python3 -c 'import yaml' 2>/dev/null; then
  if err=$(python3 -c 'import sys, yaml; d = yaml.safe_load(open("CITATION.cff")); assert isinstance(d, dict) and d["cff-version"] == "1.2.0" and isinstance(d["authors"], list) and all(isinstance(r, dict) and r.get("title") for r in d["references"]), "structure"' 2>&1)
  then ok "CITATION.cff parses as YAML (PyYAML)"; else bad "CITATION.cff YAML" "$err"; fi
else echo "[ SKIPPED  ] YAML parse: python3 with PyYAML not installed (the key checks above still ran)"; fi

# the check can fail: a copy without its title, one without the year of a reference
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
grep -v '^title:' CITATION.cff > "$tmp/a.cff"
if out=$(cff_check "$tmp/a.cff"); then bad "negative: no title" "accepted"; else ok "a copy without title is refused ($out)"; fi
grep -v '^    year:' CITATION.cff > "$tmp/b.cff"
if out=$(cff_check "$tmp/b.cff"); then bad "negative: no year" "accepted"; else ok "a copy whose references lack a year is refused ($out)"; fi
sed 's/^cff-version: .*/cff-version: 1.1.0/' CITATION.cff > "$tmp/c.cff"
if out=$(cff_check "$tmp/c.cff"); then bad "negative: cff-version" "accepted"; else ok "a copy with cff-version 1.1.0 is refused ($out)"; fi

echo "[==========] $((pass + fail)) test(s) run."
echo "[  PASSED  ] $pass test(s)."
[ "$fail" -eq 0 ] || echo "[  FAILED  ] $fail test(s)."
[ "$fail" -eq 0 ]
