// The "riccati-ip" solver: a primal-dual interior-point method on the Euler and trapezoid
// transcriptions whose Newton step is a stagewise Riccati recursion
// (solvers/README-riccati-ip.md).
#pragma once

#include <memory>
#include <string>

#include "core/option_schema.h"
#include "solvers/nlp_solve.h"
#include "solvers/solver.h"
#include "transcriptions/transcription.h"

namespace ocpb {

/// Options of riccati-ip. Names and defaults follow Ipopt's where the meaning is the same, so
/// that the two compare at equal settings.
struct RiccatiIpOptions {
  /// Converged when the scaled KKT error E_0 (Ipopt's: dual infeasibility / s_d, constraint
  /// violation, complementarity / s_c, s_max = 100) is <= tol and the unscaled dual
  /// infeasibility, constraint violation and complementarity are below dual_inf_tol,
  /// constr_viol_tol and compl_inf_tol. Ipopt's default.
  double tol = 1e-8;
  double dual_inf_tol = 1.0;
  double constr_viol_tol = 1e-4;
  double compl_inf_tol = 1e-4;
  /// Ipopt's acceptable level: a point whose scaled KKT error is <= acceptable_tol and whose
  /// unscaled dual infeasibility, constraint violation and complementarity are below the three
  /// acceptable_*_tol is acceptable. The solve stops with Solved_To_Acceptable_Level (status
  /// acceptable) after acceptable_iter consecutive acceptable iterates (0: never), or when the
  /// line search fails at an acceptable point. Ipopt's defaults.
  double acceptable_tol = 1e-6;
  int acceptable_iter = 15;
  double acceptable_dual_inf_tol = 1e10;
  double acceptable_constr_viol_tol = 1e-2;
  double acceptable_compl_inf_tol = 1e-2;
  /// Iterative refinement of every Newton step in the condensed stagewise system: at least
  /// min_refinement_steps and at most max_refinement_steps corrections (each a vector pass of
  /// the factorized recursion), stopping once the residual ratio
  /// ||r|| / (min(||sol||, 1e6 ||rhs||) + ||rhs||) is <= 1e-10 or stops falling; min <= max.
  /// Ipopt's names and rule (Ipopt refines the full primal-dual system); the default minimum is
  /// 0, not Ipopt's 1: the residual is checked every step and corrected where the ratio asks
  /// for it (a correction every step cost 30 % more instructions on comm-path2d at N = 400,
  /// the check alone 8 %; solvers/README-riccati-ip.md).
  int min_refinement_steps = 0;
  int max_refinement_steps = 10;
  /// Second-order corrections tried when a full first trial step is rejected without a
  /// decrease in the constraint violation (Wächter & Biegler's, Ipopt's max_soc); 0: none.
  int max_soc = 4;
  /// Iteration limit (status max_iterations; restoration iterations count). Ipopt's default.
  int max_iter = 3000;
  /// CPU time limit in seconds (status max_time).
  double max_cpu_time = 1e6;
  /// The first barrier parameter; then Fiacco-McCormick (monotone) decreases
  /// mu <- max(min(tol, compl_inf_tol) / 11, min(0.2 mu, mu^1.5)) whenever the barrier
  /// problem's error <= 10 mu. Ipopt's rule and default.
  double mu_init = 0.1;
  /// How far the starting controls, states (and slacks) are pushed inside their bounds, absolutely
  /// (bound_push, times max(1, |bound|)) and relative to the interval (bound_frac). Ipopt's.
  double bound_push = 1e-2;
  double bound_frac = 1e-2;
  /// Every inequality (control and state bounds, path constraints, balls) is relaxed by this factor
  /// times max(1, |bound|) before the solve, as Ipopt does with the same default, so that the two
  /// solve the same problem. 0: no relaxation.
  double bound_relax_factor = 1e-8;
  /// "gradient-based" (Ipopt's default rule, objective only: f is multiplied by
  /// min(1, nlp_scaling_max_gradient / ||grad f(z0)||_inf)) or "none". Constraint rows are not
  /// scaled (Ipopt scales them by the same rule; see the README for the consequence).
  std::string nlp_scaling_method = "gradient-based";
  double nlp_scaling_max_gradient = 100.0;
  /// 0 silent, 1 one line per iteration on stderr.
  int print_level = 0;

  static const OptionSchema& Schema();
  /// `base` with `options` applied; throws std::invalid_argument naming the key and the rule.
  static RiccatiIpOptions Apply(const OptionMap& options, RiccatiIpOptions base);
};

/// Why riccati-ip cannot solve `request` on `ocp` (empty when it can): a transcription other
/// than "euler" and "trapezoid" (since 2026-12-07), a transcription scaling other than the
/// identity, or mesh refinement. A free or partly free initial state, static parameters, state
/// bounds, a free final time, boundary equalities and inequalities and fixed control
/// components (lower == upper: no variables) are in its class on both. An empty or
/// unknown transcription name is not a reason: Solve throws std::invalid_argument for it, as
/// every NLP solver does.
std::string RiccatiIpNotApplicable(const Ocp& ocp, const SolveRequest& request);

/// Runs the interior-point method on a TranscribedNlp made by the Euler or the trapezoid
/// transcription (with the identity scaling; a free final time is its last variable),
/// from its StartingPoint (the name is kept from when Euler was the only scheme). The NLP's own
/// callbacks are not used for the iterations: the stage structure is read off its layout and every
/// value and derivative comes from its Ocp, one pass per node. The solution is in the NLP's
/// variables and multiplier convention (core/nlp.h), so SolveTranscribed fills a SolveResult from
/// it as it does for Ipopt. A NLP of another shape gives status kNotApplicable.
///
/// Statuses (solver_status verbatim): Solve_Succeeded (kConverged), Solved_To_Acceptable_Level
/// (kAcceptable: RiccatiIpOptions' acceptable level), Maximum_Iterations_Exceeded
/// (kMaxIterations), Maximum_CpuTime_Exceeded (kMaxTime), Restoration_Failed
/// (kNumericalFailure, as Ipopt's is mapped: the filter line search reached its minimal step and
/// the restoration phase could not decrease the constraint violation; in the phase a step that
/// cannot be computed or a derivative that is not finite end as in the main loop, below),
/// Error_In_Step_Computation (kNumericalFailure: the regularization exceeded 1e40),
/// Invalid_Number_Detected (kNumericalFailure: a value at the starting point or a derivative is
/// not finite), not_applicable (kNotApplicable).
///
/// Stats: riccati_ip_iterations, riccati_ip_regularizations (iterations whose KKT matrix needed
/// delta_w > 0), riccati_ip_factorizations (Riccati recursions run, retries included),
/// riccati_ip_line_search_trials, riccati_ip_refinement_steps (iterative refinement
/// corrections), riccati_ip_soc_trials (second-order corrections computed),
/// riccati_ip_soc_accepted, riccati_ip_restoration_phases (times the restoration phase was
/// entered), riccati_ip_restoration_iterations, riccati_ip_restoration_damped_steps (restoration
/// steps recomputed with Levenberg-Marquardt damping), riccati_ip_kkt_cpu_seconds (building and
/// solving the stagewise KKT system), riccati_ip_callback_cpu_seconds (Ocp evaluations),
/// riccati_ip_cpu_seconds (the whole method), riccati_ip_kkt_error (scaled E_0 at the end),
/// riccati_ip_dual_inf, riccati_ip_constr_viol, riccati_ip_complementarity (unscaled),
/// riccati_ip_mu (final), riccati_ip_objective_scale.
NlpSolution SolveEulerNlpWithRiccatiIp(const TranscribedNlp& nlp, const RiccatiIpOptions& options);

/// The solver, registered as "riccati-ip". Solve returns not_applicable (with
/// RiccatiIpNotApplicable's reason) outside the supported class and otherwise runs
/// SolveTranscribed with SolveEulerNlpWithRiccatiIp as the backend.
class RiccatiIpSolver final : public Solver {
 public:
  std::string name() const override { return "riccati-ip"; }
  SolveResult Solve(const Ocp& ocp, const SolveRequest& request) const override;
};

// ---- for tests ------------------------------------------------------------------------------

/// The Euler (or trapezoid) NLP's Lagrangian as riccati-ip assembles it, node by node, at NLP
/// variables z and
/// NLP multipliers lambda (core/nlp.h convention, sigma = 1, no bound terms): its value, its
/// gradient with respect to z (x_0 included) and its Hessian (dense, n x n). Exposed so that the
/// hand-assembled stage derivatives can be tested against finite differences and against the
/// NLP's own callbacks. False when `nlp` is not a supported Euler or trapezoid NLP.
bool EulerStageLagrangian(const TranscribedNlp& nlp,
                          const Vec& z,
                          const Vec& lambda,
                          double* value,
                          Vec* gradient,
                          Mat* hessian);

}  // namespace ocpb
