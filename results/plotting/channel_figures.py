#!/usr/bin/python3
"""Figures of the channel model from the files `ocpbench channel predict` writes.

    /usr/bin/python3 results/plotting/channel_figures.py [DIR] [--out FIGDIR]

DIR (default results/channel) holds true_gain_db.npy, predicted_mean_db.npy, s_map.npy,
measurements.npy and predict.json (or only true_gain_db.npy and simulate.json after
`ocpbench channel simulate`). Writes, to FIGDIR (default DIR):

  fig1_simulated_channel.png  the simulated channel (the paper's Fig. 1)
  fig2_predicted_channel.png  the channel predicted from the samples (the paper's Fig. 2),
                              on the same colour scale as Fig. 1
  fig_channels.png            both side by side with one colour bar
  fig_s_map.png               log10 s(q), the predicted E[1/CNR] in the cost's units, at the
                              grid points (s_map.npy: the grid prediction that the map's
                              spline interpolates)

Maps are float32 arrays of shape (ny, nx); element [j][i] sits at
(x_min + (i + 0.5) h, y_min + (j + 0.5) h). Needs numpy and matplotlib only.
"""

import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def save_figure(fig, path, **kwargs):
    """fig.savefig to a temporary name next to `path`, then os.replace: a reader never sees a
    half-written file, and an interrupted run leaves the old figure in place."""
    directory, name = os.path.split(path)
    tmp = os.path.join(directory, ".{}.{}.tmp".format(name, os.getpid()))
    fmt = os.path.splitext(name)[1].lstrip(".") or "png"
    try:
        fig.savefig(tmp, format=fmt, **kwargs)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


def write_text(path, text):
    """Writes a text file atomically (temporary name + os.replace)."""
    directory, name = os.path.split(path)
    tmp = os.path.join(directory, ".{}.{}.tmp".format(name, os.getpid()))
    try:
        with open(tmp, "w") as f:
            f.write(text)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


def load_run(directory):
    """Returns (metadata dict, dict of arrays) for a channel output directory."""
    meta = None
    for name in ("predict.json", "simulate.json"):
        path = os.path.join(directory, name)
        if os.path.exists(path):
            with open(path) as f:
                meta = json.load(f)
            break
    if meta is None:
        raise FileNotFoundError(f"no predict.json or simulate.json in {directory}")
    arrays = {}
    for key in ("true_gain_db", "predicted_mean_db", "predicted_variance_db2", "s_map",
                "measurements"):
        path = os.path.join(directory, key + ".npy")
        if os.path.exists(path):
            arrays[key] = np.load(path)
    return meta, arrays


def extent(meta):
    w = meta["workspace"]
    return (w["x_min"], w["x_min"] + w["width"], w["y_min"], w["y_min"] + w["height"])


def shared_limits(*maps):
    """Colour limits shared by the maps: the 0.5 and 99.5 percentiles of all values, so the
    path-loss peak at the base station does not wash out the rest."""
    values = np.concatenate([m.ravel() for m in maps])
    return float(np.percentile(values, 0.5)), float(np.percentile(values, 99.5))


def _channel_axes(ax, meta, image, vmin, vmax, title, measurements=None):
    im = ax.imshow(image, origin="lower", extent=extent(meta), vmin=vmin, vmax=vmax,
                   cmap="viridis", interpolation="nearest")
    base = meta["true"]["base_station"]
    ax.plot(base[0], base[1], marker="^", color="red", markersize=7, linestyle="none",
            label="base station")
    if measurements is not None:
        ax.plot(measurements[:, 0], measurements[:, 1], ".", color="white", markersize=1.5,
                alpha=0.8, label=f"{len(measurements)} samples")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(title)
    return im


def channel_figures(meta, arrays, out_dir):
    """Figs. 1 and 2 (and the pair side by side) with one shared colour scale."""
    written = []
    true = arrays["true_gain_db"]
    pred = arrays.get("predicted_mean_db")
    vmin, vmax = shared_limits(true, pred) if pred is not None else shared_limits(true)
    label = "received power for 0 dBm sent (dBm)"

    fig, ax = plt.subplots(figsize=(6.2, 5))
    im = _channel_axes(ax, meta, true, vmin, vmax, f"Simulated channel (seed {meta['seed']})")
    fig.colorbar(im, ax=ax, label=label)
    path = os.path.join(out_dir, "fig1_simulated_channel.png")
    save_figure(fig, path, dpi=150, bbox_inches="tight")
    plt.close(fig)
    written.append(path)
    if pred is None:
        return written

    samples = arrays.get("measurements")
    title = f"Predicted channel from {meta['samples']} samples (RMSE {meta['rmse_db']:.2f} dB)"
    fig, ax = plt.subplots(figsize=(6.2, 5))
    im = _channel_axes(ax, meta, pred, vmin, vmax, title, samples)
    fig.colorbar(im, ax=ax, label=label)
    path = os.path.join(out_dir, "fig2_predicted_channel.png")
    save_figure(fig, path, dpi=150, bbox_inches="tight")
    plt.close(fig)
    written.append(path)

    fig, axes = plt.subplots(1, 2, figsize=(12, 5), constrained_layout=True)
    _channel_axes(axes[0], meta, true, vmin, vmax, "Simulated")
    im = _channel_axes(axes[1], meta, pred, vmin, vmax, f"Predicted ({meta['samples']} samples)",
                       samples)
    fig.colorbar(im, ax=list(axes), label=label, shrink=0.9)
    path = os.path.join(out_dir, "fig_channels.png")
    save_figure(fig, path, dpi=150)
    plt.close(fig)
    written.append(path)
    return written


def s_map_figure(meta, arrays, out_dir):
    """log10 s(q) with the samples and the base station."""
    s = arrays["s_map"].astype(np.float64)
    fig, ax = plt.subplots(figsize=(6.2, 5))
    im = ax.imshow(np.log10(s), origin="lower", extent=extent(meta), cmap="magma",
                   interpolation="nearest")
    scale = meta.get("units", {}).get("power_unit_scale", 1e-3)
    unit = "W" if scale == 1e-3 else ("mW" if scale == 1.0 else f"x{scale:g}")
    fig.colorbar(im, ax=ax, label=f"log10 s  (s = E[1/CNR], {unit})")
    samples = arrays.get("measurements")
    if samples is not None:
        ax.plot(samples[:, 0], samples[:, 1], ".", color="cyan", markersize=1.5, alpha=0.7)
    base = meta["true"]["base_station"]
    ax.plot(base[0], base[1], marker="^", color="lime", markersize=7, linestyle="none")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    # s_map.npy is the grid prediction itself (the values the map's spline interpolates), not
    # the spline.
    ax.set_title(f"log10 s(q) predicted at the {meta['workspace']['nx']} x "
                 f"{meta['workspace']['ny']} grid points ({meta['samples']} samples)")
    path = os.path.join(out_dir, "fig_s_map.png")
    save_figure(fig, path, dpi=150, bbox_inches="tight")
    plt.close(fig)
    return [path]


def main(argv):
    args = list(argv[1:])
    out_dir = None
    if "--out" in args:
        k = args.index("--out")
        if k + 1 >= len(args):
            print("channel_figures.py: --out needs a directory", file=sys.stderr)
            return 2
        out_dir = args[k + 1]
        del args[k:k + 2]
    if len(args) > 1 or any(a.startswith("-") for a in args):
        print(__doc__, file=sys.stderr)
        return 2
    directory = args[0] if args else "results/channel"
    out_dir = out_dir or directory
    os.makedirs(out_dir, exist_ok=True)
    meta, arrays = load_run(directory)
    if "true_gain_db" not in arrays:
        print(f"channel_figures.py: no true_gain_db.npy in {directory}", file=sys.stderr)
        return 2
    written = channel_figures(meta, arrays, out_dir)
    if "s_map" in arrays:
        written += s_map_figure(meta, arrays, out_dir)
    for path in written:
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
