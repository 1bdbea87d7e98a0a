#!/bin/bash
# Adaptive mesh refinement against uniform grids on every reference problem, in one run (README,
# "Adaptive mesh refinement"; the protocol: results/mesh/measure.py's docstring).
# Usage: results/mesh/measure.sh [OCPBENCH] > results/mesh/summary.md
# Every solve's outcome goes to results/mesh/rows.jsonl; the records of the refined
# double-integrator-bounded cases to results/mesh/refined-{hs,lgr}.json, which
# results/plotting/mesh_figure.py draws (refined-{hs,lgr}.png).
set -euo pipefail
OCPBENCH=${1:-build/bin/ocpbench}
HERE=$(dirname "$0")
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT

/usr/bin/python3 "$HERE/measure.py" "$OCPBENCH" "$OUT"
cp "$OUT/rows.jsonl" "$HERE/rows.jsonl"
for scheme in hs lgr; do
  /usr/bin/python3 "$HERE/../plotting/mesh_figure.py" "$HERE/refined-$scheme.json" \
    "$HERE/refined-$scheme.png"
done
