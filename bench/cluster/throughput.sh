#!/usr/bin/env bash
# Throughput of one suite of cheap cases through one process, `run --jobs 2` and a Slurm job
# array on a private single-node cluster (bench/cluster/local-slurm.sh; root), and the cost per
# task. A benchmark, not a test: it prints what it measured, with the load average beside it.
#
#   bash bench/cluster/throughput.sh OCPBENCH WORK_DIR [CASES] [TASKS]
#
# CASES (default 2000) double-integrator cases solved by 20 Hamiltonian iterations on N = 50
# (a few ms each in a Release build); TASKS (default 20) array tasks of CASES/TASKS cases.
set -euo pipefail
ocpbench=$(realpath "$1") work=$(realpath -m "$2") cases=${3:-2000} tasks=${4:-20}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
# shellcheck source=local-slurm.sh
source "$here/local-slurm.sh"
rm -rf "$work"
mkdir -p "$work"
cd "$work"
state="$work/slurm-state"
trap 'local_slurm_stop "$state"' EXIT
now() { date +%s.%N; }
calc() { awk "BEGIN { printf \"%.3f\", $1 }"; }
since() { calc "$(now) - $1"; }
load() { cut -d' ' -f1-3 /proc/loadavg; }
cpu_sum() { /usr/bin/python3 -c "
import json, sys
print(sum(json.loads(l)['cpu_seconds'] for l in open(sys.argv[1]) if l.strip()))" "$1"; }

cat >suite.json <<JSON
{"name": "throughput", "groups": [{"problem": "double-integrator", "N": 50,
  "seeds": [$(seq -s, 1 "$cases")], "keep_trajectory": false,
  "methods": [{"solver": "hamiltonian", "options": {"max_iterations": 20}}]}]}
JSON
echo "cases $cases, tasks $tasks, $(nproc) CPUs; load at start: $(load)"

t=$(now)
/usr/bin/time -f "%U %S" -o serial.time "$ocpbench" run suite.json --out serial 2>serial.err
serial=$(since "$t")
echo "one process:    wall $(printf %.2f "$serial") s, user+sys $(awk '{print $1 + $2}' serial.time) s," \
  "cases' own CPU $(printf %.2f "$(cpu_sum serial/records.jsonl)") s; load $(load)"

t=$(now)
/usr/bin/time -f "%U %S" -o jobs.time "$ocpbench" run suite.json --out jobs --jobs 2 2>jobs.err
jobs=$(since "$t")
echo "--jobs 2:       wall $(printf %.2f "$jobs") s, user+sys $(awk '{print $1 + $2}' jobs.time) s," \
  "cases' own CPU $(printf %.2f "$(cpu_sum jobs/records.jsonl)") s; throughput x$(calc "$serial / $jobs"); load $(load)"

# One task's fixed cost outside Slurm: start, read and check the whole suite, run one case.
t=$(now)
"$ocpbench" run suite.json --out one --shard "1/$cases" 2>/dev/null
one=$(since "$t")
echo "one shard of 1 case (start + check all $cases cases + 1 case): wall $(printf %.3f "$one") s"

local_slurm_start "$state" 2>/dev/null
# Slurm's own cost per task: an array of tasks that do nothing.
t=$(now)
empty=$(sbatch --parsable --array="1-$tasks" --output=/dev/null --wrap true)
until [ -z "$(squeue -h -j "$empty" -t PD,R,CG)" ]; do sleep 0.05; done
empty_wall=$(since "$t")
echo "slurm, $tasks empty tasks: wall $(printf %.2f "$empty_wall") s" \
  "($(calc "$empty_wall * $(nproc) / $tasks") core-s per task)"

t=$(now)
ids=$("$here/slurm-submit" --ocpbench "$ocpbench" suite.json slurm "$tasks" 2>/dev/null | tail -1)
merge_job=${ids##*merge_job=}
until [ -z "$(squeue -h -j "$merge_job" -t PD,R,CG)" ]; do sleep 0.05; done
slurm=$(since "$t")
grep -q "$cases of $cases cases recorded" slurm/slurm/merge-job-"$merge_job".out ||
  { echo "the Slurm run is incomplete: $(cat slurm/slurm/merge-job-"$merge_job".out)"; exit 1; }
overhead=$(calc "($slurm * $(nproc) - $serial) / $tasks")
echo "slurm array:    wall $(printf %.2f "$slurm") s (submit to merged), cases' own CPU" \
  "$(printf %.2f "$(cpu_sum slurm/records.jsonl)") s; throughput x$(calc "$serial / $slurm");" \
  "overhead $(printf %.3f "$overhead") core-s per task; load $(load)"
/usr/bin/python3 "$here/../../tests/cluster/compare_records.py" serial/records.jsonl slurm/records.jsonl
/usr/bin/python3 "$here/../../tests/cluster/compare_records.py" serial/records.jsonl jobs/records.jsonl
t=$(now)
"$ocpbench" merge slurm 2>/dev/null
echo "merge of $cases records from $tasks shards: wall $(printf %.3f "$(since "$t")") s," \
  "records.jsonl $(du -k slurm/records.jsonl | cut -f1) KiB"
echo "load at end: $(load)"
