#!/usr/bin/python3
"""The final mesh of an adaptive mesh refinement over its solution.

Usage: /usr/bin/python3 results/plotting/mesh_figure.py RECORD.json FIGURE.png

RECORD.json is an `ocpbench solve --json` record with a `mesh` field (transcription option
mesh_tolerance > 0) and its trajectory. Top: the controls as the evaluator samples them (each
interval's left end) with the mesh nodes as vertical lines; middle: the method's own states;
bottom: the final mesh's interval lengths h_k against t, with the first (uniform) mesh's h for
comparison, and for LGR's ph-refinement each interval's degree (collocation points) on a second
axis. Written atomically (figure_io).
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from figure_io import save_figure  # noqa: E402


def main(record_path, figure_path):
    with open(record_path) as f:
        r = json.load(f)
    if "mesh" not in r or "trajectory" not in r:
        sys.exit("mesh_figure.py: %s has no mesh or no trajectory" % record_path)
    nodes = r["mesh"]["nodes"]
    traj = r["trajectory"]
    t = traj["t"]
    fig, axes = plt.subplots(3, 1, figsize=(7, 7.5), sharex=True)
    for i, row in enumerate(traj["u"]):
        # Each interval's value from its left end to the next node (the last one to tf).
        axes[0].step(t[: len(row)] + [t[-1]], row + row[-1:], where="post", label="u%d" % (i + 1))
    for tk in nodes:
        axes[0].axvline(tk, color="0.85", linewidth=0.6, zorder=0)
    axes[0].set_ylabel("control")
    axes[0].legend(loc="best")
    own = traj.get("own")
    if own:
        for i, row in enumerate(own["x"]):
            axes[1].plot(own["t"], row, ".-", markersize=2, label="x%d" % (i + 1))
        axes[1].legend(loc="best")
    axes[1].set_ylabel("states (the method's own)")
    mids = [(a + b) / 2 for a, b in zip(nodes, nodes[1:])]
    h = [b - a for a, b in zip(nodes, nodes[1:])]
    axes[2].semilogy(mids, h, "o-", markersize=3, label="final mesh (%d intervals)" % len(h))
    first = r["mesh"]["history"][0]["intervals"]
    axes[2].axhline((nodes[-1] - nodes[0]) / first, color="0.5", linestyle="--",
                    label="first mesh (uniform, %d intervals)" % first)
    axes[2].set_ylabel("interval length h_k")
    axes[2].set_xlabel("t")
    last = r["mesh"]["history"][-1]
    degrees = last.get("degrees")
    if degrees:
        right = axes[2].twinx()
        right.step(nodes, degrees + degrees[-1:], where="post", color="tab:red",
                   label="degree (points per interval)")
        right.set_ylabel("degree", color="tab:red")
        right.set_ylim(0, max(degrees) + 1)
        right.legend(loc="lower right")
    axes[2].legend(loc="upper left")
    fig.suptitle("%s, %s + %s:\n%d meshes (%s), largest estimate %.2g"
                 % (r["problem"], r["solver"], r["transcription"], len(r["mesh"]["history"]),
                    r["mesh"]["stop_reason"], last["max_error"]), fontsize=10)
    fig.tight_layout()
    save_figure(fig, figure_path, dpi=110)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
