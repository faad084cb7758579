#!/usr/bin/env bash
# What it catches: a figure check that fails on a machine whose fonts differ
# from the pinned renderer's (a false inconsistency), or that stops comparing
# what a figure plots where the raster cannot be compared.
# Figures checked on what they show (src/audit/figcheck.h): `crownshy verify`
# in this tree under three font set-ups. With the default sans-serif font
# changed (a fontconfig alias to DejaVu Serif) every script still names its
# font, so the rasters are compared and equal: exit 0. With no font at all
# (a fontconfig that finds none: gnuplot's terminal font absent) the renderer
# differs: verify says so by name, compares each figure's plotted data only,
# and exits 0. A script edited to plot other data (and re-pinned, as an
# author hiding it would) fails on its plotted data under that other
# renderer, where the raster is not compared. Prints cmocka-style lines.
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
cli="$root/build/crownshy"
pass=0; fail=0
ok()  { echo "[       OK ] $1"; pass=$((pass + 1)); }
bad() { echo "[  FAILED  ] $1: $2"; fail=$((fail + 1)); }
tmp=$(mktemp -d "$root/build/fonts.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT

# the fontconfig of (b) and (c): no font at all
mkdir -p "$tmp/nofonts"
cat > "$tmp/none.conf" <<CONF
<?xml version="1.0"?>
<!DOCTYPE fontconfig SYSTEM "fonts.dtd">
<fontconfig><dir>$tmp/nofonts</dir><cachedir>$tmp/cache-b</cachedir></fontconfig>
CONF
# (c) under that renderer, a script that plots other data, re-pinned: in a
# copy of its own, beside (a) and (b), which run verify in this tree
case_c() {
  sed 's|cache-b|cache-c|' "$tmp/none.conf" > "$tmp/none-c.conf"
  scratch="$tmp/copy"; mkdir -p "$scratch/build"
  (cd "$root" && tar cf - README.md LICENSE CITATION.cff src gates frozen audit paper figures tests) | (cd "$scratch" && tar xf -)
  sed -i 's|using (strcol(1) eq "coupled" ? $2 : NaN):7 with linespoints|using (strcol(1) eq "coupled" ? $2 : NaN):($7*1.01) with linespoints|' "$scratch/figures/field.gp"
  if cmp -s "$root/figures/field.gp" "$scratch/figures/field.gp"; then bad "other data plotted" "the edit did not apply"
  else
    (cd "$scratch" && "$cli" pin >/dev/null 2>&1)
    out=$(cd "$scratch" && FONTCONFIG_FILE="$tmp/none-c.conf" "$cli" verify 2>&1); rc=$?
    if [ $rc -eq 1 ] && grep -E '^  FAIL ' <<<"$out" | grep -q 'the data figures/field.gp plots .* differ from figures/plotted.sha256.*Elong'; then
      ok "a script plotting other data fails on its plotted data where the raster is not compared"
    else bad "other data plotted" "exit $rc: $(grep -E '^  FAIL ' <<<"$out" | head -3 | cut -c1-300)"; fi
  fi
}
case_c > "$tmp/c.out" 2>&1 &

# (a) the default sans-serif font changed; the system fonts otherwise as they are
cat > "$tmp/serif.conf" <<CONF
<?xml version="1.0"?>
<!DOCTYPE fontconfig SYSTEM "fonts.dtd">
<fontconfig>
  <include ignore_missing="yes">/etc/fonts/fonts.conf</include>
  <match target="pattern"><test name="family"><string>sans-serif</string></test>
    <edit name="family" mode="prepend" binding="strong"><string>DejaVu Serif</string></edit></match>
  <match target="pattern"><test name="family"><string>Sans</string></test>
    <edit name="family" mode="prepend" binding="strong"><string>DejaVu Serif</string></edit></match>
  <cachedir>$tmp/cache-a</cachedir>
</fontconfig>
CONF
if [ "$(FONTCONFIG_FILE="$tmp/serif.conf" fc-match -f '%{family}' sans 2>/dev/null)" != "DejaVu Serif" ]; then
  bad "default font changed" "the alias did not take (fc-match sans)"
else
  out=$(cd "$root" && FONTCONFIG_FILE="$tmp/serif.conf" "$cli" verify 2>&1); rc=$?
  if [ $rc -eq 0 ] && grep -q 'rasters compared byte for byte' <<<"$out" && ! grep -q '^  FAIL ' <<<"$out"; then
    ok "default font changed: every raster compared and equal, exit 0"
  else bad "default font changed" "exit $rc: $(grep -E '^  FAIL |renderer' <<<"$out" | head -3 | cut -c1-300)"; fi
fi

# (b) no font at all
out=$(cd "$root" && FONTCONFIG_FILE="$tmp/none.conf" "$cli" verify 2>&1); rc=$?
if [ $rc -eq 0 ] && grep -q 'renderer differs: font: pinned' <<<"$out" && grep -q 'not an inconsistency' <<<"$out" \
   && grep -q 'plots equal figures/plotted.sha256' <<<"$out" && ! grep -q '^  FAIL ' <<<"$out"; then
  ok "font absent: the renderer named as differing, plotted data compared, exit 0"
else bad "font absent" "exit $rc: $(grep -E '^  FAIL |renderer' <<<"$out" | head -3 | cut -c1-300)"; fi

wait
cat "$tmp/c.out"
grep -qE '^\[ +(OK|FAILED) +\]' "$tmp/c.out" || bad "other data plotted" "the case printed no result"
pass=$((pass + $(grep -c '^\[       OK \]' "$tmp/c.out"))); fail=$((fail + $(grep -c '^\[  FAILED  \]' "$tmp/c.out")))

echo "[==========] $((pass + fail)) test(s) run."
echo "[  PASSED  ] $pass test(s)."
[ "$fail" -eq 0 ] || echo "[  FAILED  ] $fail test(s)."
[ "$fail" -eq 0 ]
