#!/usr/bin/python3
"""Figures for a suite's results: `/usr/bin/python3 results/plot.py results/<suite>`.

Reads <dir>/derived.jsonl (written by `ocpbench run`/`merge`) and writes PNG files to <dir>/figures/:
  convergence-<problem>.png   J against iteration and against CPU time, one line per method (log scale)
  profile-time.png            Dolan-More performance profile of CPU time to target
  profile-cost.png            profile of the final J's relative gap to the best J
and, for the paper's problems, the paper's own figures through plotting/paper_figures.py, and for
records of kind "online" the re-planning figures and online-summary.md through
plotting/online_figures.py.
Never edit the figures by hand: re-run this script.
"""
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "plotting"))


def method_label(r):
    label = r["solver"]
    if r.get("transcription"):
        label += " + " + r["transcription"]
    if r.get("algorithm"):
        label += " (" + r["algorithm"] + ")"
    return label + ", " + r.get("terminal", "") + ", N=%s" % r.get("N")


def load(dirname):
    path = os.path.join(dirname, "derived.jsonl")
    with open(path) as f:
        return [json.loads(line) for line in f if line.strip()]


def convergence(records, outdir):
    by_problem = {}
    for r in records:
        by_problem.setdefault(r["problem"], []).append(r)
    for problem, rs in by_problem.items():
        seed = min(r.get("seed", 0) for r in rs)
        rs = [r for r in rs if r.get("seed", 0) == seed and r.get("history")]
        if not rs:
            continue
        best = min((r["best_J"] for r in rs if r.get("best_J") is not None), default=None)
        fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
        for r in rs:
            h = [e for e in r["history"] if e.get("J") is not None]
            if not h:
                continue
            # Plot the excess over the best J when it is known (log scale needs positive values).
            shift = best if best is not None else 0.0
            ys = [max(e["J"] - shift, 1e-12) if best is not None else e["J"] for e in h]
            if best is None and min(ys) <= 0:
                continue
            axes[0].plot([e["iteration"] for e in h], ys, label=method_label(r))
            axes[1].plot([max(e["cpu_seconds"], 1e-6) for e in h], ys, label=method_label(r))
        ylabel = "J - best J" if best is not None else "J"
        for ax, xl in zip(axes, ["iteration", "CPU seconds"]):
            ax.set_yscale("log")
            ax.set_xlabel(xl)
            ax.set_ylabel(ylabel)
            ax.grid(True, which="both", alpha=0.3)
        axes[1].set_xscale("log")
        axes[0].legend(fontsize=7)
        fig.suptitle("%s (seed %s): method's own objective per iteration" % (problem, seed))
        fig.tight_layout()
        fig.savefig(os.path.join(outdir, "convergence-%s.png" % problem), dpi=110)
        plt.close(fig)


def profile(records, outdir, metric, filename, xlabel):
    """Dolan-More profile: fraction of problem instances a method solves within a factor tau."""
    groups = {}
    for r in records:
        groups.setdefault(r["group"], []).append(r)
    methods = sorted({method_label(r).rsplit(", N=", 1)[0] for r in records})
    ratios = {m: [] for m in methods}
    for rs in groups.values():
        values = {}
        for r in rs:
            v = metric(r)
            values[method_label(r).rsplit(", N=", 1)[0]] = v
        finite = [v for v in values.values() if v is not None and math.isfinite(v)]
        if not finite:
            continue
        best = min(finite)
        for m in methods:
            if m not in values:
                continue
            v = values[m]
            ratios[m].append(v / best if v is not None and math.isfinite(v) and best > 0 else math.inf)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    taus = [1.0 * (1.08 ** k) for k in range(0, 200)]
    for m in methods:
        rs = ratios[m]
        if not rs:
            continue
        ax.step(taus, [sum(1 for x in rs if x <= t) / len(rs) for t in taus], where="post", label=m)
    ax.set_xscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel("fraction of instances")
    ax.set_ylim(0, 1.05)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(outdir, filename), dpi=110)
    plt.close(fig)


def main(argv):
    if len(argv) != 2:
        print("usage: plot.py RESULTS_DIR", file=sys.stderr)
        return 2
    dirname = argv[1]
    records = load(dirname)
    outdir = os.path.join(dirname, "figures")
    os.makedirs(outdir, exist_ok=True)
    convergence(records, outdir)
    profile(records, outdir, lambda r: r.get("time_to_target"), "profile-time.png",
            "tau (CPU time to target / best)")
    profile(records, outdir,
            lambda r: (1.0 + (r["J"] - r["best_J"]) / abs(r["best_J"]))
            if r.get("J") is not None and r.get("best_J") else None,
            "profile-cost.png", "tau (1 + relative gap of final J to the best J)")
    try:
        import paper_figures  # noqa: WPS433 (lives in results/plotting)
    except ImportError:
        paper_figures = None
    if paper_figures is not None and hasattr(paper_figures, "figures_from_records"):
        paper_figures.figures_from_records(records, outdir)
    if any(r.get("kind") == "online" for r in records):
        import online_figures  # noqa: WPS433 (lives in results/plotting)

        online_figures.figures_from_records(records, outdir)
    print("figures in %s" % outdir)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
