#!/usr/bin/env bash
# Instructions per grid point and iteration of the paper's 500-iteration Hamiltonian descent
# (comm-path2d, N = 400, seed 1, defaults; issue 20), counted by callgrind inside
# HamiltonianDescent::Solve only (the channel's construction is outside it):
#
#   bash bench/callgrind_descent.sh [path/to/ocpbench_kernels]   (default build/bin/...)
#
# Needs valgrind and a Release build of ocpbench_kernels. Instruction counts do not depend on the
# machine's load, so two builds can be compared on a busy machine.
set -euo pipefail
cd "$(dirname "$0")/.."
kernels="${1:-build/bin/ocpbench_kernels}"
log="$(mktemp)"
out="$(mktemp)"
trap 'rm -f "$log" "$out"' EXIT
valgrind --tool=callgrind --callgrind-out-file="$out" \
  --toggle-collect='ocpb::HamiltonianDescent::Solve*' \
  "$kernels" --benchmark_filter='^BM_HamiltonianPaperSolveCallgrind/' 2>"$log"
collected="$(sed -n 's/.*Collected : \([0-9]*\).*/\1/p' "$log")"
if [ -z "$collected" ] || [ "$collected" = 0 ]; then
  cat "$log" >&2
  echo "callgrind reported no count" >&2
  exit 1
fi
points=400
iterations=500
echo "instructions in HamiltonianDescent::Solve: ${collected}"
echo "per grid point per iteration (N = ${points}, ${iterations} iterations):" \
  "$((collected / (points * iterations)))"
