#!/usr/bin/env bash
# The runner of `make check` (not a test itself): runs cmocka test binaries and
# shell tests, captures their output (cmocka reports on stderr), and ends with
# one aggregate line "N passed, N failed"; a test that cannot be counted (a
# crash, a non-zero exit without a cmocka summary) counts as one failure, so a
# broken test never passes silently. Binaries after a "--" argument are the
# sanitizer build; they are counted the same way.
# Two lanes (TEST_JOBS=1: one): the first shell test given (the longest:
# make check gives tamper.sh first) in one, and the binaries, the sanitizer
# binaries and then the other shell tests, in their order, in the other. Each
# shell test works in a folder of its own (those that run verify in this tree
# share a lane), and a binary never runs beside its sanitizer build (both use
# build/test-tmp/<test>).
# Test temporaries (build/test-tmp) are removed at the end unless KEEP_TEST_TMP=1.
set -u
log_dir=${TEST_LOG_DIR:-build/test-logs}
mkdir -p "$log_dir"
export OPENBLAS_NUM_THREADS=1
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
res=$(mktemp -d "${TMPDIR:-/tmp}/crownshy-run.XXXXXX") || exit 1
trap 'rm -rf "$res"' EXIT
t_start=$SECONDS

# one test: its log, its line, and "passed failed seconds name" in $res/<k>
run_one() {
  local k=$1 t=$2 label=$3 t0=$SECONDS name suffix="" log rc p f
  name=$(basename "$t")$label
  [ -n "$label" ] && suffix="-asan"
  log="$log_dir/$(basename "$t")$suffix.log"
  # a shell test runs through bash whatever its file mode
  case $t in *.sh) bash "$t" > "$log" 2>&1 ;; *) "$t" > "$log" 2>&1 ;; esac; rc=$?
  p=$(sed -n 's/^\[  PASSED  \] \([0-9]*\) test.*/\1/p' "$log" | tail -1)
  f=$(sed -n 's/^\[  FAILED  \] \([0-9]*\) test.*/\1/p' "$log" | tail -1)
  p=${p:-0}; f=${f:-0}
  if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then f=1; fi
  if [ "$f" -gt 0 ]; then
    { echo "FAIL $name ($p passed, $f failed) — log: $log"
      grep -E '^\[  (FAILED|ERROR) |error|Error|ERROR|observed|expected|runtime error|Sanitizer' "$log" | head -20 | sed 's/^/    /'; } > "$res/$k.msg"
  else
    echo "ok   $name ($p passed, $((SECONDS - t0)) s)" > "$res/$k.msg"
  fi
  cat "$res/$k.msg"
  echo "$p $f $((SECONDS - t0)) $name" > "$res/$k"
}
# lane K TEST...: the tests one after another ("--" starts the sanitizer
# binaries; a shell test is never one)
lane() {
  local k=$1 label="" t; shift
  for t in "$@"; do
    if [ "$t" = "--" ]; then label=" [asan+ubsan]"; continue; fi
    k=$((k + 1))
    case $t in *.sh) run_one "$k" "$t" "" ;; *) run_one "$k" "$t" "$label" ;; esac
  done
}
shells=() bins=()
for t in "$@"; do case $t in *.sh) shells+=("$t") ;; *) bins+=("$t") ;; esac; done
if [ "${TEST_JOBS:-2}" -gt 1 ] && [ ${#shells[@]} -gt 0 ]; then
  lane 0 "${shells[0]}" &
  lane 1000 "${bins[@]}" "${shells[@]:1}" &
  wait
else
  lane 0 "${shells[@]}"
  lane 1000 "${bins[@]}"
fi
passed=0; failed=0; slowest=-; slowest_s=0 counted=0
for r in "$res"/[0-9]*; do
  case $r in *.msg) continue ;; esac
  read -r p f s name < "$r"
  passed=$((passed + p)); failed=$((failed + f)); counted=$((counted + 1))
  if [ "$s" -gt "$slowest_s" ]; then slowest_s=$s; slowest=$name; fi
done
# every test given reported (a lane that died would leave some uncounted)
given=$(( ${#shells[@]} + ${#bins[@]} )); for t in "${bins[@]}"; do [ "$t" = "--" ] && given=$((given - 1)); done
if [ "$counted" -ne "$given" ]; then
  echo "FAIL $((given - counted)) of $given test(s) gave no result"; failed=$((failed + given - counted))
fi
# the scratch copies of the tests (build/test-tmp, over 100 MB) go when the
# run ends; KEEP_TEST_TMP=1 keeps them to look at a failure
if [ "${KEEP_TEST_TMP:-0}" != 1 ]; then rm -rf build/test-tmp; fi
echo "took $((SECONDS - t_start)) s on $(nproc 2>/dev/null || echo ?) core(s); slowest: $slowest ($slowest_s s)"
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
