#!/usr/bin/env bash
# End-to-end on a real single-node Slurm cluster (Debian's slurm-wlm + munge, started here as
# root without systemd, stopped again whatever happens): a 12-case suite submitted with
# bench/cluster/slurm-submit as an array of 4 tasks plus a merge job; task 2 cancelled mid-run;
# the first merge reports it (exit 4, partial summary); task 2 resubmitted, it skips the cases it
# had recorded; the final merge equals a local unsharded run (same cases in the same order, same
# results apart from timings). Slurm's job states are not trusted alone (process tracking can
# fail silently on some machines): every check reads what the tasks wrote.
#
# Usage: slurm_array_test.sh OCPBENCH SOURCE_DIR WORK_DIR. Exit 77 (skipped) when not root.
set -euo pipefail
ocpbench=$(realpath "$1") source_dir=$(realpath "$2") work=$(realpath -m "$3")
if [ "$(id -u)" -ne 0 ]; then
  echo "slurm_array_test: needs root (munged runs as the munge user); skipped"
  exit 77
fi
# shellcheck source=../../bench/cluster/local-slurm.sh
source "$source_dir/bench/cluster/local-slurm.sh"
state="$work/slurm-state"
rm -rf "$work"
mkdir -p "$work"
cd "$work"
local_pid=""
# The cluster is stopped whatever happens (a failed kill of an ended local run must not skip it).
trap 'if [ -n "$local_pid" ]; then kill "$local_pid" 2>/dev/null || true; fi; local_slurm_stop "$state"' EXIT

fail() {
  echo "slurm_array_test: FAILED: $*" >&2
  echo "--- squeue" >&2
  squeue -h -t all -r -o '%i %T %r' >&2 || true
  for f in "$work"/out/slurm/*.out; do
    [ -f "$f" ] && { echo "--- $f" >&2; tail -5 "$f" >&2; }
  done
  tail -5 "$state/slurmctld.log" >&2 || true
  exit 1
}
# Polls `$2...` every 0.1 s until it succeeds; fails the test after $1 seconds.
wait_until() {
  local timeout=$1 what=$2
  shift 2
  local deadline=$((SECONDS + timeout))
  until "$@"; do
    ((SECONDS < deadline)) || fail "timed out after ${timeout} s waiting for $what"
    sleep 0.1
  done
}
# Whole records (lines ended by a newline) in a records file.
complete_lines() { if [ -f "$1" ]; then tr -cd '\n' <"$1" | wc -c; else echo 0; fi; }
has_records() { (($(complete_lines "$1") >= $2)); }
job_state() { squeue -h -t all -r -j "$1" -o '%T' 2>/dev/null | head -1; }
job_ended() {
  case "$(job_state "$1")" in
    COMPLETED | FAILED | CANCELLED | TIMEOUT | NODE_FAIL | OUT_OF_MEMORY) return 0 ;;
    *) return 1 ;;
  esac
}

# Cases of about 0.8 s in the sanitizer build (N = 1200, measured alone; 2 s at N = 3000, which
# made this test cost a minute): a shard of 3 still runs about 1.6 s after its first record,
# while the cancel lands within a few polls of 0.1 s.
seeds=$(seq -s, 1 12)
cat >suite.json <<JSON
{"name": "slurm-e2e", "groups": [{"problem": "double-integrator", "N": ${SLURM_TEST_N:-1200}, "seeds": [$seeds],
  "methods": [{"solver": "hamiltonian", "options": {"max_iterations": 30}}]}]}
JSON

local_slurm_start "$state" || fail "the cluster did not start"
# The same suite in one local process, the reference of the final check: started now, beside the
# array, because most of this test waits for Slurm (its scheduler starts a submitted or dependent
# job 1-3 s later), and the local run alone took 9 of the test's 24 s.
"$ocpbench" run suite.json --out local >local.out 2>local.err &
local_pid=$!
started=$SECONDS
submit=$("$source_dir/bench/cluster/slurm-submit" --ocpbench "$ocpbench" suite.json out 4 | tail -1)
array=$(sed -n 's/^array_job=\([0-9]*\) .*/\1/p' <<<"$submit")
merge1=$(sed -n 's/.* merge_job=\([0-9]*\)$/\1/p' <<<"$submit")
[ -n "$array" ] && [ -n "$merge1" ] || fail "slurm-submit printed '$submit'"

# Cancel task 2 as soon as it has recorded a case.
shard2=out/records.shard-2-of-4.jsonl
wait_until 120 "shard 2's first record" has_records "$shard2" 1
scancel "${array}_2"
wait_until 60 "task 2 to end" job_ended "${array}_2"
kept=$(complete_lines "$shard2")
((kept >= 1 && kept < 3)) || fail "task 2 recorded $kept of 3 cases before its cancel landed"
before=$(head -n "$kept" "$shard2")
echo "slurm_array_test: task 2 cancelled after $kept of its 3 cases ($((SECONDS - started)) s)"

# The merge after the array reports the missing cases of shard 2 and exits 4.
wait_until 120 "the first merge job" job_ended "$merge1"
log1=out/slurm/merge-job-$merge1.out
grep -q "$((9 + kept)) of 12 cases recorded in 4 shards: incomplete" "$log1" ||
  fail "the first merge did not report the missing cases: $(cat "$log1")"
grep -q "shard 2 of 4: $kept of 3 cases recorded" "$log1" || fail "no shard 2 line in $log1"
grep -q "shards to run again: 2$" "$log1" || fail "no 'shards to run again: 2' in $log1"
grep -q "Partial: $((9 + kept)) of the suite's 12 cases" out/summary.md ||
  fail "the partial summary does not say so"
scontrol show job "$merge1" | grep -q "ExitCode=4:0" || fail "the first merge did not exit 4"
set +e
"$ocpbench" status out >status.out 2>&1
status_code=$?
set -e
((status_code == 4)) || fail "status of the incomplete sweep exited $status_code"

# Resubmit task 2: it resumes, and a new merge job follows it.
submit=$("$source_dir/bench/cluster/slurm-submit" --ocpbench "$ocpbench" --tasks 2 suite.json out 4 | tail -1)
array2=$(sed -n 's/^array_job=\([0-9]*\) .*/\1/p' <<<"$submit")
merge2=$(sed -n 's/.* merge_job=\([0-9]*\)$/\1/p' <<<"$submit")
wait_until 120 "the second merge job" job_ended "$merge2"
echo "slurm_array_test: resubmitted task 2 and merged ($((SECONDS - started)) s)"

grep -q "resuming: $kept of 3 cases already recorded" out/slurm/shard-2-job-"$array2".out ||
  fail "the resubmitted task did not resume: $(cat out/slurm/shard-2-job-"$array2".out)"
[ "$(head -n "$kept" "$shard2")" = "$before" ] || fail "the resubmitted task rewrote finished records"
[ "$(complete_lines "$shard2")" = 3 ] || fail "shard 2 holds $(complete_lines "$shard2") records"
[ "$(sed -n 's/.*"key":"\([^"]*\)".*/\1/p' "$shard2" | sort -u | wc -l)" = 3 ] ||
  fail "shard 2 does not hold 3 distinct cases"
grep -q "12 of 12 cases recorded in 4 shards$" out/slurm/merge-job-"$merge2".out ||
  fail "the final merge is not complete: $(cat out/slurm/merge-job-"$merge2".out)"
scontrol show job "$merge2" | grep -q "ExitCode=0:0" || fail "the final merge did not exit 0"
! grep -q Partial out/summary.md || fail "the final summary still says Partial"
"$ocpbench" status out >/dev/null 2>&1 || fail "status of the complete sweep did not exit 0"

# The local run (started beside the array): the same cases, in order, with the same results.
wait "$local_pid" || fail "the local run failed: $(cat local.err)"
local_pid=""
/usr/bin/python3 "$source_dir/tests/cluster/compare_records.py" local/records.jsonl \
  out/records.jsonl || fail "the merged Slurm records differ from the local run"
echo "slurm_array_test: passed ($((SECONDS - started)) s)"
