// An online re-planning scenario resolved from a problem's parameters and the scenario's own
// settings: what `ocpbench online` and suite cases of kind "online" run.
#pragma once

#include <optional>
#include <string>

#include "core/option_schema.h"
#include "core/parameters.h"
#include "drivers/online/online_channel.h"
#include "drivers/online/online_replanning.h"
#include "problems/comm_path2d.h"

namespace ocpb {

/// The scenario settings (keys of a case's "online" object; `ocpbench online --period ...`).
/// Unset optionals take the problem parameter of the same meaning.
struct OnlineScenarioSettings {
  double update_period = 10.0;     ///< s between channel updates (a multiple of tf / N)
  int initial_measurements = 100;  ///< measurements known at t0 = 0
  int measurements_per_update = 100;
  std::string placement = "random";  ///< random | path | plan (MeasurementPlacement)
  /// Grid of the re-predicted s map (m, >= truth_resolution, >= 4 cells per side).
  double map_resolution = 0.5;
  std::optional<double> truth_resolution;  ///< grid of the simulated channel (grid_step)
  std::optional<double> workspace;         ///< side of the simulated square (workspace)
  int refresh = 1;  ///< 0: never refresh the prediction after t0 = 0 (a control experiment)
  double region_margin = 10.0;   ///< re-predict around the robot, D and its plan (0: everywhere)
  double smap_resolution = 1.0;  ///< grid of the s maps a record stores for figures (m)
  std::string estimator;         ///< binned | ml | reml; empty: the problem's `estimator`
};

/// The settings' keys, defaults and rules.
const OptionSchema& OnlineScenarioSchema();

/// Everything one online run needs.
struct OnlineScenario {
  Parameters params;            ///< the problem's parameters, resolved
  CommPath2d::Options problem;  ///< the problem at t0 = 0
  OnlineChannelOptions channel;
  OnlineReplanningOptions replanning;
  double smap_resolution = 1.0;
  OptionMap settings;  ///< every setting with its effective value (for the record)
};

/// What the caller chose: the problem's parameter assignments, the scenario settings, the
/// method (solver, transcription, its options for every solve, and those of the re-plans only).
struct OnlineScenarioRequest {
  std::string problem = "comm-path2d";  ///< the scenario is defined for comm-path2d only
  std::vector<std::string> set;         ///< "key=value" over comm-path2d's defaults
  OptionMap settings;                   ///< OnlineScenarioSchema() keys
  std::string solver;
  std::string transcription;  ///< NLP solvers; empty: "euler", the descent's discrete problem
  OptionMap transcription_options;
  OptionMap options;         ///< every solve
  OptionMap replan_options;  ///< over `options` and the solver's replan_defaults, re-plans only
  int intervals = 0;         ///< N on [0, tf]; 0: the problem's default
};

/// Resolves and checks everything (no channel is simulated): the settings by their schema
/// (unknown keys listed), the problem's parameters and rules, the solver and its options, the
/// update period against the step, the measurement budget against the truth grid. Throws
/// std::invalid_argument "online.KEY: rule" (or the parameter's / solver's message).
OnlineScenario ResolveOnlineScenario(const OnlineScenarioRequest& request);

}  // namespace ocpb
