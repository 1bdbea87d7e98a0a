#!/usr/bin/python3
"""Figures for a suite's results: `/usr/bin/python3 results/plot.py results/<suite>`.

Reads <dir>/derived.jsonl (written by `ocpbench run`/`merge`: the records with the fields of the
target rule, the summary table ("section") and row ("method_label") of each record, see
bench/cli/summary.h) and writes PNG files to <dir>/figures/:
  convergence-<section>-<terminal form>.png
      one per summary table and terminal form, first seed: the relative gap of each method's own
      objective to the target (best final J fine of the group) against iteration and CPU time,
      one line per summary row (log scales); the dashed line is the 1% target
  profile-time.png   Dolan-More performance profile over the suite's instances (problem, seed,
                     parameters, terminal form) of the CPU time to target (infinite: never)
  profile-cost.png   the same for the final J fine, tau = 1 + its relative gap to the target,
                     drawn against tau - 1 on a log axis (the gaps span 1e-8 to 1e3)
and, for the paper's problems, the paper's own figures through plotting/paper_figures.py, and for
records of kind "online" the re-planning figures and online-summary.md through
plotting/online_figures.py. Every figure is written to a temporary name in its directory and
renamed into place, so a killed run leaves no half-written file.
Never edit the figures by hand: re-run this script.
"""
import glob
import json
import math
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "plotting"))
from figure_io import save_figure  # noqa: E402  (lives in results/plotting)

TARGET = 0.01  # "within 1% of the best", as in bench/cli/summary.cc


def slug(text):
    """A file-name piece for a summary section: 'comm-path2d (C = [10.0,50.0,10.0])' ->
    'comm-path2d-C-10-50-10'."""
    text = re.sub(r"(\d)\.0\b", r"\1", text)
    return re.sub(r"[^A-Za-z0-9.+]+", "-", text).strip("-")


def line_styles(records):
    """One colour and dash per summary row, the same in every figure of the suite."""
    labels = sorted({r["method_label"] for r in records})
    colors = plt.cm.tab10.colors
    dashes = ["-", "--", "-.", ":"]
    return {m: {"color": colors[i % len(colors)], "linestyle": dashes[(i // len(colors)) % len(dashes)]}
            for i, m in enumerate(labels)}


def load(dirname):
    path = os.path.join(dirname, "derived.jsonl")
    with open(path) as f:
        records = [json.loads(line) for line in f if line.strip()]
    if any("method_label" not in r or "final_J" not in r for r in records):
        sys.exit("plot.py: %s predates the current target rule; regenerate it with "
                 "`ocpbench run SUITE.json --resume` (no case is re-run)" % path)
    return records


def convergence(records, outdir, styles):
    """One figure per summary section and terminal form (the summary's split), first seed."""
    keyed = {}
    for r in records:
        if r.get("kind", "solve") == "solve" and r.get("history"):
            keyed.setdefault((r["section"], r.get("terminal", "")), []).append(r)
    written = []
    for (section, terminal), rs in keyed.items():
        seed = min(r.get("seed", 0) for r in rs)
        rs = [r for r in rs if r.get("seed", 0) == seed]
        best = next((r["best_J"] for r in rs if r.get("best_J") is not None), None)
        if best is None or best == 0:
            continue
        fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
        for r in rs:
            h = [e for e in r["history"] if e.get("J") is not None and e.get("cpu_seconds") is not None]
            if not h:
                continue
            style = styles[r["method_label"]]
            # A grid-sequenced solve's iterates on a coarser grid (rows with `intervals`) come
            # first and carry that grid's J, another discrete problem's: drawn faded.
            for on_request_grid in (False, True):
                part = [e for e in h if (e.get("intervals") is None) == on_request_grid]
                if not part:
                    continue
                gaps = [max(abs(e["J"] - best) / abs(best), 1e-16) for e in part]
                label = r["method_label"] if on_request_grid else None
                drawn = style if on_request_grid else dict(style, alpha=0.3)
                axes[0].plot([e["iteration"] for e in part], gaps, label=label, **drawn)
                axes[1].plot([max(e["cpu_seconds"], 1e-6) for e in part], gaps, label=label, **drawn)
        for ax, xlabel in zip(axes, ["iteration", "CPU seconds"]):
            ax.axhline(TARGET, color="k", ls="--", lw=0.8)
            ax.set_yscale("log")
            ax.set_xlabel(xlabel)
            ax.set_ylabel("|J - target| / |target|")
            ax.grid(True, which="both", alpha=0.3)
        axes[1].set_xscale("log")
        axes[0].legend(fontsize=7)
        fig.suptitle("%s, %s form, seed %s: each method's own objective per iterate (faded: on a "
                     "coarser grid)\ntarget = best final J fine = %.6g"
                     % (section, terminal, seed, best), fontsize=10)
        fig.tight_layout()
        path = os.path.join(outdir, "convergence-%s-%s.png" % (slug(section), terminal))
        save_figure(fig, path, dpi=110)
        plt.close(fig)
        written.append(path)
    # Figures of sections that are gone would otherwise outlive their data.
    for stale in set(glob.glob(os.path.join(outdir, "convergence-*.png"))) - set(written):
        os.remove(stale)
    return written


def profile(records, outdir, styles, metric, filename, xlabel, gap_axis=False):
    """Dolan-More profile: for each method (summary row), the fraction of the instances it ran on
    where its metric is within a factor tau of the best method's on that instance. With
    gap_axis the x axis is tau - 1 (log), for ratios that all sit near 1 (final costs)."""
    groups = {}
    for r in records:
        if r.get("kind", "solve") == "solve":
            groups.setdefault(r["group"], []).append(r)
    ratios = {}
    for group, rs in groups.items():
        values = {}
        for r in rs:
            if r["method_label"] in values:
                raise SystemExit("plot.py: two records of %s share the label %s" % (group, r["method_label"]))
            v = metric(r)
            values[r["method_label"]] = v if v is not None and math.isfinite(v) else math.inf
        finite = [v for v in values.values() if math.isfinite(v)]
        if not finite or min(finite) <= 0:
            continue
        best = min(finite)
        for m, v in values.items():
            ratios.setdefault(m, []).append(v / best)
    if not ratios:
        return None
    shift = 1.0 if gap_axis else 0.0
    xs = {m: sorted(x - shift for x in rs) for m, rs in ratios.items()}
    finite = [x for v in xs.values() for x in v if math.isfinite(x)]
    positive = [x for x in finite if x > 0]
    left = (min(positive) / 2 if positive else 1e-12) if gap_axis else 1.0
    right = max(max(finite, default=left) * 1.5, left * 10 if gap_axis else 1.01)
    fig, ax = plt.subplots(figsize=(8, 5))
    for m in sorted(xs):
        v = [max(x, left) for x in xs[m]]  # a gap of 0 (the best) sits at the left edge
        points = [left] + [x for x in v if math.isfinite(x)] + [right]
        fractions = [sum(1 for x in v if x <= t) / len(v) for t in points]
        ax.step(points, fractions, where="post", label="%s (%d)" % (m, len(v)), **styles[m])
    ax.set_xscale("log")
    ax.set_xlim(left, right)
    ax.set_xlabel(xlabel)
    ax.set_ylabel("fraction of the method's instances")
    ax.set_ylim(0, 1.05)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=6)
    fig.tight_layout()
    path = os.path.join(outdir, filename)
    save_figure(fig, path, dpi=110)
    plt.close(fig)
    return path


def cost_ratio(r):
    """1 + the relative gap of the final J fine to the target, at least 1 (a hard-form case that
    did not converge may end below the converged best)."""
    v, best = r.get("final_J"), r.get("best_J")
    if v is None or best is None or best == 0:
        return None
    return max(1.0, 1.0 + (v - best) / abs(best))


def main(argv):
    if len(argv) != 2:
        print("usage: plot.py RESULTS_DIR", file=sys.stderr)
        return 2
    dirname = argv[1]
    records = load(dirname)
    outdir = os.path.join(dirname, "figures")
    os.makedirs(outdir, exist_ok=True)
    styles = line_styles(records)
    convergence(records, outdir, styles)
    # A time of 0 (a first iterate on target) would make every ratio infinite: 1 us is the floor.
    profile(records, outdir, styles,
            lambda r: max(r["time_to_target"], 1e-6) if r.get("time_to_target") is not None else None,
            "profile-time.png",
            "tau (CPU time to target / the best method's; never: off the scale)")
    profile(records, outdir, styles, cost_ratio, "profile-cost.png",
            "tau - 1 (relative gap of the final J fine to the target; 0 at the left edge)",
            gap_axis=True)
    import paper_figures  # noqa: E402  (lives in results/plotting)

    paper_figures.figures_from_records(records, outdir)
    if any(r.get("kind") == "online" for r in records):
        import online_figures  # noqa: WPS433 (lives in results/plotting)

        online_figures.figures_from_records(records, outdir)
    print("figures in %s" % outdir)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
