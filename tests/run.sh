#!/usr/bin/env bash
# Runs cmocka test binaries, captures their output (cmocka reports on stderr),
# and ends with one aggregate line "N passed, N failed". Binaries after a "--"
# argument are the sanitizer build; they are counted the same way.
# A binary that crashes or exits non-zero without a cmocka summary counts as one failure.
# Test temporaries (build/test-tmp) are removed at the end unless KEEP_TEST_TMP=1.
set -u
passed=0; failed=0; label=""
log_dir=${TEST_LOG_DIR:-build/test-logs}
mkdir -p "$log_dir"
export OPENBLAS_NUM_THREADS=1
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
t_start=$SECONDS; slowest=-; slowest_s=0
for t in "$@"; do
  if [ "$t" = "--" ]; then label=" [asan+ubsan]"; continue; fi
  t0=$SECONDS
  name=$(basename "$t")$label
  suffix=""; [ -n "$label" ] && suffix="-asan"
  log="$log_dir/$(basename "$t")$suffix.log"
  # a shell test runs through bash whatever its file mode
  case $t in *.sh) bash "$t" > "$log" 2>&1 ;; *) "$t" > "$log" 2>&1 ;; esac; rc=$?
  p=$(sed -n 's/^\[  PASSED  \] \([0-9]*\) test.*/\1/p' "$log" | tail -1)
  f=$(sed -n 's/^\[  FAILED  \] \([0-9]*\) test.*/\1/p' "$log" | tail -1)
  p=${p:-0}; f=${f:-0}
  if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then f=1; fi
  if [ "$f" -gt 0 ]; then
    echo "FAIL $name ($p passed, $f failed) — log: $log"
    grep -E '^\[  (FAILED|ERROR) |error|Error|ERROR|observed|expected|runtime error|Sanitizer' "$log" | head -20 | sed 's/^/    /'
  else
    echo "ok   $name ($p passed, $((SECONDS - t0)) s)"
  fi
  passed=$((passed + p)); failed=$((failed + f))
  if [ $((SECONDS - t0)) -gt "$slowest_s" ]; then slowest_s=$((SECONDS - t0)); slowest=$name; fi
done
# the scratch copies of the tests (build/test-tmp, over 100 MB) go when the
# run ends; KEEP_TEST_TMP=1 keeps them to look at a failure
if [ "${KEEP_TEST_TMP:-0}" != 1 ]; then rm -rf build/test-tmp; fi
echo "took $((SECONDS - t_start)) s on $(nproc 2>/dev/null || echo ?) core(s); slowest: $slowest ($slowest_s s)"
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
