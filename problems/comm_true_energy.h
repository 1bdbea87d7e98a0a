// What a communication plan really costs: its controls executed on the planner's Euler model,
// the transmission paid on another channel (the true one) than the prediction it was planned on.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "core/ocp.h"
#include "core/parameters.h"
#include "core/time_grid.h"
#include "core/types.h"
#include "problems/channel/channel_quality.h"
#include "problems/registry.h"

namespace ocpb {

/// A plan executed by ExecuteCommPlan.
struct CommExecution {
  Mat X;  ///< states, nx x (n + 1): the start, then the end of every step
  std::vector<double> step_energy_true;     ///< h_k (P_m + P_c with s_judge(q(x_k))) per step
  std::vector<double> step_energy_planned;  ///< h_k L(t_k, x_k, u_k) on the problem's channel
  double energy_true = 0.0;                 ///< sum of step_energy_true
  double transmit_energy_true = 0.0;        ///< its transmission part, sum h_k P_c
  double energy_planned = 0.0;              ///< sum of step_energy_planned
  Vec terminal_residual;                    ///< psi(x_n)
  double terminal_violation = -1.0;         ///< max |psi_i(x_n)|
  double J_true = -1.0;                     ///< energy_true + phi(x_n) + sum_i w_i psi_i(x_n)^2
};

/// Executes `controls` (nu x n, one column per step of `grid`) from `x0` on the problem's
/// forward-Euler model, x_{k+1} = x_k + h_k f(t_k, x_k, u_k) (so an executed plan follows the
/// states its Euler planner predicted exactly), and prices every step twice:
///   on `judge`:        h_k [P_m(x_k, u_k) + P_c(u_k, s_judge(q(x_k)))]  (CommEnergyModel),
///   on its own model:  h_k L(t_k, x_k, u_k).
/// With judge = the true channel (TrueChannelQuality) this is what the plan really costs: the
/// one mechanism behind the online driver's energies (drivers/online/) and the true-channel
/// fields of offline records (JudgeCommPlanOnTruth). `ocp` must be a CommEnergyModel
/// (comm-path2d, comm-fixed-path); throws std::invalid_argument otherwise or on mismatched
/// sizes.
CommExecution ExecuteCommPlan(const Ocp& ocp,
                              const ChannelQuality& judge,
                              const TimeGrid& grid,
                              const Mat& controls,
                              const Vec& x0);

/// A path's geometry against the straight segment from `a` to `b` and a point `base`: the
/// largest distance of a point of `path` (2 x n) from the segment, and the smallest from base.
struct PathGeometry {
  double max_distance_from_segment = NAN;
  double min_distance_to_base = NAN;
};
PathGeometry MeasurePath(const Mat& path,
                         const Eigen::Vector2d& a,
                         const Eigen::Vector2d& b,
                         const Eigen::Vector2d& base);

/// The comm problems' ProblemInfo::judge_on_truth: the true channel of realization `seed`
/// (MakeCommTrueChannel), the controls executed by ExecuteCommPlan from the problem's initial
/// state, and the executed path's geometry against S-D and the base station. `ocp` is the
/// problem `make(params, seed)` built.
std::optional<TruthJudgement> JudgeCommPlanOnTruth(const Parameters& params,
                                                   std::uint64_t seed,
                                                   const Ocp& ocp,
                                                   const TimeGrid& grid,
                                                   const Mat& controls);

}  // namespace ocpb
