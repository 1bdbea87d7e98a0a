// A solver written outside OCPBench: projected gradient descent on the discrete adjoint,
// registered as "projected-gradient" beside the built-in methods (my_ocpbench.cc).
#pragma once

#include "solvers/registry.h"
#include "solvers/solver.h"

namespace my_project {

/// Its options, with their defaults; the option table (my_solver.cc) states every rule.
struct ProjectedGradientOptions {
  double step = 1.0;                  ///< first trial step along -g_k / h_k (> 0)
  double sufficient_decrease = 1e-4;  ///< Armijo constant in (0, 1)
  int max_iterations = 1000;          ///< accepted steps at most (>= 0)
  int max_backtracks = 40;            ///< step halvings per iteration at most (>= 1)
  /// Converged when max_k |u_k - P_U(u_k - g_k / h_k)| <= tolerance (> 0): the projected
  /// gradient of the continuous-time cost, sampled. Much below 1e-6 the Armijo test meets the
  /// rounding of J (the decrease it asks for is below eps |J|) and the solve ends in
  /// line_search_failed instead.
  double tolerance = 1e-6;
};

/// Minimizes the forward-Euler discrete cost J(U) of ocpb::DiscreteOcp (the same discrete
/// problem as the Hamiltonian descent and Ipopt + Euler solve) in penalty terminal form: at
/// each iteration the exact gradient G = dJ/dU from the discrete adjoint, the scaled direction
/// d_k = -g_k / h_k (the continuous-time gradient), and the projected Armijo rule
///   U+ = P_U(U + s d),  accept when J(U+) - J(U) <= sufficient_decrease <G, U+ - U>,
/// halving s from min(2 s_prev, step); a trial that no longer changes U fails. Not applicable: the
/// hard terminal form, path constraints, a free final time. solver_status: "converged",
/// "max_iterations", "line_search_failed" (status step_too_small), "nonfinite_cost".
class ProjectedGradient final : public ocpb::Solver {
 public:
  using Options = ProjectedGradientOptions;
  std::string name() const override { return "projected-gradient"; }
  ocpb::SolveResult Solve(const ocpb::Ocp& ocp, const ocpb::SolveRequest& request) const override;

  /// Its registry entry: name, description, factory and option schema.
  static ocpb::SolverInfo Info();
};

}  // namespace my_project
