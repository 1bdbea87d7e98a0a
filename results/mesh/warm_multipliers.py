#!/usr/bin/python3
"""Multiplier warm starts across meshes: Ipopt iterations and CPU on the 2nd.. meshes, with and
without them, in one run.

Usage: /usr/bin/python3 results/mesh/warm_multipliers.py OCPBENCH > results/mesh/warm-multipliers.md

Cases: the corner problems of results/mesh/summary.md and one smooth problem (vanderpol), each
with Hermite-Simpson (h) and LGR (ph, K = 3 to start), refined from N = 10 at the
mesh_tolerance results/mesh/summary.md chose for it (goddard with Hermite-Simpson: 1e-6, the
loosest, where every tolerance failed there), mesh_max_iterations = 30, mesh_max_nodes = 20000,
hard terminal form. Two Ipopt settings: results/mesh's (tol = 1e-11, bound_relax_factor = 0) and
Ipopt's defaults (tol = 1e-8). Each case is solved with mesh_warm_multipliers=false (primal
start: controls and states) and =true (the same plus the mapped multipliers, Ipopt's warm start
with OCPBench's warm_start_* defaults), REPEATS times each, alternating, all in this one run.
Iterations are deterministic (the same in every repeat); CPU is the median over the repeats of
the sum of the mesh history's per-mesh CPU seconds (transcription and Ipopt) of meshes 2, 3, ...
Sweeps of warm_start_mu_init, warm_start_bound_push and warm_start_mult_bound_push, one at a
time with the others at their defaults (one run each, results/mesh's Ipopt setting, iterations
only), show how the defaults were chosen.
Every solve's outcome goes to OUT (default results/mesh/warm-multipliers.jsonl).
"""
import json
import os
import statistics
import subprocess
import sys
import tempfile

CASES = [
    ("bryson-denham", "hermite-simpson", 1e-6),
    ("bryson-denham", "lgr", 1e-11),
    ("double-integrator-bounded", "hermite-simpson", 1e-6),
    ("double-integrator-bounded", "lgr", 1e-8),
    ("goddard", "hermite-simpson", 1e-6),
    ("goddard", "lgr", 1e-7),
    ("robot-arm", "hermite-simpson", 1e-7),
    ("robot-arm", "lgr", 1e-7),
    ("vanderpol", "hermite-simpson", 1e-8),
    ("vanderpol", "lgr", 1e-6),
]
SETTINGS = {
    "results/mesh's (tol 1e-11, bound_relax_factor 0)": ["tol=1e-11", "bound_relax_factor=0"],
    "Ipopt's defaults (tol 1e-8)": [],
}
SWEEPS = {
    "warm_start_mu_init": ["1e-6", "1e-8", "1e-10", "1e-12", "1e-14"],
    "warm_start_bound_push": ["1e-9", "1e-6", "1e-3"],
    "warm_start_mult_bound_push": ["1e-9", "1e-6", "1e-3"],
}
REPEATS = 3


def solve(ocpbench, workdir, problem, scheme, tol, ipopt, extra):
    path = os.path.join(workdir, "record.json")
    if os.path.exists(path):
        os.remove(path)
    args = [ocpbench, "solve", "--problem", problem, "--solver", "ipopt", "--transcription",
            scheme, "--terminal", "hard", "--N", "10", "--json", path,
            "--option", f"mesh_tolerance={tol:g}", "--option", "mesh_max_iterations=30",
            "--option", "mesh_max_nodes=20000"]
    for o in ipopt + extra:
        args += ["--option", o]
    run = subprocess.run(args, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if run.returncode not in (0, 1) or not os.path.exists(path):
        return {"status": "no record", "error": run.stderr.strip()[-300:]}
    with open(path) as f:
        r = json.load(f)
    history = r["mesh"]["history"]
    return {
        "status": r["status"],
        "stop_reason": r["mesh"]["stop_reason"],
        "meshes": len(history),
        "iterations": [h["iterations"] for h in history],
        "cpu": [h["cpu_seconds"] for h in history],
        "cpu_seconds": r["cpu_seconds"],
        "objective": r["objective"],
        "multiplier_starts": r["solver_stats"].get("mesh_multiplier_starts"),
    }


def later(row, key):
    """The sum over meshes 2, 3, ...; None when there is no second mesh."""
    return sum(row[key][1:]) if row.get(key) and len(row[key]) > 1 else None


def loadavg():
    with open("/proc/loadavg") as f:
        return f.read().split()[0]


def main(ocpbench, out):
    log = open(out, "w")
    load_start = loadavg()
    tables = []
    with tempfile.TemporaryDirectory() as workdir:
        for setting, ipopt in SETTINGS.items():
            rows = []
            for problem, scheme, tol in CASES:
                runs = {"primal": [], "warm": []}
                for _ in range(REPEATS):
                    for mode, flag in (("primal", "false"), ("warm", "true")):
                        r = solve(ocpbench, workdir, problem, scheme, tol, ipopt,
                                  [f"mesh_warm_multipliers={flag}"])
                        r.update(setting=setting, problem=problem, scheme=scheme, tolerance=tol,
                                 mode=mode)
                        log.write(json.dumps(r) + "\n")
                        log.flush()
                        runs[mode].append(r)
                rows.append((problem, scheme, tol, runs))
            tables.append((setting, rows))
        sweeps = {}
        ipopt = SETTINGS["results/mesh's (tol 1e-11, bound_relax_factor 0)"]
        for option, values in SWEEPS.items():
            sweep = []
            for problem, scheme, tol in CASES:
                counts = []
                for value in values:
                    r = solve(ocpbench, workdir, problem, scheme, tol, ipopt,
                              ["mesh_warm_multipliers=true", f"{option}={value}"])
                    r.update(setting="sweep", problem=problem, scheme=scheme, tolerance=tol,
                             mode="warm", sweep_option=option, sweep_value=value)
                    log.write(json.dumps(r) + "\n")
                    log.flush()
                    counts.append(r)
                sweep.append((problem, scheme, counts))
            sweeps[option] = sweep
    log.close()
    print_report(tables, sweeps, load_start, loadavg())


def summary(runs):
    """Status, meshes, iterations on meshes 2.. and the median CPU of meshes 2.. over the runs."""
    first = runs[0]
    if first.get("iterations") is None:
        return first["status"], None, None, None, None
    whole = statistics.median(r["cpu_seconds"] for r in runs)
    if later(first, "iterations") is None:
        return first["status"], first["meshes"], None, None, whole
    cpu = statistics.median(later(r, "cpu") for r in runs)
    return first["status"], first["meshes"], later(first, "iterations"), cpu, whole


def fmt(x, spec):
    return "-" if x is None else format(x, spec)


def ratio(a, b):
    return "-" if a is None or b is None or b == 0 else f"{a / b:.2f}"


def print_report(tables, sweeps, load_start, load_end):
    print("# Multiplier warm starts across meshes\n")
    print("Written by `results/mesh/warm_multipliers.py` (its docstring states the protocol; "
          f"every row in one run, {REPEATS} alternating repeats per case and mode; machine load "
          f"{load_start} at the start, {load_end} at the end, 2 cores). Primal: each refined mesh "
          "starts from the previous solution's controls and states (`mesh_warm_multipliers="
          "false`); warm: the same plus its multipliers mapped to the new mesh (Ipopt's warm "
          "start, the default). Iterations and CPU are those of meshes 2, 3, ... (the first "
          "mesh is the same cold solve in both); CPU the median of the repeats, seconds "
          "(transcription and Ipopt per mesh). Ratios primal / warm: above 1, the warm start is "
          "better. The two columns' meshes can differ where the solves differ (different "
          "iterates give different estimates), so the meshes column is part of the result.\n")
    for setting, rows in tables:
        print(f"## Ipopt: {setting}\n")
        print("| problem | scheme | mesh_tolerance | primal: status, meshes, iterations, CPU s | "
              "warm: status, meshes, iterations, CPU s | iteration ratio | CPU ratio (meshes "
              "2..) | CPU ratio (whole solve) |")
        print("|---|---|---|---|---|---|---|---|")
        totals = {"primal": [0, 0.0], "warm": [0, 0.0]}
        for problem, scheme, tol, runs in rows:
            p = summary(runs["primal"])
            w = summary(runs["warm"])
            # Totals over the rows where both modes solved a second mesh.
            if p[2] is not None and w[2] is not None:
                for mode, s in (("primal", p), ("warm", w)):
                    totals[mode][0] += s[2]
                    totals[mode][1] += s[3]
            print(f"| {problem} | {scheme} | {tol:g} | {p[0]}, {fmt(p[1], 'd')}, "
                  f"{fmt(p[2], 'd')}, {fmt(p[3], '.4f')} | {w[0]}, {fmt(w[1], 'd')}, "
                  f"{fmt(w[2], 'd')}, {fmt(w[3], '.4f')} | {ratio(p[2], w[2])} | "
                  f"{ratio(p[3], w[3])} | {ratio(p[4], w[4])} |")
        print(f"| all (rows with a 2nd mesh in both) | | | {totals['primal'][0]} iterations, "
              f"{totals['primal'][1]:.3f} s | "
              f"{totals['warm'][0]} iterations, {totals['warm'][1]:.3f} s | "
              f"{ratio(totals['primal'][0], totals['warm'][0])} | "
              f"{ratio(totals['primal'][1], totals['warm'][1])} | |\n")
    for option, sweep in sweeps.items():
        values = SWEEPS[option]
        print(f"## {option} (the others at their defaults; results/mesh's Ipopt setting, one "
              "run each): iterations on meshes 2.. (status, meshes)\n")
        print("| problem | scheme | " + " | ".join(values) + " |")
        print("|---|---|" + "---|" * len(values))
        totals = [0] * len(values)
        for problem, scheme, counts in sweep:
            cells = []
            for i, r in enumerate(counts):
                it = later(r, "iterations")
                if it is None:
                    cells.append(r["status"])
                    continue
                totals[i] += it
                cells.append(f"{it} ({r['status']}, {r['meshes']} meshes)")
            print(f"| {problem} | {scheme} | " + " | ".join(cells) + " |")
        print("| all | | " + " | ".join(str(t) for t in totals) + " |\n")

if __name__ == "__main__":
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    here = os.path.dirname(os.path.abspath(__file__))
    main(sys.argv[1], sys.argv[2] if len(sys.argv) == 3 else
         os.path.join(here, "warm-multipliers.jsonl"))
