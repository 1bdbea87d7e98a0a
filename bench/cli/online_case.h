// Suite cases and `ocpbench online` runs of kind "online": re-planning with channel updates
// (paper Section IV), judged on the true channel, next to the offline plan made at t0 = 0.
#pragma once

#include <string>
#include <vector>

#include "bench/cli/case_runner.h"
#include "bench/cli/case_spec.h"
#include "bench/cli/record.h"
#include "core/solve_result.h"
#include "drivers/online/online_scenario.h"

namespace ocpb {

/// An online record's status from its cycles' statuses: the first failure (IsFailure), else the
/// first limit (not IsSuccess), else "acceptable" when any cycle stopped at its solver's
/// acceptable level (never reported as converged), else "converged".
std::string WorstCycleStatus(const std::vector<SolveStatus>& cycles);

/// Throws std::invalid_argument ("online.KEY: rule", or the problem's, the solver's message)
/// unless `spec` (kind "online") is a valid online case: problem comm-path2d, a known solver
/// with valid options, valid scenario settings (OnlineScenarioSchema in
/// drivers/online/online_scenario.h: update_period, initial_measurements,
/// measurements_per_update, placement, estimator, map_resolution, truth_resolution, workspace,
/// refresh, region_margin, smap_resolution). No channel is simulated.
/// Returns the case's estimates (the scenario's own memory is checked by
/// ResolveOnlineScenario; the record's size grows with N, the cycles and the maps).
CaseEstimate ValidateOnlineCase(const CaseSpec& spec);

/// The scenario of an online case (ResolveOnlineScenario) from the case and its options split
/// by owner (ResolveMethodOptions, or ResolvedCase::options).
OnlineScenario ResolveOnlineCaseScenario(const CaseSpec& spec, const MethodOptions& options);
/// ValidateOnlineCase's checks of a resolved scenario.
CaseEstimate CheckOnlineCase(const CaseSpec& spec, const OnlineScenario& scenario);

/// Runs an online case (RunOnlineReplanning on realization spec.seed) and returns its record:
/// the case's identity, the resolved settings (`online`), the re-plans' options
/// (`replan_options`), status (the worst cycle's), cycles [{t0, predict_seconds,
/// estimate_seconds, factor_seconds, grid_seconds, map_seconds, solve_seconds, iterations,
/// status, solver_status, new_measurements, measurements, measurement_stream, estimated,
/// planned_energy, planned_J, segment_energy_true, segment_energy_predicted, plan {t, x}}],
/// energy_true, energy_predicted, J_true, terminal_violation, terminal_residual, final_state,
/// offline_energy_true, offline_energy_predicted, offline_J_true, offline_terminal_violation,
/// energy_ratio (energy_true / offline_energy_true), transmit_energy_true and
/// offline_transmit_energy_true (the transmission parts) with their ratio
/// transmit_energy_ratio, J and Jbar (= J_true and energy_true, for summaries), cpu_seconds
/// (every cycle's prediction and solve), and with keep_trajectory: executed and offline
/// {t, x, u}, measurements {x, y, cycle}, s_map {x, y, log10_s (true), log10_s_predicted}.
Record RunOnlineCase(const CaseSpec& spec);
/// The same with the case's scenario already resolved (ResolvedCase::online).
Record RunOnlineCase(const CaseSpec& spec, const OnlineScenario& scenario);

}  // namespace ocpb
