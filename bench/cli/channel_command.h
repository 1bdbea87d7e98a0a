// `ocpbench channel simulate|predict`: the channel model from the command line.
#pragma once

namespace CLI {
class App;
}  // namespace CLI

namespace ocpb {

/// Adds `channel` with two subcommands:
///
///   ocpbench channel simulate [--seed S] [--out DIR] [workspace and parameter options]
///     simulates one realization and writes DIR/true_gain_db.npy and DIR/simulate.json;
///   ocpbench channel predict [--samples M] [--seed S] [--json FILE] [--out DIR] [...]
///     simulates, draws M measurements (or reads --measurements FILE.csv), estimates the
///     parameters, predicts every grid point and builds the s-map; writes true_gain_db.npy,
///     predicted_mean_db.npy, predicted_variance_db2.npy, s_map.npy, measurements.npy and
///     predict.json to DIR (default results/channel) and the same JSON to FILE.
///
/// Maps are float32 .npy arrays of shape (ny, nx), row j at y = y_min + (j + 1/2) h, column i
/// at x = x_min + (i + 1/2) h; results/plotting/channel_figures.py turns them into the paper's
/// Figs. 1-2 and a log-scale s-map. The predict JSON always has `estimated` {K_PL, n_PL, xi,
/// eta, rho}, `predict_seconds`, `points` and `rmse_db`, with the seed and every parameter.
/// Invalid input throws std::invalid_argument with a one-line message.
void AddChannelCommand(CLI::App& app);

}  // namespace ocpb
