#!/usr/bin/python3
"""The figures of Ali, Cai, Mostofi and Wardi (ACC 2016), Section III (Figs. 3-9), from OCPBench records.

Usage:
  /usr/bin/python3 results/plotting/paper_figures.py RECORD.json [RECORD.json ...] --out DIR

or, from results/plot.py, figures_from_records(records, outdir) with the records of a suite.

A record is one JSON object as written by `ocpbench solve --json` or by the reproduction program
tests/problems/comm_paper_reproduction.cc. Fields read (all others are ignored):
  problem                 "comm-path2d" (other problems are skipped)
  solver, seed, N         for titles and file names
  parameters.S, .D, .base start, destination and base station (2 numbers each); the paper's
                          (20, 40), (10, 5), (5, 5) when absent
  J, Jbar                 common-evaluator costs, for titles
  history                 [{iteration, J, theta, armijo_j, cpu_seconds}, ...]        (Fig. 3)
  trajectory.t            N+1 grid times
  trajectory.x            5 rows of N+1 values: x1 (2 rows: position), x2 (2 rows: velocity), x3
  trajectory.u            3 rows of N values (piecewise constant): u (2 rows), R
  s_map (optional)        {x: [nx], y: [ny], log10_s: ny rows of nx values} -- log10 s(q) on a
                          grid; without it Fig. 4 shows the path alone.
Writes, per record, into DIR (<prefix> = comm-path2d-<solver>-seed<seed>[-<tag>]):
  <prefix>-fig3-cost.png           J against iteration (log) and its tail     (paper Fig. 3)
  <prefix>-fig4-path.png           path over log10 s, S, D, base station        (Fig. 4)
  <prefix>-fig5-position-time.png  position against time, 3-D                   (Fig. 5)
  <prefix>-fig6-acceleration.png   acceleration arrows along the path           (Fig. 6)
  <prefix>-fig7-speed.png          speed along the path                         (Fig. 7)
  <prefix>-fig8-rate-path.png      spectral efficiency along the path           (Fig. 8)
  <prefix>-fig9-rate-time.png      spectral efficiency against time             (Fig. 9)
  <prefix>-extra-speed-rate-time.png  speed and R against time (not in the paper)
"""
import json
import math
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from mpl_toolkits.mplot3d import Axes3D  # noqa: E402,F401  (registers the 3-D projection)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from figure_io import save_figure  # noqa: E402

PAPER_S, PAPER_D, PAPER_BASE = (20.0, 40.0), (10.0, 5.0), (5.0, 5.0)


def _point(params, key, default):
    v = params.get(key) if params else None
    return (float(v[0]), float(v[1])) if isinstance(v, list) and len(v) == 2 else default


def _markers(ax, S, D, base, z=None):
    """The paper's markers: start as a square, end as a diamond; the base station as a triangle."""
    if z is None:
        ax.plot(*S, "ks", ms=9, label="start S")
        ax.plot(*D, "kD", ms=8, label="destination D")
        ax.plot(*base, "k^", ms=9, label="base station")
    else:
        ax.plot([S[0]], [S[1]], [z], "ks", ms=8, label="start S")
        ax.plot([D[0]], [D[1]], [z], "kD", ms=7, label="destination D")
        ax.plot([base[0]], [base[1]], [z], "k^", ms=8, label="base station")


def _stems(ax, px, py, values, color, label):
    """Values drawn as vertical stems over the path (the paper's Figs. 7-8 style)."""
    ax.plot(px, py, [0.0] * len(px), "o", color="red", ms=2, label="path")
    step = max(1, len(px) // 80)
    for i in range(0, len(px), step):
        ax.plot([px[i], px[i]], [py[i], py[i]], [0.0, values[i]], color=color, lw=1.0)
    ax.plot(px[::step], py[::step], values[::step], "o", color=color, ms=2.5, label=label)


def record_figures(rec, outdir, tag=""):
    """Writes Figs. 3-10 for one comm-path2d record; returns the list of files written."""
    if rec.get("problem") != "comm-path2d" or not rec.get("trajectory"):
        return []
    os.makedirs(outdir, exist_ok=True)
    params = rec.get("parameters", {})
    S = _point(params, "S", PAPER_S)
    D = _point(params, "D", PAPER_D)
    base = _point(params, "base", PAPER_BASE)
    traj = rec["trajectory"]
    t = traj["t"]
    x = traj["x"]
    u = traj["u"]
    px, py, vx, vy, bits = x[0], x[1], x[2], x[3], x[4]
    ax_, ay_, rate = u[0], u[1], u[2]
    n = len(rate)
    speed = [math.hypot(vx[k], vy[k]) for k in range(len(vx))]
    prefix = "comm-path2d-%s-seed%s%s" % (rec.get("solver", "method"), rec.get("seed", "?"),
                                         "-" + tag if tag else "")
    title = "%s, seed %s: J = %s, Jbar = %s" % (
        rec.get("solver", ""), rec.get("seed", "?"),
        "%.2f" % rec["J"] if rec.get("J") is not None else "n/a",
        "%.2f" % rec["Jbar"] if rec.get("Jbar") is not None else "n/a")
    files = []

    def save(fig, name):
        path = os.path.join(outdir, "%s-%s.png" % (prefix, name))
        save_figure(fig, path, dpi=120, bbox_inches="tight")
        plt.close(fig)
        files.append(path)

    # Fig. 3: cost against iteration (log), and the tail from iteration 20 on.
    hist = [h for h in rec.get("history", []) if h.get("J") is not None]
    if hist:
        fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4))
        it = [h["iteration"] for h in hist]
        J = [h["J"] for h in hist]
        a1.semilogy(it, J, "b.-", ms=3)
        a1.set_xlabel("iteration")
        a1.set_ylabel("J")
        a1.set_title("cost against iteration")
        a1.grid(True, which="both", alpha=0.3)
        tail = [(i, j) for i, j in zip(it, J) if i >= 20]
        if tail:
            a2.plot([p[0] for p in tail], [p[1] for p in tail], "b.-", ms=3)
        a2.set_xlabel("iteration")
        a2.set_ylabel("J")
        a2.set_title("tail (iteration >= 20)")
        a2.grid(True, alpha=0.3)
        fig.suptitle(title)
        save(fig, "fig3-cost")

    # Fig. 4: the path over log10 s.
    fig, ax = plt.subplots(figsize=(7, 6))
    smap = rec.get("s_map")
    if smap:
        cs = ax.contourf(smap["x"], smap["y"], smap["log10_s"], levels=30, cmap="viridis")
        fig.colorbar(cs, ax=ax, label="log10 s(x1)   (s = E[1/CNR], W)")
    ax.plot(px, py, "r-", lw=2, label="path")
    _markers(ax, S, D, base)
    ax.set_xlim(0, 50)
    ax.set_ylim(0, 50)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.legend(loc="upper right", fontsize=8)
    ax.set_title("path over the predicted channel quality\n" + title, fontsize=9)
    save(fig, "fig4-path")

    # Fig. 5: position against time (3-D), with its projection onto the plane.
    fig = plt.figure(figsize=(7, 6))
    ax = fig.add_subplot(projection="3d")
    ax.plot(px, py, t, "b-", lw=2, label="(x1(t), t)")
    ax.plot(px, py, [0.0] * len(t), "r-", lw=2, label="path in the plane")
    _markers(ax, S, D, base, z=0.0)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("t (s)")
    ax.legend(fontsize=8)
    ax.set_title("position against time", fontsize=10)
    save(fig, "fig5-position-time")

    # Fig. 6: acceleration arrows along the path (the longest arrow is drawn 3 m long).
    fig, ax = plt.subplots(figsize=(7, 7))
    ax.plot(px, py, "-", color="0.6", lw=1.0, label="path", zorder=1)
    step = max(1, n // 60)
    ks = list(range(0, n, step))
    umax_seen = max(math.hypot(ax_[k], ay_[k]) for k in range(n)) or 1.0
    ax.quiver([px[k] for k in ks], [py[k] for k in ks], [ax_[k] for k in ks], [ay_[k] for k in ks],
              angles="xy", scale_units="xy", scale=umax_seen / 3.0, color="b", width=0.004,
              zorder=3, label="acceleration u (longest: %.3g m/s^2)" % umax_seen)
    _markers(ax, S, D, base)
    pad = 5.0
    ax.set_xlim(min(min(px), S[0], D[0], base[0]) - pad, max(max(px), S[0], D[0], base[0]) + pad)
    ax.set_ylim(min(min(py), S[1], D[1], base[1]) - pad, max(max(py), S[1], D[1], base[1]) + pad)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.02, 1.0))
    ax.set_title("acceleration along the path", fontsize=10)
    save(fig, "fig6-acceleration")

    # Fig. 7: speed along the path.
    fig = plt.figure(figsize=(7, 6))
    ax = fig.add_subplot(projection="3d")
    _stems(ax, px, py, speed, "b", "speed |x2|")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("speed (m/s)")
    ax.legend(fontsize=8)
    ax.set_title("speed along the path", fontsize=10)
    save(fig, "fig7-speed")

    # Fig. 8: spectral efficiency along the path (R_k at the interval's start point).
    fig = plt.figure(figsize=(7, 6))
    ax = fig.add_subplot(projection="3d")
    _stems(ax, px[:n], py[:n], rate, "b", "R")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("R (bits/s/Hz)")
    ax.legend(fontsize=8)
    ax.set_title("spectral efficiency along the path", fontsize=10)
    save(fig, "fig8-rate-path")

    # Fig. 9: R against time.
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.step(t[:n], rate, where="post", color="b")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("R (bits/s/Hz)")
    ax.set_title("spectral efficiency against time (bits sent: %.2f)" % bits[-1], fontsize=10)
    ax.grid(True, alpha=0.3)
    save(fig, "fig9-rate-time")

    # Not in the paper: speed and R against time on one axis (slow down where R is high).
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.plot(t, speed, "b-", label="speed |x2| (m/s)")
    ax2 = ax.twinx()
    ax2.step(t[:n], rate, where="post", color="g", label="R (bits/s/Hz)")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("speed (m/s)", color="b")
    ax2.set_ylabel("R (bits/s/Hz)", color="g")
    ax.set_title("speed and spectral efficiency against time", fontsize=10)
    ax.grid(True, alpha=0.3)
    save(fig, "extra-speed-rate-time")
    return files


def figures_from_records(records, outdir):
    """Entry point for results/plot.py: the paper's figures for the comm-path2d records of the
    first seed, for the Hamiltonian descent and Ipopt on the Euler transcription (the pair that
    solves the same discrete problem), one set per summary section (penalty setting) and terminal
    form. Every record would give hundreds of near-identical figures; the others' paths are in the
    records."""
    paper = [r for r in records if r.get("problem") == "comm-path2d" and r.get("trajectory")
             and r.get("kind", "solve") == "solve"]
    if not paper:
        return []
    first_seed = min(r.get("seed", 0) for r in paper)
    files = []
    seen = set()
    for rec in paper:
        method = rec.get("solver", "") + ("-" + rec["transcription"] if rec.get("transcription") else "")
        if rec.get("seed", 0) != first_seed or method not in ("hamiltonian", "ipopt-euler"):
            continue
        # The setting as summary.md splits it (the parameters that vary, e.g. C): "C-10-50-10".
        section = rec.get("section", "")
        setting = section[section.find("(") + 1:-1] if section.endswith(")") else ""
        setting = re.sub(r"(\d)\.0\b", r"\1", setting)
        setting = re.sub(r"[^A-Za-z0-9.+]+", "-", setting).strip("-")
        tag = "-".join(x for x in (rec.get("transcription"), rec.get("terminal", ""), setting) if x)
        if (method, tag) in seen:  # two records, one name: a setting the section does not name
            raise SystemExit("paper_figures.py: two %s records would write %s" % (method, tag))
        seen.add((method, tag))
        files += record_figures(rec, os.path.join(outdir, "paper"), tag=tag)
    return files


def main(argv):
    args = argv[1:]
    out = "results/paper/figures"
    if "--out" in args:
        i = args.index("--out")
        out = args[i + 1]
        del args[i:i + 2]
    if not args:
        print(__doc__)
        return 2
    written = []
    for path in args:
        with open(path) as f:
            rec = json.load(f)
        tag = os.path.splitext(os.path.basename(path))[0]
        written += record_figures(rec, out, tag=tag.split("_", 1)[1] if "_" in tag else "")
    for w in written:
        print(w)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
