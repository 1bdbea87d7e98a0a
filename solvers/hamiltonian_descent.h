// The Hamiltonian-based descent of Ali, Cai, Mostofi and Wardi (OCPBench solver "hamiltonian").
#pragma once

#include <limits>
#include <map>
#include <optional>
#include <string>

#include "core/discrete_ocp.h"
#include "core/option_schema.h"
#include "solvers/solver.h"

namespace ocpb {

/// Options of HamiltonianDescent (the paper's defaults).
struct HamiltonianDescentOptions {
  /// Armijo sufficient-decrease constant: accept when J(U + beta^j D) - J(U) <= alpha beta^j theta.
  /// Must lie in (0, 1). The paper's value.
  double alpha = 0.1;
  /// Armijo step reduction: step sizes 1, beta, beta^2, ... Must lie in (0, 1). The paper's value.
  double beta = 0.5;
  /// Stop after this many accepted steps (>= 0; 0 only evaluates the start). The paper's value.
  int max_iterations = 500;
  /// Largest Armijo exponent tried; the solve stops when j would exceed it (>= 0). The paper's 50.
  int max_armijo_exponent = 50;
  /// Stop when |theta(U)| <= theta_tolerance (>= 0). 0: only theta == 0 exactly stops (off).
  double theta_tolerance = 0.0;
  /// Stop before the next Armijo search once the solve has used this much CPU time (> 0;
  /// infinity: no limit).
  double max_cpu_seconds = std::numeric_limits<double>::infinity();
  /// Passed to Ocp::HamiltonianReformulation: rho > 0 of a path-constraint penalty and eps > 0 of
  /// a control regularization, for problems that need a reformulation (unset: the problem's own
  /// default, stated in its header).
  std::optional<double> path_penalty;
  std::optional<double> regularization;
  /// Reject Armijo trials early when the problem gives Ocp::RunningCostLowerBound() m (forward
  /// Euler only): a states-only simulation gives x_N and the bound
  ///   J(trial) >= sum_k h_k m + Phi(x_N),
  /// and a trial whose bound already exceeds J(U) + alpha beta^j theta (plus a 1e-10 relative
  /// margin for summation roundoff) fails the Armijo test without its running cost being computed.
  /// When Ocp::HasAffineDynamics(), x_N is affine in the controls and one states-only simulation
  /// per iteration (of U + d) gives x_N of every trial.
  /// Problems with an EulerStageModel add a pointwise bound and a running-cost pass that stops
  /// once its partial sum fails the test (DescentPasses).
  /// The accepted exponents and iterates are exactly those without it (tested); it only saves
  /// time.
  bool armijo_prefilter = true;

  /// False, with a one-line reason in *error, when a field violates its rule above.
  bool IsValid(std::string* error) const;
};

/// Minimizes the discrete penalized cost J(U) of DiscreteOcp (piecewise-constant controls u_k on
/// the request's grid) by the algorithm of Section II.C of
///   U. Ali, H. Cai, Y. Mostofi, Y. Wardi, "Motion and communication co-optimization with path
///   planning and online channel estimation" (ACC 2016),
/// which is the Hamiltonian-based method of Hale, Wardi, Jaleel and Egerstedt (arXiv 1603.02747):
///
///   1. simulate x_k, then the exact discrete adjoint lambda_k of DiscreteOcp::Adjoint;
///   2. u*_k = argmin_{u in U} H(t_k, x_k, u, lambda_{k+1})   (Ocp::MinimizeHamiltonian),
///      direction d_k = u*_k - u_k, and
///        theta(U) = sum_k h_k [H(t_k, x_k, u*_k, lambda_{k+1}) - H(t_k, x_k, u_k, lambda_{k+1})]
///                 <= 0;
///   3. Armijo: the smallest j in {0, ..., max_armijo_exponent} with
///        J(U + beta^j D) - J(U) <= alpha beta^j theta(U),
///      then U <- U + beta^j D (which stays in U: it is convex and u_k, u*_k lie in it).
///
/// Forward Euler (the paper's integrator, SolveRequest::integrator = kEuler): lambda_{k+1} is the
/// exact costate of the discrete problem, the gradient is g_k = h_k dH/du(t_k, x_k, u_k,
/// lambda_{k+1}), and when H is convex in u (f affine in u, L convex in u: the paper's
/// Assumption 1)
///   sum_k g_k . d_k <= theta(U) <= 0,
/// so d is a descent direction of the discrete J whenever theta < 0 and the Armijo search ends: a
/// true descent method on the discrete cost, projected-gradient-like (not conjugate gradient).
///
/// RK4 (kRk4): lambda_k is the exact adjoint of the RK4 map, and u*_k minimizes H at the
/// interval's left node with the costate of its right node, H(t_k, x_k, ., lambda_{k+1}); theta is
/// the same left-node sum. This is a consistent approximation, not an exact descent guarantee on
/// the RK4 cost: the Armijo test (on the RK4 J) guards every step, and a direction that is not a
/// descent direction ends the solve with "armijo_exponent_exceeded".
///
/// Applicability (otherwise SolveStatus::kNotApplicable with the reason in `message`):
///  - TerminalMode::kPenalty (the terminal penalty sum_i w_i psi_i^2 enters Phi); the hard form
///    psi = 0 has no place in this unconstrained-in-x method;
///  - the problem solved must have Ocp::HasHamiltonianMinimizer() and num_path() == 0: path
///    constraints c(t, x, u) <= 0 are not handled by the method itself. When
///    Ocp::HamiltonianReformulation({path_penalty, regularization}) returns a problem (path
///    constraints folded into L as a penalty, or a regularized L where H is linear in u), that
///    problem is solved instead and `message` says so; its controls are still judged on the
///    original problem by the common evaluator, while `objective`, `history` and the costates
///    belong to the reformulation.
///
/// Stopping (SolveResult::status / verbatim SolveResult::solver_status):
///  - |theta(U)| <= theta_tolerance          -> kConverged        "theta_below_tolerance"
///  - iterations == max_iterations            -> kMaxIterations    "max_iterations"
///  - CPU time >= max_cpu_seconds             -> kMaxTime          "max_cpu_seconds"
///  - no j <= max_armijo_exponent accepted    -> kStepTooSmall     "armijo_exponent_exceeded"
///    (the paper's rule: "terminated whenever the Armijo parameter is greater than 50")
///  - J(U0) or theta not finite               -> kNumericalFailure "nonfinite_cost" /
///                                                                 "nonfinite_theta"
///  - 0 < theta <= 64 eps sum_k h_k (|H(u*_k)| + |H(u_k)|)
///                                            -> kConverged        "theta_at_roundoff"
///    (theta is rounding noise of the sums: stationary to machine precision)
///  - theta > 0 above that (the minimizer did not minimize) -> kError "theta_positive"
/// Trial steps whose J is NaN/inf count as failed Armijo tests (the step is halved).
///
/// Result: controls piecewise constant on request.grid (the final U); state_grid = request.grid;
/// states X and costates Lambda of the final U; objective = the final discrete J; iterations =
/// accepted steps. history[i] describes iterate U_i (i = 0 is the starting control): J(U_i),
/// theta(U_i), the Armijo exponent that produced U_i (-1 for i = 0) and the cumulative CPU time.
/// The stopping test is made on the last record, so its theta is the final stationarity measure.
/// solver_stats: "final_theta" (theta of the returned controls), "simulations" (full
/// evaluations of J: 1 + every Armijo trial not rejected by the prefilter), "prefilter_rejections"
/// (trials rejected by a lower bound: the sum of "constant_bound_rejections",
/// "pointwise_bound_rejections" and "partial_rejections"), "cost_point_evaluations" (grid points
/// at which L was evaluated), "reformulated" (1 when a reformulation was solved).
/// `message` ends with the final J and theta.
///
/// The passes (simulation, the fused adjoint-and-direction sweep, the Armijo trials with their
/// bounds) are DescentPasses (solvers/descent_passes.h); a problem may speed them up with an
/// EulerStageModel (core/euler_stage_model.h) without changing a number.
class HamiltonianDescent final : public Solver {
 public:
  using Options = HamiltonianDescentOptions;

  HamiltonianDescent() = default;
  explicit HamiltonianDescent(const Options& options);

  /// The solver's options: every key (alpha, beta, max_iterations, max_armijo_exponent,
  /// theta_tolerance, max_cpu_seconds, path_penalty, regularization, armijo_prefilter) with its
  /// default (HamiltonianDescentOptions') and rule.
  static const OptionSchema& Schema();
  /// `base` with `options` applied: each value resolved by Schema() (unknown keys refused with
  /// the valid ones, values converted and checked), then IsValid. Throws std::invalid_argument.
  static Options ApplyOptions(const OptionMap& options, const Options& base = Options());

  /// Step 2 of the algorithm on `docp`'s grid: fills D (nu x N) with d_k = u*_k - u_k, u*_k =
  /// argmin_{u in U} H(t_k, x_k, u, lambda_{k+1}), and returns
  /// theta = sum_k h_k [H(t_k, x_k, u*_k, lambda_{k+1}) - H(t_k, x_k, u_k, lambda_{k+1})], given X
  /// from DiscreteOcp::Simulate(U) and Lambda from DiscreteOcp::Adjoint. `scratch` (resized to nx
  /// if needed) avoids allocation in repeated calls. Requires ocp.HasHamiltonianMinimizer().
  /// If theta_scale is given it receives sum_k h_k (|H(u*_k)| + |H(u_k)|), the magnitude against
  /// which theta's rounding error is judged.
  static double Direction(const DiscreteOcp& docp,
                          const Mat& U,
                          const Mat& X,
                          const Mat& Lambda,
                          Mat* D,
                          Vec* scratch,
                          double* theta_scale = nullptr);

  std::string name() const override { return "hamiltonian"; }
  const Options& options() const { return options_; }

  /// Solves with options_ overridden by request.options. Throws std::invalid_argument for an
  /// invalid request (bad options, a grid that does not span [t0, tf], an initial guess of the
  /// wrong size); numerical trouble and inapplicability are the result's status.
  SolveResult Solve(const Ocp& ocp, const SolveRequest& request) const override;

 private:
  Options options_;
};

}  // namespace ocpb
