#!/usr/bin/env bash
# End-to-end: the README's GNU parallel recipe, as a user would run it. A 12-case suite in 4
# shards, 2 at once; shard 2's process killed mid-run; merge reports the missing cases (exit 4,
# partial summary); the same command run again finishes shard 2 without redoing its recorded
# cases (the others run nothing); the merge equals a local unsharded run (same cases in the same
# order, same results apart from timings).
#
# Usage: parallel_recipe_test.sh OCPBENCH SOURCE_DIR WORK_DIR
set -euo pipefail
ocpbench=$(realpath "$1") source_dir=$(realpath "$2") work=$(realpath -m "$3")
command -v parallel >/dev/null || {
  echo "parallel_recipe_test: GNU parallel not found (Debian package parallel)" >&2
  exit 1
}
rm -rf "$work"
mkdir -p "$work"
cd "$work"
parallel_pid=""
# Only what this test started: the parallel process and its descendants.
cleanup() {
  [ -n "$parallel_pid" ] || return 0
  local pid
  for pid in $(descendants "$parallel_pid") "$parallel_pid"; do kill -KILL "$pid" 2>/dev/null || true; done
}
trap cleanup EXIT
descendants() {
  local child
  for child in $(cat /proc/"$1"/task/*/children 2>/dev/null); do
    echo "$child"
    descendants "$child"
  done
}
fail() {
  echo "parallel_recipe_test: FAILED: $*" >&2
  exit 1
}
wait_until() {
  local timeout=$1 what=$2
  shift 2
  local deadline=$((SECONDS + timeout))
  until "$@"; do
    ((SECONDS < deadline)) || fail "timed out after ${timeout} s waiting for $what"
    sleep 0.05
  done
}
complete_lines() { if [ -f "$1" ]; then tr -cd '\n' <"$1" | wc -c; else echo 0; fi; }
has_records() { (($(complete_lines "$1") >= $2)); }
# The pid of the ocpbench process running shard $1 of 4, among parallel's descendants.
shard_pid() {
  local pid
  for pid in $(descendants "$parallel_pid"); do
    if [ "$(tr '\0' ' ' <"/proc/$pid/cmdline" 2>/dev/null)" = \
      "$ocpbench run suite.json --out results/big --resume --shard $1/4 " ]; then
      echo "$pid"
      return 0
    fi
  done
  return 1
}

# Cases of about 0.8 s in the sanitizer build (N = 1200): shard 2 still runs about 1.6 s after
# its first record, and the kill follows that record within a poll of 0.05 s.
seeds=$(seq -s, 1 12)
cat >suite.json <<JSON
{"name": "big", "groups": [{"problem": "double-integrator", "N": ${PARALLEL_TEST_N:-1200}, "seeds": [$seeds],
  "methods": [{"solver": "hamiltonian", "options": {"max_iterations": 30}}]}]}
JSON

# The README's recipe (with the test's program path).
recipe() {
  parallel -j 2 "$ocpbench" run suite.json --out results/big --resume --shard {}/4 ::: $(seq 4)
}
recipe >parallel1.out 2>&1 &
parallel_pid=$!
shard2=results/big/records.shard-2-of-4.jsonl
wait_until 120 "shard 2's first record" has_records "$shard2" 1
pid=$(shard_pid 2) || fail "no process runs shard 2 ($(complete_lines "$shard2") records)"
kill -KILL "$pid"
set +e
wait "$parallel_pid"
parallel_code=$?
set -e
parallel_pid=""
((parallel_code == 1)) || fail "parallel exited $parallel_code, not 1 (one failed job)"
kept=$(complete_lines "$shard2")
((kept >= 1 && kept < 3)) || fail "shard 2 recorded $kept of 3 cases before its kill"
before=$(head -n "$kept" "$shard2")

set +e
"$ocpbench" merge results/big >merge1.out 2>&1
merge_code=$?
set -e
((merge_code == 4)) || fail "the merge of the incomplete sweep exited $merge_code: $(cat merge1.out)"
grep -q "shard 2 of 4: $kept of 3 cases recorded" merge1.out || fail "no shard 2 line: $(cat merge1.out)"
grep -q "Partial: $((9 + kept)) of the suite's 12 cases" results/big/summary.md ||
  fail "the partial summary does not say so"

# The same command again: shard 2 resumes, the finished shards run nothing.
recipe >parallel2.out 2>&1 || fail "the second parallel run failed: $(cat parallel2.out)"
grep -q "resuming: $kept of 3 cases already recorded" parallel2.out || fail "shard 2 did not resume"
[ "$(grep -c "resuming: 3 of 3 cases already recorded" parallel2.out)" = 3 ] ||
  fail "the finished shards did not skip all their cases: $(cat parallel2.out)"
[ "$(head -n "$kept" "$shard2")" = "$before" ] || fail "finished records of shard 2 were rewritten"
"$ocpbench" merge results/big >merge2.out 2>&1 || fail "the final merge failed: $(cat merge2.out)"
grep -q "12 of 12 cases recorded in 4 shards$" merge2.out || fail "$(cat merge2.out)"
! grep -q Partial results/big/summary.md || fail "the final summary still says Partial"

"$ocpbench" run suite.json --out local 2>local.err || fail "the local run failed: $(cat local.err)"
/usr/bin/python3 "$source_dir/tests/cluster/compare_records.py" local/records.jsonl \
  results/big/records.jsonl || fail "the merged records differ from the local run"
echo "parallel_recipe_test: passed"
