#!/usr/bin/python3
"""Figures of online re-planning with channel updates (paper Section IV, Figs. 11-12), from the
records of `ocpbench online --json FILE` or of a suite with entries of kind "online".

Usage:
  /usr/bin/python3 results/plotting/online_figures.py RECORD.json|records.jsonl [...] --out DIR

Fields read (records of kind "online"; others are skipped):
  solver, seed, parameters.S/.D/.base, cycles[i].t0, cycles[i].plan {t, x: 2 rows},
  executed.x / offline.x (5 rows), measurements {x, y, cycle}, s_map {x, y, log10_s,
  log10_s_predicted}, energy_true, offline_energy_true, energy_ratio.
Writes, per record with trajectories (<prefix> = online-<solver>-seed<seed>):
  <prefix>-fig11-plans.png             each cycle's plan from its t0 to tf over log10 s (true
                                       channel), measurements by cycle             (paper Fig. 11)
  <prefix>-fig12-offline-vs-online.png the executed offline and online paths over log10 s (Fig. 12)
and, for two or more records, online-energy-ratio.png: the online/offline ratio of the energy on
the true channel per seed and solver; always online-summary.md: per solver, mean ± sd [min, max]
over the records of the energies, their ratios, terminal violations and per-cycle CPU times.
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from channel_figures import save_figure, write_text  # noqa: E402
from paper_figures import PAPER_BASE, PAPER_D, PAPER_S, _markers, _point  # noqa: E402


def _load(paths):
    records = []
    for p in paths:
        with open(p) as f:
            text = f.read().strip()
        if not text:
            continue
        if text.startswith("{") and "\n{" not in text:
            records.append(json.loads(text))
        else:
            records.extend(json.loads(line) for line in text.splitlines() if line.strip())
    return [r for r in records if r.get("kind") == "online"]


def _background(fig, ax, rec, key="log10_s", label="log10 s, true channel (W)"):
    smap = rec.get("s_map")
    if smap and smap.get(key):
        cs = ax.contourf(smap["x"], smap["y"], smap[key], levels=30, cmap="viridis")
        fig.colorbar(cs, ax=ax, label=label)
    side = rec.get("online", {}).get("workspace", 50.0)
    ax.set_xlim(0, side)
    ax.set_ylim(0, side)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")


def record_figures(rec, outdir):
    if "executed" not in rec:
        return []
    params = rec.get("parameters", {})
    S = _point(params, "S", PAPER_S)
    D = _point(params, "D", PAPER_D)
    base = _point(params, "base", PAPER_BASE)
    prefix = os.path.join(outdir, "online-{}-seed{}".format(rec["solver"], rec["seed"]))
    written = []
    colors = plt.cm.autumn_r
    n = len(rec["cycles"])

    fig, ax = plt.subplots(figsize=(7.5, 6.5))
    _background(fig, ax, rec)
    m = rec.get("measurements")
    for i, c in enumerate(rec["cycles"]):
        col = colors(0.25 + 0.75 * i / max(1, n - 1))
        x = c["plan"]["x"]
        ax.plot(x[0], x[1], "-", color=col, lw=2, label="plan at t0 = {:g} s".format(c["t0"]))
        ax.plot(x[0][0], x[1][0], "o", color=col, ms=6)
        if m:
            mx = [a for a, k in zip(m["x"], m["cycle"]) if k == i]
            my = [b for b, k in zip(m["y"], m["cycle"]) if k == i]
            ax.plot(mx, my, ".", color=col, ms=3)
    _markers(ax, S, D, base)
    ax.legend(loc="upper left", fontsize=8)
    ax.set_title("{} seed {}: plans of each cycle to tf (dots: measurements)".format(
        rec["solver"], rec["seed"]))
    fig.tight_layout()
    path = prefix + "-fig11-plans.png"
    save_figure(fig, path, dpi=120)
    plt.close(fig)
    written.append(path)

    fig, ax = plt.subplots(figsize=(7.5, 6.5))
    _background(fig, ax, rec)
    off, on = rec["offline"]["x"], rec["executed"]["x"]
    ax.plot(off[0], off[1], "b-", lw=2,
            label="offline (t0 = 0): true energy {:.1f}".format(rec["offline_energy_true"]))
    ax.plot(on[0], on[1], "r-", lw=2,
            label="online: true energy {:.1f}".format(rec["energy_true"]))
    _markers(ax, S, D, base)
    ax.legend(loc="upper left", fontsize=8)
    ax.set_title("{} seed {}: offline vs online, online/offline = {:.3f}".format(
        rec["solver"], rec["seed"], rec["energy_ratio"]))
    fig.tight_layout()
    path = prefix + "-fig12-offline-vs-online.png"
    save_figure(fig, path, dpi=120)
    plt.close(fig)
    written.append(path)
    return written


def ratio_figure(records, outdir):
    by_solver = {}
    for r in records:
        if r.get("energy_ratio") is not None:
            by_solver.setdefault(r["solver"], []).append((r["seed"], r["energy_ratio"]))
    if sum(len(v) for v in by_solver.values()) < 2:
        return []
    fig, ax = plt.subplots(figsize=(7, 4))
    for solver, pts in sorted(by_solver.items()):
        pts.sort()
        ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-", label=solver)
    ax.axhline(1.0, color="k", lw=0.8)
    ax.set_xlabel("channel seed")
    ax.set_ylabel("online / offline energy (true channel)")
    ax.legend()
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    path = os.path.join(outdir, "online-energy-ratio.png")
    save_figure(fig, path, dpi=120)
    plt.close(fig)
    return [path]


def _stats(values):
    values = [v for v in values if v is not None]
    if not values:
        return "-"
    n = len(values)
    mean = sum(values) / n
    sd = (sum((v - mean) ** 2 for v in values) / (n - 1)) ** 0.5 if n > 1 else 0.0
    return "{:.6g} ± {:.2g} [{:.6g}, {:.6g}]".format(mean, sd, min(values), max(values))


def summary_table(records):
    """Markdown: per solver, mean ± sd [min, max] over seeds of the online/offline comparison."""
    rows = [
        ("online / offline energy, true channel", lambda r: r.get("energy_ratio")),
        ("online energy, true channel", lambda r: r.get("energy_true")),
        ("offline energy, true channel", lambda r: r.get("offline_energy_true")),
        ("online energy, predicted", lambda r: r.get("energy_predicted")),
        ("offline energy, predicted", lambda r: r.get("offline_energy_predicted")),
        ("online / offline transmission energy, true channel",
         lambda r: r.get("transmit_energy_ratio")),
        ("online transmission energy, true channel", lambda r: r.get("transmit_energy_true")),
        ("offline transmission energy, true channel",
         lambda r: r.get("offline_transmit_energy_true")),
        ("online terminal violation", lambda r: r.get("terminal_violation")),
        ("offline terminal violation", lambda r: r.get("offline_terminal_violation")),
    ]
    cycle_rows = [
        ("predict CPU s per re-plan (cycles >= 1)", "predict_seconds", 1),
        ("solve CPU s per re-plan (cycles >= 1)", "solve_seconds", 1),
        ("iterations per re-plan (cycles >= 1)", "iterations", 1),
        ("solve CPU s of the plan at t0 = 0", "solve_seconds", 0),
        ("predict CPU s at t0 = 0", "predict_seconds", 0),
    ]
    solvers = sorted({r["solver"] for r in records})
    out = ["| quantity | " + " | ".join("{} ({} seeds)".format(
        s, sum(1 for r in records if r["solver"] == s)) for s in solvers) + " |",
        "|---|" + "---|" * len(solvers)]
    for name, get in rows:
        out.append("| {} | {} |".format(name, " | ".join(
            _stats([get(r) for r in records if r["solver"] == s]) for s in solvers)))
    for name, key, first in cycle_rows:
        cells = []
        for s in solvers:
            vals = []
            for r in records:
                if r["solver"] != s:
                    continue
                cyc = r["cycles"][1:] if first == 1 else r["cycles"][:1]
                vals += [c[key] for c in cyc]
            cells.append(_stats(vals))
        out.append("| {} | {} |".format(name, " | ".join(cells)))
    return "\n".join(out) + "\n"


def figures_from_records(records, outdir):
    records = [r for r in records if r.get("kind") == "online"]
    os.makedirs(outdir, exist_ok=True)
    written = []
    for r in records:
        written += record_figures(r, outdir)
    written += ratio_figure(records, outdir)
    if records:
        path = os.path.join(outdir, "online-summary.md")
        write_text(path, summary_table(records))
        written.append(path)
    return written


def main(argv):
    if "--out" not in argv or argv.index("--out") + 1 >= len(argv):
        print(__doc__)
        return 2
    i = argv.index("--out")
    outdir = argv[i + 1]
    paths = argv[:i] + argv[i + 2:]
    for p in figures_from_records(_load(paths), outdir):
        print(p)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
