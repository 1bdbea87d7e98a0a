#!/usr/bin/python3
"""Re-runs refined rows of results/mesh/rows.jsonl by measure.py's protocol and replaces them.

Usage: /usr/bin/python3 results/mesh/rerun_rows.py OCPBENCH PROBLEM SCHEME TOL [TOL ...]

For rows the measure.py run lost ("no record": the script version that ran kept only exit code
0). Each tolerance is solved as measure.py solves it (3 repeats, median CPU), with
mesh_warm_multipliers=false: the primal-only start every other row of that run had (it predates
multiplier warm starts). The error is against the reference value that run recorded for the
problem (goddard, robot-arm) or the record's own reference. rows.jsonl is rewritten in place,
each re-run row marked "rerun": true.
"""
import json
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import measure  # noqa: E402


def main(ocpbench, problem, scheme, tolerances):
    rows_path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "rows.jsonl")
    with open(rows_path) as f:
        rows = [json.loads(line) for line in f]
    reference = next((r["value"] for r in rows
                      if r.get("problem") == problem and r.get("kind") == "reference"), None)
    with tempfile.TemporaryDirectory() as out:
        for tol in tolerances:
            r, _ = measure.solve(ocpbench, out, f"{problem}-{scheme}-tol{tol:g}", problem, scheme,
                                 10, [f"mesh_tolerance={tol:g}", "mesh_max_iterations=30",
                                      "mesh_max_nodes=20000", "mesh_warm_multipliers=false"])
            J = reference if reference is not None else r["reference"]["value"] if r else None
            row = dict(problem=problem, scheme=scheme, kind="refined", tolerance=tol,
                       **measure.outcome(r, J), rerun=True)
            print(json.dumps(row), flush=True)
            for i, old in enumerate(rows):
                if (old.get("problem"), old.get("scheme"), old.get("kind"),
                        old.get("tolerance")) == (problem, scheme, "refined", tol):
                    rows[i] = row
    with open(rows_path, "w") as f:
        for r in rows:
            f.write(json.dumps(r) + "\n")


if __name__ == "__main__":
    if len(sys.argv) < 5:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2], sys.argv[3], [float(t) for t in sys.argv[4:]])
