// The indirect method: Newton's method on the discretized maximum principle (OCPBench solver
// "indirect-newton").
#pragma once

#include <limits>
#include <optional>
#include <string>

#include "core/control_trajectory.h"
#include "core/ocp.h"
#include "core/option_schema.h"
#include "core/time_grid.h"
#include "solvers/solver.h"

namespace ocpb {

/// Options of IndirectNewton. Keys for SolveRequest::options are the field names;
/// warm_start_options are given as "hamiltonian.<key>".
struct IndirectNewtonOptions {
  /// The sparse LU that factors the Newton matrix (unsymmetric), through Eigen's wrappers of
  /// SuiteSparse 5: UMFPACK (multifrontal, Davis 2004) or KLU (left-looking with BTF, Davis and
  /// Palamadai Natarajan 2010), or kRiccati: the structured sweep of BvpRiccatiSolver (O(N nx^3),
  /// no fill; on comm-path2d, N = 400, a factorization and solve in about 7e6 instructions
  /// against KLU's 1.5e7 (callgrind; solvers/README-family.md)), with KLU where the sweep declines
  /// (a singular interval block or a solve whose residual fails its test; solver_stats
  /// "riccati_fallbacks" counts them). Key "linear_solver": "umfpack" | "klu" | "riccati".
  enum class LinearSolver { kUmfpack, kKlu, kRiccati };
  /// Where Newton starts. Key "warm_start": "none" | "hamiltonian" | "ipopt".
  ///  - kNone: from the request's controls (states by RK4 simulation; costates from those
  ///    controls as `costates` says; IndirectNewton::StartFromControls);
  ///  - kHamiltonian: first runs the registered "hamiltonian" solver (penalty form, the
  ///    request's grid, integrator and initial guess, warm_start_options) and starts from its
  ///    states, with costates from its controls as `costates` says;
  ///  - kIpopt: first runs "ipopt" with its defaults on the trapezoid transcription of the
  ///    request's grid, terminal form and initial guess, and starts from its states (on its
  ///    state_grid: for a free final time stretched to Ipopt's T), with costates as `costates`
  ///    says (kAdjoint: Ipopt's multiplier costates).
  enum class WarmStart { kNone, kHamiltonian, kIpopt };
  /// How the start's costates are made from its controls u and states X. Key "costates":
  /// "fit" | "adjoint" | "default"; kDefault: kAdjoint with warm_start = kIpopt (a KKT point's
  /// multipliers are its costates; the fit cannot see controls on the boundary of U, such as the
  /// disc of brachistochrone-free-time, and gives zero costates there), kFit otherwise
  /// (EffectiveCostates()).
  ///  - kFit: the trapezoidal costate equation of u
  ///  (IndirectNewton::CostatesFromControls)
  ///    with the terminal costate chosen by least squares so that u is as stationary as it can be
  ///    (H_u = 0 wherever u is strictly inside U), i.e. so that u*(x_k, p_k) reproduces u_k. The
  ///    boundary condition p_N = grad Phi is left to Newton.
  ///  - kAdjoint: the costates of u itself: the same equation from p_N = grad Phi(x_N) (kNone),
  ///    the descent's own discrete adjoint (kHamiltonian), or Ipopt's costates from its
  ///    multipliers (kIpopt). These are what u's cost gradient uses,
  ///    but their terminal value 2 w psi(x_N) amplifies the terminal error a first-order method
  ///    leaves, so u*(x, p) can differ wildly from u (on comm-path2d after 200 descent iterations:
  ///    R* = 0 and |u*| = umax at every node; solvers/README-indirect.md).
  enum class Costates { kDefault, kFit, kAdjoint };

  /// Newton steps at most (>= 0; 0 only evaluates the start).
  int max_iterations = 50;
  /// CPU limit of the whole solve, a warm start included (> 0; inf: none). Tested before every
  /// Newton step and before every line-search trial after the first: the solve ends within one
  /// step's (one residual evaluation's, or one Jacobian and factorization's) cost of the limit,
  /// with kMaxTime ("max_cpu_seconds") and the last accepted iterate. A warm start gets the
  /// limit too (hamiltonian: max_cpu_seconds unless given; ipopt: max_cpu_time). Key
  /// "max_cpu_seconds".
  double max_cpu_seconds = std::numeric_limits<double>::infinity();
  /// Converged when ||F(z)||_inf <= tolerance (> 0), F the residual of PmpResidual.
  double tolerance = 1e-10;
  /// Armijo constant c in (0, 1/2): a step a along the Newton direction d is accepted when
  ///   1/2 ||F(z + a d)||^2 <= (1 - 2 c a) 1/2 ||F(z)||^2
  /// (the directional derivative of 1/2 ||F||^2 along d is -||F||^2).
  double sufficient_decrease = 1e-4;
  /// Backtracking factor in (0, 1): steps 1, backtrack, backtrack^2, ...
  double backtrack = 0.5;
  /// Smallest step tried, in (0, 1]; when no step >= min_step is accepted the solve ends with
  /// kStepTooSmall ("line_search_failed").
  double min_step = 1e-10;
  /// Stall test (>= 0; 0: off): the solve ends with kStepTooSmall ("stalled") after this many
  /// consecutive steps accepted only at a length <= kStallStep. Such steps leave ||F|| where it
  /// is: the semismooth merit has a kink there that the generalized Jacobian does not see
  /// (comm-path2d, gamma = 1e-4, hard form: 60 steps of length 2^-10 .. 2^-15 at ||F|| = 0.093,
  /// solvers/README-family.md); a caller with another way forward (the polish: more descent)
  /// saves those steps. Key "stall_steps".
  int stall_steps = 0;
  static constexpr double kStallStep = 1.0 / 256.0;
  /// KLU by default: on these banded systems it factors 2-4x faster than UMFPACK (measured in
  /// solvers/README-indirect.md).
  LinearSolver linear_solver = LinearSolver::kKlu;
  WarmStart warm_start = WarmStart::kNone;
  Costates costates = Costates::kDefault;
  /// `costates`, with kDefault resolved for `warm_start` (kFit or kAdjoint, never kDefault).
  Costates EffectiveCostates() const {
    if (costates != Costates::kDefault) return costates;
    return warm_start == WarmStart::kIpopt ? Costates::kAdjoint : Costates::kFit;
  }
  /// Options handed to the "hamiltonian" solver (keys "hamiltonian.<key>", resolved by its
  /// schema); only allowed with warm_start = kHamiltonian. path_penalty and regularization
  /// below are passed on to it unless given here.
  OptionMap warm_start_options;
  /// Passed to Ocp::HamiltonianReformulation: rho > 0 of a path-constraint penalty and eps > 0 of
  /// a control regularization, for problems that need a reformulation (unset: the problem's own
  /// default, stated in its header). Keys "path_penalty", "regularization".
  std::optional<double> path_penalty;
  std::optional<double> regularization;
  /// The discretization of the boundary-value problem (PmpResidual::Scheme): the trapezoid
  /// (default), or forward Euler with its exact discrete adjoint, whose solutions are the
  /// stationary points of the Euler discrete cost (what the Hamiltonian family's polish stage
  /// uses with SolveFrom; the result's controls are then u*(t_k, x_k, p_{k+1}), piecewise
  /// constant, and its objective the Euler J). Not a string option yet (no key): set it in code.
  enum class Scheme { kTrapezoid, kEuler };
  Scheme scheme = Scheme::kTrapezoid;

  /// False, with a one-line reason in *error, when a field violates its rule above.
  bool IsValid(std::string* error) const;
};

const char* ToString(IndirectNewtonOptions::LinearSolver solver);
const char* ToString(IndirectNewtonOptions::WarmStart warm_start);
const char* ToString(IndirectNewtonOptions::Costates costates);

/// Solves the maximum principle's boundary-value problem, discretized by trapezoidal collocation
/// on the request's grid (PmpResidual: unknowns x_k, p_k at the nodes, u_k = u*(t_k, x_k, p_k) from
/// Ocp::MinimizeHamiltonian, plus the multipliers nu of psi = 0 in the hard form), by Newton's
/// method with a backtracking Armijo line search on 1/2 ||F||^2 (Dennis and Schnabel, "Numerical
/// Methods for Unconstrained Optimization and Nonlinear Equations", 1983, Sec. 6.3 and 6.5):
///
///   J(z_k) d = -F(z_k),   z_{k+1} = z_k + a_k d,   a_k the first of 1, backtrack, ... accepted.
///
/// The Jacobian is sparse with a fixed structure (analyzed once, factored every step by UMFPACK or
/// KLU). Where u* is clipped by U the Jacobian is a generalized one (MinimizerDerivative), which
/// makes this a semismooth Newton method: locally superlinear, and quadratic where u* is smooth
/// (Qi and Sun 1993). The classical indirect ("Pontryagin") approach is Bryson and Ho, "Applied
/// Optimal Control", 1975, Ch. 7; its trapezoidal collocation is the scheme of Ascher, Mattheij and
/// Russell, "Numerical Solution of Boundary Value Problems for ODEs", 1995, Sec. 5.1.
///
/// Accuracy: the trapezoidal scheme is second order, so states, costates and the discrete cost
/// approach the continuous optimum as O(h^2) for smooth solutions (tested on the double
/// integrator with p*(t) = (-12, 12t - 6), from H = p^T f + L: p1' = 0, p2' = -p1, and on LQ
/// problems with Riccati costates).
///
/// Reformulation: like the Hamiltonian descent, the method solves
/// Ocp::HamiltonianReformulation({path_penalty, regularization}) in place of the problem when the
/// problem offers one (path constraints folded into L as an exterior penalty, eps |u|^2 added where
/// H is linear in u); the message then says so and solver_stats["reformulated"] = 1. The controls
/// are to be judged on the original problem (the common evaluator does).
///
/// Applicability (otherwise SolveStatus::kNotApplicable with the reason in `message`), for the
/// problem solved (the reformulation if any):
///  - Ocp::HasHamiltonianMinimizer(), with H strictly convex in u on the free directions (else
///    the Jacobian does not exist and the solve ends in kNumericalFailure, saying so);
///  - num_path() == 0;
///  - a fixed horizon, or a free final time (Ocp::free_final_time()): T is then one more
///    unknown with the condition H(T) = 0 (PmpResidual), the start's T is the request grid's tf
///    (the problem's nominal tf from `ocpbench`), and the grid's nodes keep their relative
///    positions. T stays within the problem's bounds (a trial step outside them is a failed
///    Armijo test), so an optimum on a bound, where H(T) != 0, ends in "line_search_failed".
///    (The time-scaled problems, problems/reference/scaled_min_time.h and scaled_free_time.h,
///    pose free time on a fixed horizon instead, for every method.)
/// Both terminal forms: kPenalty (p(tf) = grad Phi) and kHard (psi = 0, nu unknown).
///
/// Stopping (SolveResult::status / verbatim SolveResult::solver_status):
///  - ||F||_inf <= tolerance                      -> kConverged        "converged"
///  - max_iterations steps taken                  -> kMaxIterations    "max_iterations"
///  - CPU time >= max_cpu_seconds (before a step or a line-search trial)
///                                                -> kMaxTime          "max_cpu_seconds"
///  - no step >= min_step accepted                -> kStepTooSmall     "line_search_failed"
///  - stall_steps steps in a row of length <= kStallStep -> kStepTooSmall "stalled"
///  - the sparse LU reports the matrix singular   -> kNumericalFailure "singular_jacobian"
///  - NaN/inf in F or its Jacobian, or in the step -> kNumericalFailure "nonfinite_residual" /
///                                                                    "nonfinite_step"
///  - H_uu singular on the free directions        -> kNumericalFailure "singular_minimizer"
///  - (a trial step to a final time outside its bounds is a failed Armijo test)
///  - the warm start produced no states/costates  -> kError            "warm_start_failed"
///  - warm_start = hamiltonian on a problem with a free initial state (the descent does not
///    take it), before any work                   -> kNotApplicable    "not_applicable"
///  A free initial state and static parameters are solved through the transversality rows
///  (PmpResidual; the record's initial_state is x(t0)).
/// A trial point whose residual is not finite counts as a failed Armijo test.
///
/// Result: controls = u*(t_k, x_k, p_k) at the nodes, piecewise linear on state_grid (what the
/// trapezoidal scheme means); state_grid = request.grid, stretched to [t0, T] for a free final
/// time (solver_stats "final_time" = T); states X and costates P (nx x N+1) of the
/// last iterate; objective = its trapezoidal discrete cost (PmpResidual); iterations = Newton steps
/// taken. history[i] is iterate i (0 = the start): J = discrete cost, primal_inf = ||F||_inf,
/// armijo_j = number of backtracks of the step that produced it (-1 for i = 0), cpu_seconds
/// cumulative from the start of Solve (the warm start included). solver_stats (CPU seconds):
/// "assembly_seconds" (residual and Jacobian evaluations), "factorization_seconds" (symbolic and
/// numeric LU), "solve_seconds" (triangular solves), "newton_cpu_seconds", "start_cpu_seconds"
/// (Solve only: the start's states and costates from its controls, after any warm start),
/// "warm_start_cpu_seconds" and "warm_start_iterations" (warm starts only),
/// "start_adjoint_fallback" (when the start's costates come from the fit: 1 when the fit was
/// degenerate, a Mayer cost, and the adjoint sweep's costates were used instead, else 0),
/// "residual_inf",
/// "unknowns",
/// "jacobian_nonzeros", "residual_evaluations", "jacobian_evaluations", "reformulated";
/// "riccati_fallbacks" with linear_solver = kRiccati (steps whose system KLU solved instead).
class IndirectNewton final : public Solver {
 public:
  using Options = IndirectNewtonOptions;

  IndirectNewton() = default;
  /// Throws std::invalid_argument when !options.IsValid().
  explicit IndirectNewton(const Options& options);

  /// The solver's options (max_iterations, tolerance, sufficient_decrease, backtrack,
  /// min_step, linear_solver, warm_start, costates, path_penalty, regularization,
  /// hamiltonian.<key>), with defaults (IndirectNewtonOptions') and rules.
  static const OptionSchema& Schema();
  /// `base` with `options` applied (resolved by Schema()), then IsValid. Throws
  /// std::invalid_argument naming the key and its rule.
  static Options ApplyOptions(const OptionMap& options, const Options& base = Options());

  /// A start from controls: X by RK4 simulation of `controls` on `grid` (core Evaluate), P by
  /// CostatesFromControls(..., how).
  static void StartFromControls(const Ocp& ocp,
                                const TimeGrid& grid,
                                TerminalMode mode,
                                const ControlTrajectory& controls,
                                Mat* X,
                                Mat* P,
                                Options::Costates how = Options::Costates::kAdjoint);

  /// Costates P (nx x N+1) for controls u(t) and states X (nx x N+1) on `grid`: the trapezoidal
  /// rule applied to the linear costate equation p' = -H_x(t, x, u(t), p), with u(t) taken from
  /// the right at t_k and from the left at t_{k+1} on interval k, so that p_k = M_k q + c_k is
  /// affine in the terminal costate q = p_N. Then
  ///  - kAdjoint: q0 = grad Phi(x_N) (penalty form) or grad phi(x_N) (hard form);
  ///  - kFit (and kDefault): q minimizes
  ///      sum_k w_k |(H_uu,k)_F^-1 (H_u,k)_F|^2 + delta^2 |q - q0|^2,
  ///    H_u,k = L_u + f_u^T p_k(q) at (t_k, x_k, u_k), F the components of u_k strictly inside U
  ///    (box components more than 1e-6 of their range from a bound; ball blocks with |u - c| <
  ///    (1 - 1e-6) r), w_k the trapezoidal weights of the nodes. Each node's residual is the
  ///    Newton step of u_k towards argmin H (H_uu at p_k(q0); unweighted where that block is not
  ///    positive definite), so the sum measures |u*(x, p) - u| in the controls' own units. The
  ///    ridge delta = 1e-8 max_j |column j| keeps q0 in the directions the controls do not
  ///    determine (q = q0 when no component is free). The solve is FitTerminalCostate
  ///    (solvers/costate_fit.h), shared with FitEulerCostates. A degenerate fit (a Mayer cost
  ///    along the controls, L = 0: the rows are homogeneous and the fitted costates
  ///    near zero) is replaced by the adjoint sweep with q = grad Phi(x_N) of the penalty form (in
  ///    the hard form grad phi + psi_x^T nu with the penalty's estimate nu = 2 w psi(x_N));
  ///    *adjoint_fallback (may be null) receives whether that happened (false for kAdjoint).
  static void CostatesFromControls(const Ocp& ocp,
                                   const TimeGrid& grid,
                                   TerminalMode mode,
                                   const ControlTrajectory& controls,
                                   const Mat& X,
                                   Options::Costates how,
                                   Mat* P,
                                   bool* adjoint_fallback = nullptr);

  std::string name() const override { return "indirect-newton"; }
  const Options& options() const { return options_; }

  /// Solves with options_ overridden by request.options, from the warm start, or else from
  /// request.initial_guess (default: DefaultInitialGuess) with states request.initial_states
  /// (default: RK4 simulation of the controls) and costates request.initial_costates (default:
  /// from the controls as the `costates` option says), each sampled at the grid's nodes; for a
  /// free final time the start's T is the guess's own end when the bounds admit it (a previous
  /// solution's T). Throws std::invalid_argument for an invalid request (bad options, a grid
  /// that does not span [t0, tf], guesses of the wrong size); numerical trouble is the result's
  /// status.
  SolveResult Solve(const Ocp& ocp, const SolveRequest& request) const override;

  /// Newton from an explicit start: X and P (nx x N+1) on request.grid, for example a
  /// Hamiltonian-descent result's states and costates (its Euler discrete adjoint Lambda is within
  /// O(h) of p(t)). nu (hard form; size npsi) defaults to the least-squares solution of
  /// p_N = grad phi(x_N) + psi_x(x_N)^T nu. request.initial_guess and warm_start are ignored; the
  /// reformulation applies as in Solve().
  SolveResult SolveFrom(const Ocp& ocp,
                        const SolveRequest& request,
                        const Mat& X,
                        const Mat& P,
                        const Vec* nu = nullptr) const;

 private:
  Options options_;
};

}  // namespace ocpb
