#!/usr/bin/env bash
# Fuzzes one libFuzzer target for FUZZ_SECONDS from its seed corpus:
#   FUZZ_SECONDS=20 bash tests/fuzz/run_fuzzer.sh BUILD_DIR SOURCE_DIR TARGET
# The one way a fuzzer is run: by .ci/fuzz (every target, a few at a time; CI runs it after the
# test command with FUZZ_SECONDS=20) and by the CTest test fuzz.<target>
# (tests/fuzz/CMakeLists.txt); without FUZZ_SECONDS (or with 0) it exits 77, which CTest reports
# as skipped, so a plain `ctest` does not fuzz (`.ci/test` leaves these tests out).
# The corpus grows in BUILD_DIR/fuzz/corpus/TARGET/. A crash fails the run (exit non-zero) and
# leaves its input in BUILD_DIR/fuzz/crashes/TARGET/: copy it to tests/fuzz/regressions/TARGET/
# (replayed by every test run, fuzz_replay.TARGET) and fix the bug. The whole log is
# BUILD_DIR/fuzz/TARGET.log; its end (libFuzzer's final statistics) is printed.
set -euo pipefail
if [ $# -ne 3 ]; then
  echo "usage: FUZZ_SECONDS=N bash run_fuzzer.sh BUILD_DIR SOURCE_DIR TARGET" >&2
  exit 2
fi
build=$1 source=$2 target=$3
seconds=${FUZZ_SECONDS:-0}
if ! [[ "$seconds" =~ ^[0-9]+$ ]]; then
  echo "run_fuzzer: FUZZ_SECONDS must be a whole number of seconds, not '$seconds'" >&2
  exit 2
fi
if [ "$seconds" -eq 0 ]; then
  echo "fuzz.${target}: FUZZ_SECONDS is not set; skipped (FUZZ_SECONDS=20 ctest, or .ci/fuzz)"
  exit 77
fi
work="${build}/fuzz/corpus/${target}"
crashes="${build}/fuzz/crashes/${target}"
log="${build}/fuzz/${target}.log"
mkdir -p "$work" "$crashes"
echo "fuzzing ${target} for ${seconds} s (log ${log})"
# -error_exitcode=1: libFuzzer's own default, 77, is CTest's skip code here (a crash reported
# as skipped would pass the run).
rc=0
"${build}/bin/${target}_fuzzer" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
  -error_exitcode=1 -artifact_prefix="${crashes}/" -print_final_stats=1 "$work" \
  "${source}/tests/fuzz/corpus/${target}" >"$log" 2>&1 || rc=$?
if [ "$rc" -eq 77 ]; then rc=1; fi
echo "--- ${target}_fuzzer: exit ${rc}"
if [ "$rc" -ne 0 ]; then
  # The report and the input's file; the statistics below would push them out of the tail.
  grep -E '^==[0-9]+==|^SUMMARY:|deadly signal|Test unit written|^artifact_prefix' "$log" | head -n 40 || true
fi
tail -n 12 "$log"
exit "$rc"
