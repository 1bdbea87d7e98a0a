#include "solvers/solver.h"

namespace ocpb {

namespace {

std::string FreeFinalTimeReason(const Ocp& ocp, const std::string& solver) {
  return "problem '" + ocp.name() + "' has a free final time, which " + solver +
         " does not take (it keeps the horizon fixed): indirect-newton (H(tf) = 0) and the "
         "NLP solvers on a collocation transcription (T a variable) solve it, and so does "
         "riccati-ip on euler and trapezoid; the time-scaled problems (brachistochrone, zermelo, "
         "steering, "
         "goddard, robot-arm) "
         "pose free time on a fixed horizon for every method";
}

// Who takes the features beyond free final time, for the refusal's text.
constexpr const char* kCollocationSolvers =
    "ipopt and nlopt on a collocation transcription (euler, trapezoid, hermite-simpson, lgr) "
    "solve it";

// kCollocationSolvers, and riccati-ip, which takes every feature of the problem class (since
// 2026-12-07 boundary inequalities too).
std::string WhoSolvesIt() {
  return std::string(kCollocationSolvers) + ", and so does riccati-ip on euler and trapezoid";
}

}  // namespace

SolveResult NotApplicableResult(const std::string& solver, const std::string& why) {
  SolveResult r;
  r.solver = solver;
  r.status = SolveStatus::kNotApplicable;
  r.solver_status = "not_applicable";
  r.message = why;
  r.iterations = 0;
  r.cpu_seconds = 0.0;
  r.wall_seconds = 0.0;
  return r;
}

std::optional<SolveResult> FreeFinalTimeNotApplicable(const Ocp& ocp, const std::string& solver) {
  if (!ocp.free_final_time()) return std::nullopt;
  return NotApplicableResult(solver, FreeFinalTimeReason(ocp, solver));
}

ProblemFeatures ProblemFeatures::Of(const Ocp& ocp) {
  ProblemFeatures f;
  f.free_final_time = ocp.free_final_time().has_value();
  f.free_initial_state = ocp.HasFreeInitialState();
  f.state_bounds = ocp.state_bounds().has_value();
  f.boundary_constraints = ocp.num_boundary() > 0;
  const VectorBounds& b = ocp.boundary_bounds();
  f.boundary_inequalities = (b.lower.array() < b.upper.array()).any();
  return f;
}

std::string UnsupportedFeature(const Ocp& ocp,
                               const std::string& solver,
                               const ProblemFeatures& takes) {
  const ProblemFeatures uses = ProblemFeatures::Of(ocp);
  if (uses.free_final_time && !takes.free_final_time) return FreeFinalTimeReason(ocp, solver);
  // indirect-newton and the Hamiltonian family take these two too (transversality rows, a
  // gradient step on x(t0)), where they apply at all.
  const std::string and_newton =
      "; indirect-newton and the Hamiltonian family (forward Euler) too, where the problem has "
      "a closed-form Hamiltonian minimizer";
  if (uses.free_initial_state && !takes.free_initial_state && ocp.num_static_parameters() > 0) {
    return "problem '" + ocp.name() +
           "' has static parameters (constant decisions, posed as a "
           "partly free initial state), which " +
           solver + " does not take: " + WhoSolvesIt() + and_newton;
  }
  if (uses.free_initial_state && !takes.free_initial_state) {
    return "problem '" + ocp.name() + "' has a free initial state, which " + solver +
           " does not take (it starts every trajectory from x0): " + WhoSolvesIt() + and_newton;
  }
  if (uses.state_bounds && !takes.state_bounds) {
    return "problem '" + ocp.name() + "' has state bounds, which " + solver +
           " does not take (its states follow from the controls, or it has no bounds on "
           "them): " +
           WhoSolvesIt();
  }
  if (uses.boundary_constraints && !takes.boundary_constraints) {
    return "problem '" + ocp.name() + "' has boundary constraints b(x(t0), x(tf)), which " +
           solver + " does not take: " + WhoSolvesIt();
  }
  return "";
}

std::optional<SolveResult> FeaturesNotApplicable(const Ocp& ocp,
                                                 const std::string& solver,
                                                 const ProblemFeatures& takes) {
  const std::string why = UnsupportedFeature(ocp, solver, takes);
  if (why.empty()) return std::nullopt;
  return NotApplicableResult(solver, why);
}

ControlTrajectory DefaultInitialGuess(const Ocp& ocp, const TimeGrid& grid) {
  Vec u = ocp.CheckedNominalControl();
  ocp.control_set().Project(u);
  return ControlTrajectory::Constant(grid, u);
}

}  // namespace ocpb
