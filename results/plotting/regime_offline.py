#!/usr/bin/python3
"""The offline part of the regime study (issue 22): when does co-optimizing the path pay?

    /usr/bin/python3 results/plotting/regime_offline.py [DIR]

DIR (default results/regime-offline) holds records.jsonl of `ocpbench run` on a suite written
by bench/suites/make_regime_offline.py (the main job's small one: results/regime). Writes to DIR:

  regime.md                    per (c, gamma): seeds, then median [10 %, 90 %] over channel seeds
                               of the energy the co-optimized path saves on the true channel
                               against the best plan on the straight segment S-D and against the
                               naive plan, the segment plan's own saving against the naive one,
                               the co-optimized path's largest distance from S-D and its closest
                               approach to the base station, and the transmission share
  cpu.md                       per (problem, method, gamma): cases, converged, median [10 %, 90 %]
                               CPU seconds, median iterations, statuses
  fig_offline_saving.png       the two savings against gamma, one curve per c, 10-90 % bands
  fig_offline_geometry.png     distance from S-D and closest approach to the base, the same way

The plans of one (gamma, c, seed): "path" = comm-path2d, "segment" = comm-fixed-path (the
straight segment as its path), "naive" = comm-path2d with the baseline method. Where a plan was
solved by several methods (Ipopt + Euler, hamiltonian-polish), the one taken is the feasible solve
(terminal violation <= 1e-6, whatever its status: a plan a user can execute) with the lowest
*predicted* energy (the record's Jbar, on the channel the planner knew): the choice a user can
make without the truth. Its energy on the true channel (energy_true) is what is compared.
Saving = 1 - E_path / E_other (> 0: the co-optimized path spent less). cpu.md counts, per method,
the seeds on which it found that plan (predicted energy within 1e-5 relative: Ipopt's default tol
leaves about 1e-6). Needs numpy and matplotlib only.
"""

import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from figure_io import save_figure  # noqa: E402
from records_io import load_records  # noqa: E402


def finite(x):
    return isinstance(x, (int, float)) and math.isfinite(x)


def plan_of(r):
    if r["problem"] == "comm-path2d":
        return "naive" if r["solver"] == "baseline" else "path"
    if r["problem"] == "comm-fixed-path":
        return "segment"
    return None


def method_of(r):
    return r["solver"] + (" + " + r["transcription"] if r.get("transcription") else "")


def quantiles(values):
    v = np.asarray(values, dtype=float)
    return np.median(v), np.quantile(v, 0.1), np.quantile(v, 0.9)


def fmt_q(q, spec="%.3g"):
    return (spec + " [" + spec + ", " + spec + "]") % q


FEASIBLE = 1e-6  # terminal violation of a usable plan (hard form: every converged solve < 1e-6)
SAME_OPTIMUM = 1e-5  # relative: Ipopt's default tol leaves about 1e-6 in the energy (README)


def feasible(r):
    return (finite(r.get("terminal_violation")) and r["terminal_violation"] <= FEASIBLE
            and finite(r.get("energy_true")) and finite(r.get("Jbar")))


def choose(records):
    """The feasible record with the lowest predicted energy (Jbar), or None."""
    ok = [r for r in records if feasible(r)]
    return min(ok, key=lambda r: r["Jbar"]) if ok else None


def main():
    folder = sys.argv[1] if len(sys.argv) > 1 else "results/regime-offline"
    records = load_records(os.path.join(folder, "records.jsonl"))
    by_point = {}
    for r in records:
        plan = plan_of(r)
        if plan is None:
            continue
        p = r["parameters"]
        key = (float(p["c"]), float(p["gamma"]), int(r["seed"]))
        by_point.setdefault(key, {}).setdefault(plan, []).append(r)

    cells = {}
    missing = {}
    for (c, gamma, seed), plans in by_point.items():
        chosen = {name: choose(rs) for name, rs in plans.items()}
        if any(chosen.get(name) is None for name in ("path", "segment", "naive")):
            missing[(c, gamma)] = missing.get((c, gamma), 0) + 1
            continue
        path, seg, naive = chosen["path"], chosen["segment"], chosen["naive"]
        cells.setdefault((c, gamma), []).append({
            "vs_segment": 1 - path["energy_true"] / seg["energy_true"],
            "vs_naive": 1 - path["energy_true"] / naive["energy_true"],
            "segment_vs_naive": 1 - seg["energy_true"] / naive["energy_true"],
            "saved_J": seg["energy_true"] - path["energy_true"],
            "distance": path["max_distance_from_segment"],
            "base": path["min_distance_to_base"],
            "segment_base": seg["min_distance_to_base"],
            "share": path["transmit_energy_true"] / path["energy_true"],
            "segment_share": seg["transmit_energy_true"] / seg["energy_true"],
            "path_method": "%s (%s)" % (method_of(path), path["status"]),
        })

    lines = [
        "# When does co-optimizing the path pay? (issue 22, offline)",
        "",
        "Generated by `results/plotting/regime_offline.py` from `records.jsonl` "
        "(%d records); do not edit. Per channel seed: the co-optimized path (comm-path2d), the "
        "best plan on the straight segment S-D (comm-fixed-path: speed and rate optimized, path "
        "fixed) and the naive plan (baseline: constant speed along S-D, constant rate), each "
        "judged on the true simulated channel; of several methods, the feasible solve (terminal "
        "violation <= 1e-6) with the lowest predicted energy. Saving = 1 - E_path / E_other. "
        "Median [10 %%, 90 %%] over seeds." % len(records),
        "",
        "| c (bits/Hz) | gamma | seeds | saving vs segment | saved J vs segment | saving vs naive "
        "| segment vs naive | max distance from S-D (m) | closest to base (m; segment: %s) "
        "| transmission share (path / segment) | path solved by |" % "min",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    curves = {}
    for (c, gamma) in sorted(cells, key=lambda k: (k[0], -k[1])):
        rows = cells[(c, gamma)]
        q = {k: quantiles([row[k] for row in rows])
             for k in ("vs_segment", "saved_J", "vs_naive", "segment_vs_naive", "distance",
                       "base", "share", "segment_share")}
        methods = {}
        for row in rows:
            methods[row["path_method"]] = methods.get(row["path_method"], 0) + 1
        seg_base = min(row["segment_base"] for row in rows)
        note = "" if (c, gamma) not in missing else " (+%d without all plans)" % missing[(c, gamma)]
        lines.append(
            "| %g | %g | %d%s | %s | %s | %s | %s | %s | %s (%.3g) | %.2g / %.2g | %s |" % (
                c, gamma, len(rows), note, fmt_q(q["vs_segment"]), fmt_q(q["saved_J"]),
                fmt_q(q["vs_naive"]), fmt_q(q["segment_vs_naive"]), fmt_q(q["distance"]),
                fmt_q(q["base"]), seg_base, q["share"][0], q["segment_share"][0],
                ", ".join("%s %d" % kv for kv in sorted(methods.items()))))
        curves.setdefault(c, []).append((gamma, q))
    for key, n in sorted(missing.items()):
        if key not in cells:
            lines.append("| %g | %g | 0 (+%d without all plans) | | | | | | | | |" % (*key, n))
    with open(os.path.join(folder, "regime.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    write_cpu_table(folder, records)

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib missing: wrote %s/regime.md and cpu.md only" % folder)
        return
    panels = [
        (("vs_segment", "co-optimized path vs best plan on segment S-D", "energy saved (%)", 100),
         ("vs_naive", "co-optimized path vs naive plan", "energy saved (%)", 100)),
        (("distance", "co-optimized path: largest distance from S-D", "m", 1),
         ("base", "co-optimized path: closest approach to the base", "m", 1)),
    ]
    for name, pair in zip(("fig_offline_saving.png", "fig_offline_geometry.png"), panels):
        fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
        for ax, (key, title, unit, scale) in zip(axes, pair):
            for c, pts in sorted(curves.items()):
                pts.sort(key=lambda p: p[0])
                gam = [p[0] for p in pts]
                med = [scale * p[1][key][0] for p in pts]
                lo = [scale * p[1][key][1] for p in pts]
                hi = [scale * p[1][key][2] for p in pts]
                ax.plot(gam, med, marker="o", label="c = %g bits/Hz" % c)
                ax.fill_between(gam, lo, hi, alpha=0.2)
            ax.set_xscale("log")
            if scale == 100:
                ax.set_yscale("symlog", linthresh=1e-4)
                ax.axhline(0.0, color="k", lw=0.5)
            ax.set_xlabel("gamma (weight of motion)")
            ax.set_ylabel(unit)
            ax.set_title(title, fontsize=10)
            ax.grid(True, which="both", alpha=0.3)
            ax.legend(fontsize=8)
        fig.suptitle("true simulated channel, median and 10-90 %% band over %d channel seeds"
                     % max(len(v) for v in cells.values()) if cells else "", fontsize=9)
        fig.tight_layout()
        save_figure(fig, os.path.join(folder, name), dpi=120)
        plt.close(fig)
    print("wrote %s/regime.md, cpu.md and the figures (%d points)"
          % (folder, sum(len(v) for v in cells.values())))


def write_cpu_table(folder, records):
    # The best plan found per (problem and plan kind, c, gamma, seed): its predicted energy.
    best = {}
    for r in records:
        if not feasible(r):
            continue
        p = r["parameters"]
        k = (r["problem"], plan_of(r), p["c"], p["gamma"], r["seed"])
        best[k] = min(best.get(k, math.inf), r["Jbar"])
    groups = {}
    for r in records:
        key = (r["problem"], method_of(r), float(r["parameters"]["gamma"]))
        groups.setdefault(key, []).append(r)
    lines = [
        "# CPU per method and gamma (issue 22, offline)",
        "",
        "Generated by `results/plotting/regime_offline.py`; do not edit. CPU seconds of the "
        "solve (median [10 %, 90 %] over the cases: seeds x c), median iterations, and the "
        "statuses; \"best plan\": the cases in which the method's plan is feasible (terminal "
        "violation <= 1e-6) and its predicted energy within 1e-5 relative of the best any "
        "method found for that problem, c, gamma and seed. The hard terminal form, N = 400.",
        "",
        "| problem | method | gamma | cases | converged | best plan | CPU s | iterations | "
        "statuses |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for (problem, method, gamma) in sorted(groups, key=lambda k: (k[0], k[1], -k[2])):
        rs = groups[(problem, method, gamma)]
        cpu = [r["cpu_seconds"] for r in rs if finite(r.get("cpu_seconds"))]
        its = [r["iterations"] for r in rs if isinstance(r.get("iterations"), int)]
        statuses = {}
        reached = 0
        for r in rs:
            statuses[r["status"]] = statuses.get(r["status"], 0) + 1
            p = r["parameters"]
            b = best.get((r["problem"], plan_of(r), p["c"], p["gamma"], r["seed"]))
            if feasible(r) and b is not None and r["Jbar"] <= b + SAME_OPTIMUM * abs(b):
                reached += 1
        lines.append("| %s | %s | %g | %d | %d | %d | %s | %s | %s |" % (
            problem, method, gamma, len(rs), statuses.get("converged", 0), reached,
            fmt_q(quantiles(cpu)) if cpu else "", "%g" % np.median(its) if its else "",
            ", ".join("%s %d" % kv for kv in sorted(statuses.items()))))
    with open(os.path.join(folder, "cpu.md"), "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
