// `ocpbench online`: re-planning with channel updates (paper Section IV), judged on the true
// channel, next to the offline plan made at t0 = 0.
#pragma once

#include <nlohmann/json.hpp>

#include "bench/cli/case_runner.h"

namespace CLI {
class App;
}  // namespace CLI

namespace ocpb {

/// `ocpbench online --problem comm-path2d --solver hamiltonian|ipopt [--seed S] [--json FILE]
/// [--period 10] [--initial-measurements 100] [--per-update 100] [--placement random|path|plan]
/// [--estimator binned|ml|reml] ...`.
void AddOnlineCommand(CLI::App& app);

/// Throws std::invalid_argument ("online.KEY: rule") unless `spec` (kind "online") is a valid
/// online case: problem comm-path2d, known solver, valid scenario settings. Settings (strings in
/// CaseSpec::online, all optional):
///   update_period (s, > 0, multiple of tf/N; 10), initial_measurements (>= 3; 100),
///   measurements_per_update (>= 1; 100), placement (random | path: driven since the last
///   update | plan: the rest of the current plan, evenly spaced in time; random), estimator
///   (binned | ml | reml; the channel library's default, EstimationOptions::method),
///   map_resolution (m, > 0; 0.5), truth_resolution (m, > 0; 0.1), workspace (side of the
///   simulated square, m, > 0; 50), refresh (0 | 1; 1), region_margin (m, >= 0; 10: re-predict
///   around the robot, D and its plan only; 0: everywhere), smap_resolution (m, > 0; 1: the grid of
///   the s maps stored for figures).
void ValidateOnlineCase(const CaseSpec& spec);

/// Runs an online case (RunOnlineReplanning on realization spec.seed) and returns its record:
/// kind, problem, parameters, seed, solver, transcription, N, options, replan_options, online
/// (resolved settings), key, status, cycles [{t0, predict_seconds, estimate_seconds,
/// factor_seconds, grid_seconds, map_seconds, solve_seconds, iterations, status, solver_status,
/// new_measurements, measurements, measurement_stream, estimated, planned_energy, planned_J,
/// segment_energy_true, segment_energy_predicted, plan {t, x}}], energy_true, energy_predicted,
/// J_true, terminal_violation, terminal_residual, final_state, offline_energy_true,
/// offline_energy_predicted, offline_J_true, offline_terminal_violation, energy_ratio
/// (energy_true / offline_energy_true), transmit_energy_true and offline_transmit_energy_true (the
/// transmission parts) with their ratio transmit_energy_ratio, J and Jbar (= J_true and
/// energy_true, for summaries), cpu_seconds (every cycle's prediction and solve), and with
/// keep_trajectory: executed and offline {t, x, u}, measurements {x, y, cycle}, s_map {x, y,
/// log10_s (true), log10_s_predicted (final)}.
nlohmann::json RunOnlineCase(const CaseSpec& spec);

}  // namespace ocpb
