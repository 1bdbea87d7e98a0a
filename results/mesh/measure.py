#!/usr/bin/python3
"""Adaptive mesh refinement against uniform grids, every reference problem, in one run.

Usage: /usr/bin/python3 results/mesh/measure.py OCPBENCH OUT_DIR > results/mesh/summary.md

For each reference problem and scheme (Hermite-Simpson: h-refinement; LGR with K = 3 points
per interval to start: ph-refinement), Ipopt with tol = 1e-11 and bound_relax_factor = 0 (with
Ipopt's default 1e-8 relaxation of the bounds the cost error stalls near 1e-8: bryson-denham at
9.0e-8 = the relaxed x1 <= 1/9, double-integrator-bounded at 1.0e-8), hard terminal form:

  - uniform: N = 10, 20, 40, ... (a doubling sequence, at most 2560 intervals for
    Hermite-Simpson and 1280 for LGR: comparable NLP sizes), the first N whose error is <= the
    problem's target;
  - refined: from N = 10 (LGR: degree 3), mesh_tolerance = 1e-6, 1e-7, ..., 1e-12 (the scheme's
    own estimate, mesh_max_iterations = 30, mesh_max_nodes = 20000), the first tolerance whose
    error is <= the target.

error = |Jbar_fine - J*| / |J*|: the common evaluator's RK4 re-simulation of the method's
controls on its final grid refined 10 times, against the published continuous optimum.
goddard and robot-arm have only COPS' discrete optima: their J* here is this run's own
reference solve (LGR ph-refined with the simulation estimate to mesh_tolerance 1e-10, a
configuration neither row uses), and their error is the distance to it.

Every solve is timed over 3 repeats (median CPU); each row's CPU is that of its one solve on the
chosen grid or tolerance (the searches along the sequences are not counted, for either side).
Every solve's outcome is kept in OUT_DIR/rows.jsonl; the records of the two figure cases are
copied to results/mesh (refined-hs.json, refined-lgr.json).
"""
import json
import os
import shutil
import subprocess
import sys

# (problem, target relative error, why the target is not 1e-8 where it is not).
PROBLEMS = [
    ("double-integrator", 1e-8, ""),
    ("double-integrator-bounded", 1e-8, ""),
    ("bryson-denham", 1e-8, ""),
    ("lqr", 1e-8, ""),
    ("hager", 1e-8, ""),
    ("vanderpol", 1e-8, ""),
    ("rayleigh", 1e-7, "J* = 44.8044433 is published to 9 digits and the PMP-BVP value "
                       "44.80444491 differs by 3.6e-8"),
    ("brachistochrone", 1e-8, ""),
    ("zermelo", 1e-8, ""),
    ("steering", 1e-8, ""),
    ("double-integrator-free-time", 1e-8, ""),
    ("brachistochrone-free-time", 1e-8, ""),
    ("goddard", 1e-7, "no continuous optimum is published (COPS: a discrete one); error against "
                      "this run's own reference solve, whose accuracy is not known better"),
    ("robot-arm", 1e-7, "as goddard"),
]
SELF_REFERENCE = {"goddard", "robot-arm"}
SCHEMES = {"hermite-simpson": 2560, "lgr": 1280}
TOLERANCES = [1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12]
IPOPT = ["tol=1e-11", "bound_relax_factor=0"]
REPEATS = 3


def solve(ocpbench, out, name, problem, scheme, N, options, repeats=REPEATS):
    path = os.path.join(out, name + ".json")
    args = [ocpbench, "solve", "--problem", problem, "--solver", "ipopt", "--transcription",
            scheme, "--terminal", "hard", "--N", str(N), "--repeats", str(repeats), "--json", path]
    for o in IPOPT + options:
        args += ["--option", o]
    run = subprocess.run(args, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    # Exit code 1: the solve ended with a failure status, whose record is kept (and reported).
    if run.returncode not in (0, 1) or not os.path.exists(path):
        return None, path
    with open(path) as f:
        return json.load(f), path


def outcome(r, reference):
    """The row of one record: error (None when the solve did not succeed), size, CPU."""
    ok = r is not None and r["status"] in ("converged", "acceptable")
    mesh = r.get("mesh") if r else None
    last = mesh["history"][-1] if mesh else None
    row = {
        "status": r["status"] if r else "no record",
        "error": abs(r["Jbar_fine"] - reference) / abs(reference)
        if ok and r.get("Jbar_fine") is not None else None,
        "nlp_variables": int(last["nlp_variables"] if last else r["solver_stats"]["nlp_variables"])
        if r else None,
        "cpu_seconds": r["cpu_seconds"] if r else None,
        "iterations": r["iterations"] if r else None,
    }
    if mesh:
        row.update({"meshes": len(mesh["history"]), "stop_reason": mesh["stop_reason"],
                    "intervals": last["intervals"], "degrees": last.get("degrees")})
    return row


def main(ocpbench, out):
    os.makedirs(out, exist_ok=True)
    rows = []
    log = open(os.path.join(out, "rows.jsonl"), "w")

    def keep(row):
        rows.append(row)
        log.write(json.dumps(row) + "\n")
        log.flush()

    summary = []
    # OCPB_MESH_PROBLEMS=a,b restricts the run to those problems (for a quick check).
    only = [p for p in os.environ.get("OCPB_MESH_PROBLEMS", "").split(",") if p]
    for problem, target, why in PROBLEMS:
        if only and problem not in only:
            continue
        reference = None
        if problem in SELF_REFERENCE:
            r, _ = solve(ocpbench, out, problem + "-reference", problem, "lgr", 10,
                         ["mesh_tolerance=1e-10", "mesh_estimate=simulation",
                          "mesh_max_iterations=40", "mesh_max_nodes=20000"], repeats=1)
            reference = r["Jbar_fine"] if r and r["status"] in ("converged", "acceptable") else None
            keep({"problem": problem, "kind": "reference", "status": r["status"] if r else None,
                  "value": reference})
            if reference is None:
                summary.append((problem, None, target, why, None, None))
                continue
        for scheme, max_N in SCHEMES.items():
            uniform = None
            N = 10
            while N <= max_N:
                r, _ = solve(ocpbench, out, f"{problem}-{scheme}-{N}", problem, scheme, N, [])
                J = reference if reference is not None else r["reference"]["value"] if r else None
                row = dict(problem=problem, scheme=scheme, kind="uniform", N=N,
                           **outcome(r, J) if J is not None else {"status": "no record"})
                keep(row)
                if row.get("error") is not None and row["error"] <= target:
                    uniform = row
                    break
                N *= 2
            refined = None
            for tol in TOLERANCES:
                name = f"{problem}-{scheme}-tol{tol:g}"
                r, path = solve(ocpbench, out, name, problem, scheme, 10,
                                [f"mesh_tolerance={tol:g}", "mesh_max_iterations=30",
                                 "mesh_max_nodes=20000"])
                J = reference if reference is not None else r["reference"]["value"] if r else None
                row = dict(problem=problem, scheme=scheme, kind="refined", tolerance=tol,
                           **outcome(r, J) if J is not None else {"status": "no record"})
                keep(row)
                if row.get("error") is not None and row["error"] <= target:
                    refined = row
                    if problem == "double-integrator-bounded":
                        figure = "refined-hs.json" if scheme == "hermite-simpson" else "refined-lgr.json"
                        shutil.copy(path, os.path.join(os.path.dirname(__file__), figure))
                    break
            summary.append((problem, scheme, target, why, uniform, refined))
    log.close()
    ROWS.extend(rows)
    print_summary(summary)


def fmt(x, spec):
    return "-" if x is None else format(x, spec)


ROWS = []


def best(problem, scheme, kind):
    """The smallest error of a sequence that never reached its target, with where."""
    mine = [r for r in ROWS if r.get("problem") == problem and r.get("scheme") == scheme
            and r.get("kind") == kind and r.get("error") is not None]
    if not mine:
        return "no successful solve"
    r = min(mine, key=lambda r: r["error"])
    where = f"N = {r['N']}" if kind == "uniform" else f"mesh_tolerance {r['tolerance']:g}"
    return f"{r['error']:.1e} at {where} ({r['nlp_variables']} variables)"


def print_summary(summary):
    print("# Adaptive mesh refinement against uniform grids, every reference problem\n")
    print("Written by `results/mesh/measure.sh` (`measure.py`: every row in one run; its "
          "docstring states the protocol). Ipopt tol = 1e-11, bound_relax_factor = 0, hard "
          "terminal form; error = |Jbar_fine - J*| / |J*| (the common evaluator's fine RK4 "
          "re-simulation); uniform: the first N of 10, 20, 40, ... (Hermite-Simpson up to 2560, "
          "LGR with K = 3 up to 1280) with error <= the target; refined: from N = 10 (LGR K = 3), "
          "the first mesh_tolerance of 1e-6 ... 1e-12 with error <= the target; CPU: median of 3 "
          "repeats of that one solve (the searches not counted on either side). Ratios are "
          "uniform / refined: above 1, refinement is smaller or faster.\n")
    print("| problem | scheme | target | refined: mesh_tolerance, meshes, final intervals "
          "(degrees) | refined: NLP variables, error, CPU s | uniform: N, NLP variables, error, "
          "CPU s | size ratio | CPU ratio |")
    print("|---|---|---|---|---|---|---|---|")
    notes = []
    for problem, scheme, target, why, uniform, refined in summary:
        if why and (problem, why) not in notes:
            notes.append((problem, why))
        if scheme is None:
            print(f"| {problem} | - | {target:g} | reference solve failed | - | - | - | - |")
            continue
        if refined:
            deg = refined.get("degrees")
            degs = f", degrees {min(deg)}..{max(deg)}" if deg else ""
            ref_mesh = (f"{refined['tolerance']:g}, {refined['meshes']} meshes "
                        f"({refined['stop_reason']}), {refined['intervals']}{degs}")
            ref_cost = (f"{refined['nlp_variables']}, {fmt(refined['error'], '.1e')}, "
                        f"{fmt(refined['cpu_seconds'], '.4f')}")
        else:
            ref_mesh, ref_cost = "not reached by 1e-12", "best: " + best(problem, scheme, "refined")
        if uniform:
            uni = (f"{uniform['N']}, {uniform['nlp_variables']}, {fmt(uniform['error'], '.1e')}, "
                   f"{fmt(uniform['cpu_seconds'], '.4f')}")
        else:
            uni = "not reached by the largest N; best: " + best(problem, scheme, "uniform")
        size = cpu = "-"
        if refined and uniform:
            size = f"{uniform['nlp_variables'] / refined['nlp_variables']:.1f}"
            cpu = f"{uniform['cpu_seconds'] / refined['cpu_seconds']:.1f}"
        print(f"| {problem} | {scheme} | {target:g} | {ref_mesh} | {ref_cost} | {uni} | {size} "
              f"| {cpu} |")
    if notes:
        print("\nTargets other than 1e-8:\n")
        for problem, why in notes:
            print(f"- {problem}: {why}.")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
