#include "core/evaluator.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ocpb {
namespace {

using Side = ControlTrajectory::Side;

// Track the worst control-set and path-constraint violation at a point.
struct ViolationTracker {
  const Ocp& ocp;
  double control = 0.0;
  double path = 0.0;
  Vec c;
  explicit ViolationTracker(const Ocp& o) : ocp(o), c(o.num_path()) {}
  void Visit(double t, ConstVecRef x, ConstVecRef u) {
    control = std::max(control, ocp.control_set().Violation(u));
    if (ocp.num_path() > 0) {
      ocp.PathConstraints(t, x, u, c);
      if (!c.allFinite()) {
        path = std::numeric_limits<double>::infinity();
      } else {
        path = std::max(path, c.maxCoeff());
      }
    }
  }
};

}  // namespace

Evaluation Evaluate(const Ocp& ocp, const ControlTrajectory& controls, const TimeGrid& grid,
                    Integrator integrator) {
  const int nx = ocp.nx(), nu = ocp.nu(), N = grid.intervals();
  Evaluation ev;
  ev.grid = grid;
  ev.integrator = integrator;
  ev.X.resize(nx, N + 1);
  Vec x = ocp.x0();
  ev.X.col(0) = x;
  ViolationTracker tracker(ocp);
  Vec u0(nu), um(nu), u1(nu), k1(nx), k2(nx), k3(nx), k4(nx);
  double running = 0.0;
  for (int k = 0; k < N; ++k) {
    const double t = grid.t(k), h = grid.h(k);
    controls.Evaluate(t, Side::kRight, u0);
    tracker.Visit(t, x, u0);
    if (integrator == Integrator::kEuler) {
      ocp.Dynamics(t, x, u0, k1);
      running += h * ocp.RunningCost(t, x, u0);
      x += h * k1;
    } else {
      controls.Evaluate(t + 0.5 * h, Side::kRight, um);
      controls.Evaluate(t + h, Side::kLeft, u1);
      ocp.Dynamics(t, x, u0, k1);
      double l = ocp.RunningCost(t, x, u0);
      Vec z = x + 0.5 * h * k1;
      ocp.Dynamics(t + 0.5 * h, z, um, k2);
      l += 2.0 * ocp.RunningCost(t + 0.5 * h, z, um);
      z = x + 0.5 * h * k2;
      ocp.Dynamics(t + 0.5 * h, z, um, k3);
      l += 2.0 * ocp.RunningCost(t + 0.5 * h, z, um);
      z = x + h * k3;
      ocp.Dynamics(t + h, z, u1, k4);
      l += ocp.RunningCost(t + h, z, u1);
      tracker.Visit(t + 0.5 * h, x, um);
      running += (h / 6.0) * l;
      x += (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    }
    ev.X.col(k + 1) = x;
  }
  controls.Evaluate(grid.tf(), Side::kLeft, u1);
  tracker.Visit(grid.tf(), x, u1);

  ev.running_cost = running;
  ev.terminal_cost = ocp.TerminalCost(x);
  ev.terminal_residual.resize(ocp.num_terminal());
  ocp.TerminalConstraints(x, ev.terminal_residual);
  ev.terminal_penalty = ocp.terminal_weights().dot(ev.terminal_residual.cwiseAbs2());
  ev.terminal_violation =
      ocp.num_terminal() > 0 ? ev.terminal_residual.cwiseAbs().maxCoeff() : 0.0;
  ev.Jbar = ev.running_cost + ev.terminal_cost;
  ev.J = ev.Jbar + ev.terminal_penalty;
  ev.control_violation = tracker.control;
  ev.path_violation = tracker.path;
  ev.finite = std::isfinite(ev.J) && ev.X.allFinite() && std::isfinite(ev.terminal_violation);
  return ev;
}

double ResimulationDefect(const Ocp& ocp, const ControlTrajectory& controls,
                          const TimeGrid& state_grid, const Mat& X, int refine) {
  const TimeGrid fine = state_grid.Refined(refine);
  const Evaluation ev = Evaluate(ocp, controls, fine, Integrator::kRk4);
  if (!ev.finite || !X.allFinite()) return std::numeric_limits<double>::quiet_NaN();
  double worst = 0.0;
  for (int k = 0; k < state_grid.size(); ++k) {
    worst = std::max(worst, (ev.X.col(k * refine) - X.col(k)).cwiseAbs().maxCoeff());
  }
  return worst;
}

}  // namespace ocpb
