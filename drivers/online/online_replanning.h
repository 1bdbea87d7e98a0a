// Online motion and communication co-optimization with channel updates (paper Section IV).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/option_value.h"
#include "core/solve_result.h"
#include "core/time_grid.h"
#include "core/types.h"
#include "drivers/online/online_channel.h"
#include "problems/comm_path2d.h"

namespace ocpb {

/// Where the measurements of each update are taken.
enum class MeasurementPlacement {
  kRandom,     ///< "random": uniformly at random in the workspace (unmeasured cells)
  kAlongPath,  ///< "path": along the path the robot drove since the last update
  /// "plan": along the rest of the current plan (from the robot's position to tf), at points
  /// evenly spaced in time: the channel where the robot is about to go.
  kAlongPlan,
};
const char* ToString(MeasurementPlacement placement);
/// "random", "path" or "plan"; throws std::invalid_argument otherwise.
MeasurementPlacement MeasurementPlacementFromString(const std::string& name);

/// The scenario and the method. Defaults: the paper's Section IV (100 measurements at t0 = 0,
/// 100 more every 10 s, N = 400 over [0, 40] s) with the paper's solver.
struct OnlineReplanningOptions {
  double update_period = 10.0;        ///< s between channel updates (> 0, a multiple of tf / N)
  int initial_measurements = 100;     ///< measurements known at t0 = 0 (>= 3)
  int measurements_per_update = 100;  ///< new measurements per update (>= 1)
  MeasurementPlacement placement = MeasurementPlacement::kRandom;
  int intervals = 400;                 ///< N on [0, tf]; every plan uses the same step tf / N
  std::string solver = "hamiltonian";  ///< registry name ("hamiltonian", "ipopt", ...)
  std::string transcription;           ///< NLP solvers ("euler": the same discrete problem)
  OptionMap transcription_options;     ///< the transcription's options, every solve
  OptionMap offline_options;           ///< solver options of the plan at t0 = 0
  OptionMap replan_options;            ///< solver options of the re-plans

  /// False with a one-line reason naming the field when a value breaks its rule (the
  /// multiple-of-step rule is checked by RunOnlineReplanning, which knows tf).
  bool IsValid(std::string* error) const;
};

/// One re-planning cycle: update the channel, solve J_{t0} from the current state, execute the
/// plan until the next update.
struct OnlineCycle {
  double t0 = 0.0;                       ///< s
  int first_step = 0;                    ///< k0: t0 = k0 tf / N
  int steps_executed = 0;                ///< steps of this plan the robot drove
  int new_measurements = 0;              ///< measurements added at this update
  int measurements = 0;                  ///< measurements known after it
  std::uint64_t measurement_stream = 0;  ///< RandomStream stream of the draw (random placement)
  ChannelParameters estimated;           ///< parameters the prediction used
  ChannelUpdateTimings predict;          ///< CPU seconds of re-estimation and re-prediction
  GridSpec map_grid;                     ///< where s was re-predicted (OnlineChannel::map_grid)
  double solve_seconds = -1.0;           ///< CPU seconds of the solve
  int iterations = -1;
  SolveStatus status = SolveStatus::kError;
  std::string solver_status;
  double planned_energy = -1.0;           ///< predicted Jbar of the plan on [t0, tf] (Euler)
  double planned_J = -1.0;                ///< predicted penalized J of the plan
  double segment_energy_true = 0.0;       ///< energy of the executed steps on the true channel
  double segment_energy_predicted = 0.0;  ///< the same on this cycle's predicted channel
  std::vector<double> plan_times;         ///< t0 .. tf
  Mat plan_states;                        ///< 5 x (N - k0 + 1), the plan's predicted states
};

/// The online run and the offline plan it is compared with.
struct OnlineResult {
  TimeGrid grid;  ///< [0, tf], N intervals
  std::vector<OnlineCycle> cycles;
  Mat X;                                      ///< executed states, 5 x (N + 1)
  Mat U;                                      ///< executed controls, 3 x N
  std::vector<double> step_energy_true;       ///< h (motion + (2^R - 1)/K s_true(x_k)) per step
  std::vector<double> step_energy_predicted;  ///< the same with the then-current prediction
  double energy_true = 0.0;                   ///< sum of step_energy_true
  double energy_predicted = 0.0;              ///< sum of step_energy_predicted
  double transmit_energy_true = 0.0;          ///< the transmission part of energy_true
  Vec terminal_residual;                      ///< psi(x_N) = (x1 - D, x2, x3 - c)
  double terminal_violation = -1.0;           ///< max |psi_i(x_N)|
  double J_true = -1.0;                       ///< energy_true + sum w_i psi_i^2

  Mat offline_X, offline_U;  ///< the plan made at t0 = 0, executed to tf
  double offline_energy_true = 0.0;
  double offline_energy_predicted = 0.0;      ///< its Jbar on the t0 = 0 prediction
  double offline_transmit_energy_true = 0.0;  ///< the transmission part of offline_energy_true
  Vec offline_terminal_residual;
  double offline_terminal_violation = -1.0;
  double offline_J_true = -1.0;
  double offline_solve_seconds = -1.0;  ///< = cycles[0].solve_seconds
  bool all_solved = true;  ///< false if some cycle ended in a failure status (see cycles)
};

/// The paper's Section IV scenario on a simulated channel:
///
///  1. t0 = 0: `initial_measurements` random measurements; the channel parameters are estimated
///     and s is predicted (OnlineChannel::Update); the problem (CommPath2d with `problem`'s
///     options) is solved on the grid of N intervals. This plan, executed to tf, is the
///     *offline* plan.
///  2. Every `update_period` s (t0 = k0 h, h = tf / N): `measurements_per_update` new
///     measurements (random; along the path driven since the last update; or along the rest of
///     the current plan, evenly spaced in time: MeasureAlongPath on the planned states from
///     t0 to tf, so cells already measured or repeated give fewer), re-estimation and
///     re-prediction with all measurements so far, then the cost-to-go problem J_{t0} (CommPath2d
///     with t0, start = x1(t0), v0 = x2(t0), x3_0 = x3(t0), same D, c, tf and penalties) is solved
///     on the remaining N - k0 intervals, warm-started from the rest of the previous controls,
///     with `replan_options`.
///  3. The robot executes each plan until the next update: x_{k+1} = x_k + h f(x_k, u_k) (the
///     planner's forward-Euler model, so an executed plan follows its predicted states exactly).
///
/// The honest measure is the energy on the *true* channel: step k costs
///   h [gamma (motion power of u_k, x2_k) + (2^R_k - 1)/K s_true(x1_k)],
/// the transmit power the real channel needs for the planned rate (OnlineChannel::TrueQuality),
/// next to what the planner predicted for the same steps. Both runs (online, offline) are judged
/// this way on the same realization, by ExecuteCommPlan (problems/comm_true_energy.h): the one
/// mechanism that also judges offline records on the true channel (ProblemInfo::judge_on_truth).
/// `seed` chooses the measurement draws: RandomStream(seed, 100 + cycle index). The channel must be
/// fresh (no measurements yet).
///
/// Throws std::invalid_argument on invalid options (including an update period that is not a
/// multiple of h, an unknown solver or invalid solver options); a solver failure ends nothing:
/// it is the cycle's status, and the robot executes the controls it returned.
OnlineResult RunOnlineReplanning(const CommPath2d::Options& problem,
                                 OnlineChannel* channel,
                                 std::uint64_t seed,
                                 const OnlineReplanningOptions& options);

/// The stream of the measurement draw of cycle `cycle` (0: the initial draw).
inline std::uint64_t OnlineMeasurementStream(int cycle) {
  return 100 + static_cast<std::uint64_t>(cycle);
}

}  // namespace ocpb
