#include "my_solver.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/discrete_ocp.h"
#include "core/option_binding.h"
#include "core/timer.h"

namespace my_project {
namespace {

using ocpb::Mat;
using ocpb::OptionBounds;

// The option table: names, defaults (the struct's), rules and one-line docs. OCPBench validates
// a suite's or a command line's options against it before anything runs.
const ocpb::OptionBinding<ProjectedGradientOptions>& Binding() {
  static const ocpb::OptionBinding<ProjectedGradientOptions> table = [] {
    using O = ProjectedGradientOptions;
    ocpb::OptionBinding<O> t("projected-gradient");
    t.Number("step", &O::step, "first trial step along -g/h", OptionBounds::Above(0));
    t.Number("sufficient_decrease",
             &O::sufficient_decrease,
             "Armijo constant",
             OptionBounds::Open(0, 1));
    t.Integer(
        "max_iterations", &O::max_iterations, "accepted steps at most", OptionBounds::AtLeast(0));
    t.Integer("max_backtracks",
              &O::max_backtracks,
              "step halvings per iteration at most",
              OptionBounds::AtLeast(1));
    t.Number("tolerance",
             &O::tolerance,
             "converged when the projected gradient is below",
             OptionBounds::Above(0));
    return t;
  }();
  return table;
}

ocpb::SolveResult Refused(const std::string& why) {
  ocpb::SolveResult r;
  r.solver = "projected-gradient";
  r.status = ocpb::SolveStatus::kNotApplicable;
  r.solver_status = "not_applicable";
  r.message = why;
  r.iterations = 0;
  return r;
}

void Project(const ocpb::ControlSet& set, Mat* U) {
  for (Eigen::Index k = 0; k < U->cols(); ++k) set.Project(U->col(k));
}

// max_k |u_k - P_U(u_k - g_k / h_k)|
double ProjectedGradientNorm(const ocpb::Ocp& ocp,
                             const ocpb::TimeGrid& grid,
                             const Mat& U,
                             const Mat& G) {
  Mat trial = U;
  for (int k = 0; k < grid.intervals(); ++k) trial.col(k) -= G.col(k) / grid.h(k);
  Project(ocp.control_set(), &trial);
  return (trial - U).cwiseAbs().maxCoeff();
}

}  // namespace

ocpb::SolveResult ProjectedGradient::Solve(const ocpb::Ocp& ocp,
                                           const ocpb::SolveRequest& request) const {
  const Options o = Binding().Apply(request.options, Options());
  if (request.terminal != ocpb::TerminalMode::kPenalty) {
    return Refused("projected-gradient takes the penalty terminal form only");
  }
  if (ocp.num_path() > 0) return Refused("projected-gradient handles no path constraints");
  if (ocp.free_final_time()) return Refused("projected-gradient keeps the horizon fixed");
  const ocpb::Stopwatch watch;
  const ocpb::TimeGrid& grid = request.grid;
  const ocpb::DiscreteOcp docp(ocp, grid, ocpb::Integrator::kEuler, request.terminal);
  Mat U = request.initial_guess ? request.initial_guess->SampleIntervals(grid)
                                : ocpb::DefaultInitialGuess(ocp, grid).values();
  Project(ocp.control_set(), &U);
  Mat X, Lambda, G, X_trial;
  double J = docp.Simulate(U, &X);
  ocpb::SolveResult r;
  r.solver = name();
  r.iterations = 0;
  double step = o.step;
  auto finish = [&](ocpb::SolveStatus status, const char* code) {
    r.status = status;
    r.solver_status = code;
    r.message = std::string(code) + " after " + std::to_string(r.iterations) + " iterations";
  };
  while (true) {
    if (!std::isfinite(J)) {
      finish(ocpb::SolveStatus::kNumericalFailure, "nonfinite_cost");
      break;
    }
    docp.Adjoint(U, X, &Lambda, &G);
    const double pg = ProjectedGradientNorm(ocp, grid, U, G);
    ocpb::IterationRecord row;
    row.iteration = r.iterations;
    row.J = J;
    row.dual_inf = pg;
    row.cpu_seconds = watch.cpu();
    r.history.push_back(row);
    if (pg <= o.tolerance) {
      finish(ocpb::SolveStatus::kConverged, "converged");
      break;
    }
    if (r.iterations >= o.max_iterations) {
      finish(ocpb::SolveStatus::kMaxIterations, "max_iterations");
      break;
    }
    bool accepted = false;
    step = std::min(2.0 * step, o.step);
    for (int b = 0; b < o.max_backtracks && !accepted; ++b, step *= 0.5) {
      Mat trial = U;
      for (int k = 0; k < grid.intervals(); ++k) trial.col(k) -= step * G.col(k) / grid.h(k);
      Project(ocp.control_set(), &trial);
      if (trial == U) break;  // the step no longer moves U: rounding, not progress
      const double J_trial = docp.Simulate(trial, &X_trial);
      const double decrease = o.sufficient_decrease * (G.array() * (trial - U).array()).sum();
      if (std::isfinite(J_trial) && J_trial - J <= decrease) {
        U = trial;
        X = X_trial;
        J = J_trial;
        accepted = true;
      }
    }
    if (!accepted) {
      finish(ocpb::SolveStatus::kStepTooSmall, "line_search_failed");
      break;
    }
    ++r.iterations;
  }
  r.controls = ocpb::ControlTrajectory::PiecewiseConstant(grid, U);
  r.state_grid = grid;
  r.states = X;
  r.costates = Lambda;
  r.objective = J;
  r.cpu_seconds = watch.cpu();
  r.wall_seconds = watch.wall();
  return r;
}

ocpb::SolverInfo ProjectedGradient::Info() {
  ocpb::SolverInfo info;
  info.name = "projected-gradient";
  info.description =
      "user example: projected gradient descent with Armijo steps on the discrete adjoint "
      "(forward Euler, penalty form)";
  info.make = [] { return std::make_unique<ProjectedGradient>(); };
  info.options = Binding().schema();
  return info;
}

}  // namespace my_project
