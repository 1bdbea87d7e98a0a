#include "problems/comm_true_energy.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "problems/comm_energy_model.h"
#include "problems/comm_path2d.h"

namespace ocpb {

CommExecution ExecuteCommPlan(const Ocp& ocp,
                              const ChannelQuality& judge,
                              const TimeGrid& grid,
                              const Mat& controls,
                              const Vec& x0) {
  const auto* model = dynamic_cast<const CommEnergyModel*>(&ocp);
  if (model == nullptr) {
    throw std::invalid_argument("problem '" + ocp.name() +
                                "' has no communication energy model (comm-path2d, "
                                "comm-fixed-path)");
  }
  const int n = grid.intervals();
  if (controls.rows() != ocp.nu() || controls.cols() != n || x0.size() != ocp.nx()) {
    throw std::invalid_argument("ExecuteCommPlan: controls must be nu x N of the grid and x0 nx");
  }
  CommExecution e;
  e.X.resize(ocp.nx(), n + 1);
  e.X.col(0) = x0;
  e.step_energy_true.reserve(n);
  e.step_energy_planned.reserve(n);
  Vec x = x0, f(ocp.nx());
  for (int k = 0; k < n; ++k) {
    const double t = grid.t(k), h = grid.h(k);
    const auto u = controls.col(k);
    double s = 0.0;
    judge.Evaluate(model->Position(x), &s, nullptr, nullptr);
    const double transmit = h * model->TransmitPower(u, s);
    const double energy = h * model->MotionPower(x, u) + transmit;
    const double planned = h * ocp.RunningCost(t, x, u);
    e.step_energy_true.push_back(energy);
    e.step_energy_planned.push_back(planned);
    e.energy_true += energy;
    e.transmit_energy_true += transmit;
    e.energy_planned += planned;
    ocp.Dynamics(t, x, u, f);
    x += h * f;
    e.X.col(k + 1) = x;
  }
  e.terminal_residual.resize(ocp.num_terminal());
  ocp.TerminalConstraints(x, e.terminal_residual);
  e.terminal_violation = ocp.num_terminal() > 0 ? e.terminal_residual.cwiseAbs().maxCoeff() : 0.0;
  e.J_true = e.energy_true + ocp.TerminalCost(x) +
             ocp.terminal_weights().dot(e.terminal_residual.cwiseAbs2());
  return e;
}

PathGeometry MeasurePath(const Mat& path,
                         const Eigen::Vector2d& a,
                         const Eigen::Vector2d& b,
                         const Eigen::Vector2d& base) {
  PathGeometry g;
  if (path.cols() == 0) return g;
  const Eigen::Vector2d ab = b - a;
  const double ab2 = ab.squaredNorm();
  g.max_distance_from_segment = 0.0;
  g.min_distance_to_base = INFINITY;
  for (int k = 0; k < path.cols(); ++k) {
    const Eigen::Vector2d q = path.col(k).head<2>();
    const double along = ab2 > 0.0 ? std::clamp((q - a).dot(ab) / ab2, 0.0, 1.0) : 0.0;
    g.max_distance_from_segment =
        std::max(g.max_distance_from_segment, (q - (a + along * ab)).norm());
    g.min_distance_to_base = std::min(g.min_distance_to_base, (q - base).norm());
  }
  return g;
}

std::optional<TruthJudgement> JudgeCommPlanOnTruth(const Parameters& params,
                                                   std::uint64_t seed,
                                                   const Ocp& ocp,
                                                   const TimeGrid& grid,
                                                   const Mat& controls) {
  const auto* model = dynamic_cast<const CommEnergyModel*>(&ocp);
  if (model == nullptr) return std::nullopt;
  const std::shared_ptr<const ChannelQuality> truth = MakeCommTrueChannel(params, seed);
  const CommExecution e = ExecuteCommPlan(ocp, *truth, grid, controls, ocp.x0());
  Mat path(2, e.X.cols());
  for (int k = 0; k < e.X.cols(); ++k) {
    // Element by element: GCC 12 reports a false -Wstringop-overread on a vectorized column copy.
    const Eigen::Vector2d q = model->Position(e.X.col(k));
    path(0, k) = q.x();
    path(1, k) = q.y();
  }
  const PathGeometry g =
      MeasurePath(path, params.Vector("S"), params.Vector("D"), params.Vector("base"));
  TruthJudgement j;
  j.truth = truth->Describe();
  j.energy_true = e.energy_true;
  j.transmit_energy_true = e.transmit_energy_true;
  j.J_true = e.J_true;
  j.terminal_violation = e.terminal_violation;
  j.max_distance_from_segment = g.max_distance_from_segment;
  j.min_distance_to_base = g.min_distance_to_base;
  return j;
}

}  // namespace ocpb
