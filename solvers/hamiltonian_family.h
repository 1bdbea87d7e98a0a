// The Hamiltonian family: the paper's descent with a proximal direction, an augmented-Lagrangian
// outer loop (hard terminal form, path constraints), a free final time and a Newton polish.
#pragma once

#include <limits>
#include <optional>
#include <string>

#include "core/option_schema.h"
#include "solvers/augmented_lagrangian_loop.h"
#include "solvers/descent_loop.h"
#include "solvers/indirect_newton.h"
#include "solvers/solver.h"

namespace ocpb {

/// Options of HamiltonianFamily (every default documented; the presets of the family's methods
/// are HamiltonianFamily::Proximal(), AugmentedLagrangian() and Polished()).
struct HamiltonianFamilyOptions {
  enum class Direction {
    kPaper,     ///< u* = argmin H (the paper's)
    kProximal,  ///< argmin H + |w - u|^2 / (2 eps) (Sakawa and Shindo), eps by `proximal`
  };
  /// The discretization the descent works on (key "scheme"): forward Euler with one control per
  /// interval (the default, every ingredient; the request's integrator), or an explicit
  /// Runge-Kutta scheme with one control per stage (StageRkOcp, Hager's transformed adjoint):
  /// kRk2 Heun (c = (0, 1), b = (1/2, 1/2)), kRk4 the classical one (b = (1/6, 1/3, 1/3, 1/6)),
  /// of order 2 and 4 for the control problem (RkTableau, HagerOrderConditions). With kRk2 and
  /// kRk4 the descent (either direction) in the penalty form, the hard terminal form by the
  /// augmented-Lagrangian loop, a free final time (dJ/dT through the stages), and the polish as
  /// projected truncated Newton on the stage controls (StageNewton; a fixed horizon); path
  /// constraints in the loop are Euler's and report kNotApplicable naming the option, as does a
  /// request integrator other than euler (the scheme replaces it).
  enum class Scheme { kEuler, kRk2, kRk4 };
  enum class PathConstraints {
    kReformulation,        ///< Ocp::HamiltonianReformulation's penalty (the paper's method's)
    kAugmentedLagrangian,  ///< the outer loop's multipliers (AugmentedLagrangianOcp)
  };

  // ---- the descent ----
  /// Armijo constants and limits as HamiltonianDescentOptions: alpha, beta in (0, 1),
  /// max_armijo_exponent >= 0; armijo_prefilter as there (same iterates).
  double alpha = 0.1;
  double beta = 0.5;
  int max_armijo_exponent = 50;
  bool armijo_prefilter = true;
  /// Descent steps at most, over every phase and outer iteration (>= 0); with the polish, the
  /// descent's steps before Newton's first attempt (the Polished() preset: 250).
  int max_iterations = 500;
  /// Penalty form: stop when |theta| <= relative_theta_tolerance (1 + |J|) (>= 0; 0: off). With
  /// polish, the descent hands over to Newton at this level (polish_switch below).
  double relative_theta_tolerance = 0.0;
  /// CPU limit of the whole solve (> 0).
  double max_cpu_seconds = std::numeric_limits<double>::infinity();
  /// Passed to Ocp::HamiltonianReformulation (unset: the problem's defaults).
  std::optional<double> path_penalty;
  std::optional<double> regularization;
  Direction direction = Direction::kPaper;
  Scheme scheme = Scheme::kEuler;
  /// The proximal direction's eps schedule (used with kProximal).
  ProximalSchedule proximal;

  // ---- the augmented Lagrangian: the hard terminal form, and path constraints with kAL ----
  PathConstraints path = PathConstraints::kReformulation;
  AugmentedLagrangianRule augmented_lagrangian;

  // ---- free final time (problems with Ocp::free_final_time(); forward Euler) ----
  /// The first T step moves T by at most this fraction of T - t0 (> 0); the step then follows
  /// the Armijo outcome (DescentPasses::EnableFreeFinalTime).
  double free_time_initial_fraction = 0.1;

  // ---- polish: Newton on the Euler maximum principle (PmpResidual::Scheme::kEuler); with
  // scheme rk2/rk4 projected truncated Newton on the stage controls (StageNewton: newton_max_
  // iterations, newton_tolerance on its projected residual, newton_backtrack and newton_
  // sufficient_decrease on J; one attempt, no grid sequencing, no Riccati sweep) ----
  bool polish = false;
  /// The descent hands over when |theta| <= polish_switch (1 + |J|) or at max_iterations (> 0).
  double polish_switch = 1e-3;
  /// Newton's limits (IndirectNewtonOptions: max_iterations >= 0, tolerance > 0 on ||F||_inf).
  int newton_max_iterations = 100;
  double newton_tolerance = 1e-10;
  /// How Newton's linear systems are solved (IndirectNewtonOptions::LinearSolver; key
  /// "newton_linear_solver": "riccati" | "klu" | "umfpack"): the Riccati sweep of
  /// BvpRiccatiSolver (KLU where it declines) by default: the same steps as KLU's to roundoff
  /// (the path of a long semismooth solve can still part at a kink) for about half of KLU's
  /// factorization and solve instructions (solvers/README-family.md).
  /// IndirectNewtonOptions::stall_steps: an attempt ends ("stalled") after this many Newton
  /// steps in a row of length <= 1/256, and the descent continues (>= 0; 0: off). Key
  /// "newton_stall_steps".
  int newton_stall_steps = 0;
  /// Newton's backtracking line search on 1/2 ||F||^2 (IndirectNewtonOptions::backtrack and
  /// sufficient_decrease: steps 1, b, b^2, ... until the Armijo test with constant c holds). Keys
  /// "newton_backtrack" (in (0, 1), default 0.5) and "newton_sufficient_decrease" (in (0, 1/2),
  /// default 1e-4). Other values were measured on comm-path2d and not adopted: the semismooth
  /// path is chaotic in them (solvers/README-family.md).
  double newton_backtrack = 0.5;
  double newton_sufficient_decrease = 1e-4;
  IndirectNewtonOptions::LinearSolver newton_linear_solver =
      IndirectNewtonOptions::LinearSolver::kRiccati;
  /// Newton attempts at most (>= 1). When Newton does not converge, the descent continues from
  /// its own last iterate for as many steps again as it has taken (its budget doubles) and Newton
  /// starts over from there: Newton's basin on the semismooth maximum principle is irregular
  /// (comm-path2d, hard form, gamma = 1e-5: a start from 250 descent steps fails on some channel
  /// seeds and a later one converges; solvers/README-family.md). 6 attempts: up to 8000 steps.
  int polish_attempts = 6;
  /// Before each Newton attempt, the costate of every integrator state (a state no dynamics and
  /// no running cost depend on, such as comm-path2d's bits) is set to the constant that meets
  /// that state's terminal condition with the other states and costates held, and the state's
  /// row to its Euler trajectory under the resulting u* (ConstantCostateStart; on comm-path2d:
  /// the bit budget's water-filling along the descent's path). Exact for the Euler maximum
  /// principle (such a costate is constant there); skipped where no component qualifies or no
  /// root is bracketed. solver_stats "start_constant_costates" (components set, last attempt)
  /// and "start_constant_costate_evaluations" (scalar equation evaluations, all attempts). Key
  /// "polish_constant_costate_start". Off by default: on comm-path2d's hard form it makes Newton
  /// slower at every gamma <= 1e-3 (the descent's path is far from the optimum's, and the
  /// budget's costate on that path is 30x the optimum's; solvers/README-family.md).
  bool polish_constant_costate_start = false;
  /// Grid sequencing of the polish (solvers/grid_sequence.h). With L > 0 halvings of the
  /// request's grid, the whole polish (descent, fitted costates, one Newton attempt) runs on the
  /// grid of every 2^L-th node, then Newton on each finer grid (every 2^(L-1)-th node, ..., the
  /// request's) from the coarser solution's states and costates interpolated linearly (a free
  /// final time keeps the coarser solution's T as its start; nu is re-estimated from p_N); the
  /// coarsest grid's last Newton iterate starts the finer grids even when it did not converge
  /// (it stops mostly at a kink of the semismooth residual near the solution). The
  /// descent and Newton's steps through the moving active set are paid on the coarse grid, and
  /// each finer grid takes a few steps (Newton's mesh independence: comm-path2d, N = 400: 3-4
  /// steps from the interpolated N = 200 solution; solvers/README-family.md). Where Newton on a
  /// finer grid fails (or the coarsest grid's polish leaves no finite iterate), the request's
  /// grid is solved as without sequencing (all polish_attempts), after the failed sequence, and
  /// the record says so; when max_cpu_seconds is reached first, the result is the controls of
  /// the finest grid the sequence solved (else the coarsest grid's) on the request's grid
  /// (status kMaxTime; newton_iterations then counts every grid's steps). L is the largest level <=
  /// polish_coarse_levels at which every grid has an even number of intervals to halve and the
  /// coarsest keeps at least polish_coarse_min_intervals: with the defaults (2, 100) N = 400 ->
  /// 200 -> 100, N = 200 -> 100, N = 300 -> 150, and no sequencing for N < 200, odd N, or
  /// newton_max_iterations = 0. Keys "polish_coarse_levels" (>= 0; 0: off) and
  /// "polish_coarse_min_intervals" (>= 1).
  int polish_coarse_levels = 2;
  int polish_coarse_min_intervals = 100;

  bool IsValid(std::string* error) const;
};

/// The family of the paper's method, each ingredient an option of one solver (documented in
/// solvers/README-family.md), all on the discrete problem of the request's grid and integrator
/// (forward Euler: the exact discrete adjoint; everything below is exact for that discrete
/// problem):
///
///  1. direction: the paper's u* or the proximal minimizer (DescentPasses::Backward);
///  2. terminal form: penalty (the paper's Phi, as `hamiltonian`) or hard psi(x(tf)) = 0 by the
///     augmented-Lagrangian outer loop (RunAugmentedLagrangian) with the descent as the inner
///     solver; path constraints c <= 0 by the same loop (kAugmentedLagrangian) or by the
///     problem's penalty reformulation (kReformulation, as `hamiltonian`);
///  3. free final time: T is a variable with the exact dJ/dT (DescentPasses);
///  4. polish: after the descent (|theta| <= polish_switch (1 + |J|) or max_iterations; for the
///     hard form the descent runs on the penalty form, a better start for Newton than the outer
///     loop's first iterations), the
///     costates are fitted to its controls (FitEulerCostates; for a Mayer cost, where the fit is
///     degenerate, the adjoint sweep's) and IndirectNewton with
///     Scheme::kEuler solves the Euler maximum principle of the same discrete problem (penalty
///     or hard form, T included) from its states: the optimum of the discrete problem to Newton's
///     tolerance, the Euler transcription's NLP optimum. On grids of an even number >= 200 of
///     intervals the polish is grid-sequenced by default (polish_coarse_levels): it runs on a
///     coarser grid first and Newton refines the solution grid by grid.
///
/// Result: controls piecewise constant on state_grid (the request's grid, stretched to T for a
/// free final time); states, costates of the final iterate (the polished one with polish);
/// objective = the final discrete J of the problem solved in the request's terminal form (hard:
/// without penalty or multiplier terms); iterations = descent steps + Newton steps. history, in
/// the order of execution and numbered by position: the descent's rows (J of the problem being
/// descended: the AL's J_A inside the outer loop), then each Newton attempt's (primal_inf =
/// ||F||_inf; J its discrete cost) and the descent's continuation between attempts. Status: without
/// polish the descent's (or the outer loop's: "al_converged", "al_max_outer_iterations",
/// "max_iterations", or the inner failure's code); with polish Newton's (its solver_status
/// verbatim); when Newton does not converge the result keeps the descent's controls, states and J,
/// and says so. solver_stats: "descent_iterations", "descent_cpu_seconds" (the descent's CPU,
/// the outer loop's and the continuations' between Newton attempts included), "final_theta",
/// "simulations", "prefilter_rejections", "reformulated"; AL: "outer_iterations",
/// "terminal_residual", "path_violation", "penalty", "nu_<i>" (the final terminal multipliers,
/// those of psi_i = 0 in the Lagrangian J + nu^T psi); free time: "final_time", "dJdT"; free
/// initial state (forward Euler): "initial_state_stationarity" (at the descent's end,
/// DescentPasses::InitialStateStationarity), and the result's initial_state is x(t0) of its
/// states (the descent's, or Newton's when the polish converged); polish:
/// "newton_iterations", "newton_cpu_seconds", "newton_residual_inf" and Newton's own stats prefixed
/// "newton_", "start_adjoint_fallback" (last attempt: 1 when the fit was degenerate, a Mayer cost
/// L = 0, and Newton started from the descent's adjoint sweep instead, FitEulerCostates; else 0);
/// with polish_constant_costate_start "start_constant_costates" and
/// "start_constant_costate_evaluations". Grid sequencing (polish_coarse_levels): "coarse_levels"
/// (halvings used; 0: the polish ran on the request's grid alone), and when > 0
/// "coarse_intervals" (the coarsest grid's), "coarse_newton_iterations" (Newton steps there),
/// "coarse_newton_converged" (1 when the coarsest grid's Newton converged, else 0),
/// "fine_newton_iterations" (on the finer grids), "coarse_cpu_seconds" (the coarsest grid's
/// descent and Newton), "fine_cpu_seconds" (Newton on the finer grids), "coarse_fallback" (1
/// when the sequence failed and the request's grid was solved without it), and with a fallback
/// "coarse_fallback_intervals" (the grid whose Newton failed: the coarsest when it left no
/// finite iterate) and "coarse_failed_iterations" (the failed sequence's steps). When the
/// sequence converged, the descent's stats ("descent_*", "final_theta", "simulations",
/// "prefilter_rejections", "dJdT", "start_constant_*") and "newton_attempts" are the coarsest
/// grid's, "newton_iterations" and "newton_cpu_seconds" sum every grid's, and the other
/// "newton_<key>" and "newton_residual_inf" are the request grid's Newton's; after a fallback
/// all of these describe the solve on the request's grid alone (the failed sequence is in the
/// coarse_* stats). The history holds the rows of every grid in the order of execution, each
/// coarser grid's rows with their grid's IterationRecord::intervals (their J is that grid's
/// discrete J); `iterations` counts every step taken, a failed sequence's included.
///
/// With scheme = rk2 or rk4 (Options::Scheme) the descent runs on the stage controls of that
/// Runge-Kutta scheme (StageDescentPasses), in the hard form inside the outer loop (terminal
/// multipliers only): the result's controls are a
/// custom trajectory, per interval the polynomial through the stage controls at their abscissae
/// c_i (stages with equal c averaged: Heun linear, RK4 quadratic through 0, 1/2, 1), projected
/// onto U; states and costates are the scheme's nodes x_k and lambda_k; objective the scheme's
/// discrete J (hard form: without penalty or multiplier terms); solver_stats add
/// "scheme_stages" (s) and "stage_controls" (s N). With polish (a fixed horizon) the descent runs
/// on the penalty form up to polish_switch or max_iterations and StageNewton minimizes the scheme's
/// J from its controls: in the hard form inside a multiplier loop of Newton solves to max |psi| <=
/// newton_tolerance (StageNewtonAugmentedLagrangian; from nu = 0 with the AL rule's
/// initial_penalty, penalty_growth, max_penalty, max_outer_iterations; the costates from the
/// adjoint at the last solve's (nu, rho); "outer_iterations", "terminal_residual", "penalty",
/// "nu_<i>"); one attempt, not grid-sequenced. Its iterate is the result's (its line search accepts
/// only decreases of J, or J_A, to J's rounding), its status the polish's (solver_status
/// "stage_newton_<code>": converged, max_iterations, line_search and rounding -> step_too_small,
/// not_finite
/// -> numerical_failure, max_cpu_seconds, max_outer_iterations); stats "newton_iterations",
/// "newton_hessian_products", "newton_cg_iterations", "newton_residual_inf" (the projected
/// residual), "newton_cpu_seconds"; one history row for the polished iterate (dual_inf: the
/// projected residual; primal_inf: the terminal residual in the hard form).
///
/// Not applicable (kNotApplicable, reason in `message`): no Hamiltonian minimizer; path
/// constraints left after the choice of `path`; a free final time with the request integrator RK4
/// (scheme euler); a polish with path constraints handled by the outer loop (Newton takes none);
/// with scheme rk2 or rk4 path constraints in the outer loop, a request integrator other than
/// euler, or a polish with a free final time (each message
/// names the scheme).
class HamiltonianFamily final : public Solver {
 public:
  using Options = HamiltonianFamilyOptions;
  /// The registered methods: each is the family with one ingredient on by default (and every
  /// other one an option): "hamiltonian-proximal" (direction = proximal), "hamiltonian-al"
  /// (path = augmented-lagrangian; the hard form uses the outer loop in every preset),
  /// "hamiltonian-polish" (polish = true).
  enum class Preset { kProximal, kAugmentedLagrangian, kPolish };

  /// The registered method `preset` with its defaults.
  explicit HamiltonianFamily(Preset preset = Preset::kProximal);
  /// Given options (validated: throws std::invalid_argument when !options.IsValid()); request
  /// options are applied over them by `preset`'s schema.
  HamiltonianFamily(const Options& options, Preset preset = Preset::kProximal);

  /// The presets' defaults: the proximal direction; the outer loop for path constraints too;
  /// the polish.
  static Options Proximal();
  static Options AugmentedLagrangian();
  static Options Polished();
  static Options Defaults(Preset preset);
  static const char* Name(Preset preset);
  /// The one-line description `ocpbench list solvers` prints.
  static const char* Description(Preset preset);
  /// The option schema of each registered method (`ocpbench describe solver NAME`): one set of
  /// keys, each preset's defaults.
  static const OptionSchema& Schema(Preset preset);
  /// `base` with `options` applied and validated; throws std::invalid_argument naming the key.
  static Options ApplyOptions(Preset preset, const OptionMap& options, const Options& base);

  std::string name() const override { return Name(preset_); }
  const Options& options() const { return options_; }

  /// Throws std::invalid_argument for an invalid request: bad options, a grid that does not
  /// span the horizon, an initial guess of the wrong size.
  SolveResult Solve(const Ocp& ocp, const SolveRequest& request) const override;

 private:
  Preset preset_;
  Options options_;
};

}  // namespace ocpb
