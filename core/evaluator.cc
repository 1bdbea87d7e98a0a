#include "core/evaluator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

namespace ocpb {
namespace {

using Side = ControlTrajectory::Side;

// Track the worst control-set and path-constraint violation. Controls are checked wherever
// the integrator uses them; path constraints only at grid nodes, with the node's state and
// the control there (an RK4 stage mixes a node's state with a later time and control, which
// is no point of the trajectory).
struct ViolationTracker {
  const Ocp& ocp;
  double control = 0.0;
  double path = 0.0;
  Vec c;
  explicit ViolationTracker(const Ocp& o) : ocp(o), c(o.num_path()) {}
  void VisitControl(ConstVecRef u) { control = std::max(control, ocp.control_set().Violation(u)); }
  void VisitNode(double t, ConstVecRef x, ConstVecRef u) {
    VisitControl(u);
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

std::string Str(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

// The controls and the grid must fit the problem: a silent mismatch would judge the wrong thing
// (Eigen would read past the controls, or the piecewise rules would extrapolate).
void CheckInputs(const Ocp& ocp, const ControlTrajectory& controls, const TimeGrid& grid) {
  if (controls.nu() != ocp.nu()) {
    throw std::invalid_argument("Evaluate: the controls have " + std::to_string(controls.nu()) +
                                " components, the problem " + ocp.name() +
                                " has nu = " + std::to_string(ocp.nu()));
  }
  if (grid.size() < 2) throw std::invalid_argument("Evaluate: the grid has no interval");
  const double tol = 1e-9 * std::max({1.0, std::abs(ocp.t0()), std::abs(ocp.tf())});
  if (const std::string off = ocp.GridOffHorizon(grid, Ocp::HorizonEnd::kAdmissible);
      !off.empty()) {
    throw std::invalid_argument("Evaluate: " + off);
  }
  const TimeGrid& cg = controls.grid();
  if (cg.size() < 2 || cg.t0() > grid.t0() + tol || cg.tf() < grid.tf() - tol) {
    throw std::invalid_argument(
        "Evaluate: the controls are defined on [" + (cg.size() ? Str(cg.t0()) : "?") + ", " +
        (cg.size() ? Str(cg.tf()) : "?") + "], which does not cover the grid [" + Str(grid.t0()) +
        ", " + Str(grid.tf()) + "]");
  }
  // With a free final time the controls end where the solution ends (at its T): a grid that
  // stops earlier (the request's nominal grid) would judge a truncated trajectory, with a
  // plausible but wrong cost and terminal miss.
  if (ocp.free_final_time() && cg.tf() > grid.tf() + tol) {
    throw std::invalid_argument("Evaluate: problem " + ocp.name() +
                                " has a free final time and the controls end at T = " +
                                Str(cg.tf()) + ", but the grid ends at " + Str(grid.tf()) +
                                ": judge on the solution's horizon (JudgeResult in "
                                "solvers/judge.h, or the grid StretchedTo(T))");
  }
}

}  // namespace

Evaluation Evaluate(const Ocp& ocp,
                    const ControlTrajectory& controls,
                    const TimeGrid& grid,
                    Integrator integrator) {
  return Evaluate(ocp, controls, grid, integrator, ocp.x0());
}

Evaluation Evaluate(const Ocp& ocp,
                    const ControlTrajectory& controls,
                    const TimeGrid& grid,
                    Integrator integrator,
                    ConstVecRef initial_state) {
  CheckInputs(ocp, controls, grid);
  const int nx = ocp.nx(), nu = ocp.nu(), N = grid.intervals();
  if (initial_state.size() != nx) {
    throw std::invalid_argument("Evaluate: the initial state has " +
                                std::to_string(initial_state.size()) + " components, problem " +
                                ocp.name() + " has nx = " + std::to_string(nx));
  }
  Evaluation ev;
  ev.grid = grid;
  ev.integrator = integrator;
  ev.X.resize(nx, N + 1);
  Vec x = initial_state;
  ev.X.col(0) = x;
  // x(t0) against its bounds (a fixed x0 against itself: any other start is a violation).
  ev.state_bound_violation = ocp.InitialNodeBounds().Violation(x);
  const std::optional<VectorBounds>& state_bounds = ocp.state_bounds();
  ViolationTracker tracker(ocp);
  Vec u0(nu), um(nu), u1(nu), k1(nx), k2(nx), k3(nx), k4(nx);
  double running = 0.0;
  for (int k = 0; k < N; ++k) {
    const double t = grid.t(k), h = grid.h(k);
    controls.Evaluate(t, Side::kRight, u0);
    tracker.VisitNode(t, x, u0);
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
      tracker.VisitControl(um);
      tracker.VisitControl(u1);
      running += (h / 6.0) * l;
      x += (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    }
    ev.X.col(k + 1) = x;
    if (state_bounds) {
      ev.state_bound_violation = std::max(ev.state_bound_violation, state_bounds->Violation(x));
    }
  }
  controls.Evaluate(grid.tf(), Side::kLeft, u1);
  tracker.VisitNode(grid.tf(), x, u1);

  ev.running_cost = running;
  ev.terminal_cost = ocp.TerminalCost(x);
  ev.terminal_residual.resize(ocp.num_terminal());
  ocp.TerminalConstraints(x, ev.terminal_residual);
  ev.terminal_penalty = ocp.terminal_weights().dot(ev.terminal_residual.cwiseAbs2());
  ev.terminal_violation = ocp.num_terminal() > 0 ? ev.terminal_residual.cwiseAbs().maxCoeff() : 0.0;
  ev.Jbar = ev.running_cost + ev.terminal_cost;
  // Only with a free initial state, as the transcriptions count it (for a fixed x0 it would be
  // a constant no method sees); every other problem's J keeps its bits.
  if (ocp.HasFreeInitialState() && ocp.HasInitialCost()) {
    ev.initial_cost = ocp.InitialCost(ev.X.col(0));
    ev.Jbar += ev.initial_cost;
  }
  ev.J = ev.Jbar + ev.terminal_penalty;
  ev.boundary_residual.resize(ocp.num_boundary());
  ev.boundary_violation = 0.0;
  if (ocp.num_boundary() > 0) {
    ocp.BoundaryConstraints(ev.X.col(0), x, ev.boundary_residual);
    ev.boundary_violation = ev.boundary_residual.allFinite()
                                ? ocp.boundary_bounds().Violation(ev.boundary_residual)
                                : std::numeric_limits<double>::quiet_NaN();
  }
  ev.control_violation = tracker.control;
  ev.path_violation = tracker.path;
  ev.finite = std::isfinite(ev.J) && ev.X.allFinite() && std::isfinite(ev.terminal_violation) &&
              std::isfinite(ev.boundary_violation);
  return ev;
}

double ResimulationDefect(const Ocp& ocp,
                          const ControlTrajectory& controls,
                          const TimeGrid& state_grid,
                          const Mat& X,
                          int refine) {
  const TimeGrid fine = state_grid.Refined(refine);
  const bool own_start = ocp.HasFreeInitialState() && X.rows() == ocp.nx() && X.cols() > 0;
  const Evaluation ev =
      Evaluate(ocp, controls, fine, Integrator::kRk4, own_start ? Vec(X.col(0)) : ocp.x0());
  if (!ev.finite || !X.allFinite()) return std::numeric_limits<double>::quiet_NaN();
  double worst = 0.0;
  for (int k = 0; k < state_grid.size(); ++k) {
    worst = std::max(worst, (ev.X.col(k * refine) - X.col(k)).cwiseAbs().maxCoeff());
  }
  return worst;
}

}  // namespace ocpb
