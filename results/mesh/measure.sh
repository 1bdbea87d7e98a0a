#!/bin/bash
# Adaptive mesh refinement against uniform grids, in one run (README, "Adaptive mesh refinement").
# Usage: results/mesh/measure.sh [OCPBENCH] > results/mesh/summary.md
# Every case: Ipopt (default options, tol 1e-8) on double-integrator-bounded (J* = 6.0450277563,
# two corners of u*), hard terminal form, 5 timing repeats (median CPU). Records go to a
# temporary folder, except the refined Hermite-Simpson one (results/mesh/refined-hs.json), which
# results/plotting/mesh_figure.py draws (results/mesh/refined-hs.png).
set -euo pipefail
OCPBENCH=${1:-build/bin/ocpbench}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT

solve() {  # NAME SCHEME N [MESH_TOLERANCE]
  local args=(solve --problem double-integrator-bounded --solver ipopt --transcription "$2"
              --terminal hard --N "$3" --repeats 5 --json "$OUT/$1.json")
  if [ $# -ge 4 ]; then args+=(--option "mesh_tolerance=$4"); fi
  "$OCPBENCH" "${args[@]}" > /dev/null
}

for scheme in hermite-simpson trapezoid; do
  solve "$scheme-refined" "$scheme" 10 "$([ $scheme = trapezoid ] && echo 1e-7 || echo 1e-8)"
  for N in 25 50 100 200 400 800 1600; do solve "$scheme-uniform-$N" "$scheme" "$N"; done
done

HERE=$(dirname "$0")
cp "$OUT/hermite-simpson-refined.json" "$HERE/refined-hs.json"
/usr/bin/python3 "$HERE/../plotting/mesh_figure.py" "$HERE/refined-hs.json" "$HERE/refined-hs.png"

/usr/bin/python3 - "$OUT" <<'PY'
import glob, json, os, sys
out = sys.argv[1]
print("# Adaptive mesh refinement against uniform grids (double-integrator-bounded)\n")
print("Written by `results/mesh/measure.sh` (every row in one run; Ipopt with its default options, "
      "hard terminal form; relative errors against J* = 6.0450277563; Jbar_fine is the common "
      "evaluator's RK4 re-simulation of the controls on the final grid refined 10 times). "
      "Figure: `refined-hs.png`.\n")
print("| scheme | grid | final N | NLP variables | objective rel. error | Jbar_fine rel. error | Ipopt iterations | CPU s (median of 5) |")
print("|---|---|---|---|---|---|---|---|")
def key(path):  # (scheme, 0 for the refined case, else N)
    name = os.path.basename(path)[:-len(".json")]
    if name.endswith("-refined"):
        return (name[:-len("-refined")], 0)
    scheme, _, N = name.rsplit("-", 2)
    return (scheme, int(N))
for path in sorted(glob.glob(out + "/*.json"), key=key):
    r = json.load(open(path))
    J = r["reference"]["value"]
    m = r.get("mesh")
    grid = (f"refined from N = 10, mesh_tolerance {r['transcription_options']['mesh_tolerance']:g} "
            f"({len(m['history'])} meshes, {m['stop_reason']})" if m else "uniform")
    N = len(m["nodes"]) - 1 if m else r["N"]
    print(f"| {r['transcription']} | {grid} | {N} | {int(r['solver_stats']['nlp_variables'])} | "
          f"{abs(r['objective'] - J) / J:.1e} | {abs(r['Jbar_fine'] - J) / J:.1e} | "
          f"{r['iterations']} | {r['cpu_seconds']:.4f} |")
PY
