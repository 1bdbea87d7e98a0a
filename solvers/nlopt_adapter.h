// NLopt on an OCPBench Nlp: dense gradients, vector constraints, exceptions mapped to statuses.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "core/nlp.h"
#include "core/option_schema.h"
#include "core/solve_result.h"
#include "solvers/nlp_solve.h"

namespace ocpb {

/// Options of the NLopt backend (S. G. Johnson, The NLopt nonlinear-optimization package,
/// https://github.com/stevengj/nlopt). Stopping tests are NLopt's: a run stops at the first that
/// holds.
struct NloptOptions {
  /// Algorithm by NLopt's name without "NLOPT_": LD_SLSQP (Kraft 1988, dense SQP, all constraint
  /// kinds), LD_MMA (Svanberg 2002, inequalities only), LD_CCSAQ (Svanberg 2002, inequalities
  /// only), LD_LBFGS (bounds only), AUGLAG or AUGLAG_EQ (augmented Lagrangian, Conn-Gould-Toint /
  /// Birgin-Martinez, around local_algorithm; AUGLAG_EQ keeps the inequalities in the local
  /// algorithm). See NloptAlgorithmNames().
  std::string algorithm = "LD_SLSQP";
  /// The subsidiary algorithm of AUGLAG / AUGLAG_EQ: LD_LBFGS, LD_MMA, LD_CCSAQ or LD_SLSQP.
  std::string local_algorithm = "LD_LBFGS";

  // ---- stopping tests (NLopt: stop when a step changes f by less than ftol_rel |f|, or every
  // ---- z_i by less than xtol_rel |z_i|; <= 0 disables a test) ----------------------------
  double ftol_rel = 1e-10;
  double xtol_rel = 1e-8;
  /// Stop after this many objective evaluations (kMaxTime, "evaluation limit").
  int maxeval = 20000;
  /// Stop after this many seconds of wall time (kMaxTime).
  double maxtime = 600.0;
  /// The same tests for the subsidiary algorithm of AUGLAG / AUGLAG_EQ.
  double local_ftol_rel = 1e-12;
  double local_xtol_rel = 1e-10;
  int local_maxeval = 5000;

  // ---- constraints -------------------------------------------------------------------------
  /// NLopt's per-constraint tolerance: a constraint counts as satisfied within this.
  double constraint_tol = 1e-8;
  /// OCPBench's check after NLopt says it converged: if max_i violation (NlpViolation) at the
  /// returned point exceeds feasibility_tol, the status becomes kInfeasible (NLopt's status is
  /// still kept verbatim). NLopt's convergence tests look at f and z only, not at feasibility.
  double feasibility_tol = 1e-6;
  /// OCPBench's second check when NLopt stops on FTOL_REACHED or XTOL_REACHED (its tests look
  /// at the size of the last change, not at the gradient): the relative stationarity residual
  /// with least-squares multipliers (NlpStationarity, active within 1e-4 relative) must not
  /// exceed stationarity_tol, else the status becomes kStepTooSmall (progress stopped at a
  /// non-stationary point; NLopt's name is kept verbatim). The default separates what was
  /// measured: converged runs 2e-9 .. 2.2e-3 (single shooting, C = 500), a false FTOL_REACHED
  /// of AUGLAG(LBFGS) at J = 2.56e6 on comm-path2d 1.0 (solvers/README-nlp.md).
  double stationarity_tol = 1e-2;

  // ---- refusal limits: cases that would run for hours are refused with kNotApplicable ---------
  /// Dense constraint Jacobian: refuse when m * n exceeds this. NLopt's vector constraints take
  /// a dense m x n gradient array, filled at every evaluation. Measured (solvers/README-nlp.md,
  /// BM_NloptSingleShootingScaling): AUGLAG(LD_LBFGS) on the paper's problem, single shooting,
  /// peak memory +77 MB at m n = 7.7e6 (N = 1600) and +151 MB at 1.7e7 (N = 2400), about 9 bytes
  /// per entry; 8.3 and 16.4 ms CPU per evaluation; converging runs need 500-1700 evaluations.
  /// At the limit, 2e7: ~175 MB and about 10-35 s CPU per run.
  double max_dense_jacobian = 2e7;
  /// LD_SLSQP: refuse when n exceeds this (its quasi-Newton matrix and least-squares
  /// subproblem, bounds included, are dense: O(n^2) memory, O(n^3) per iteration). Measured on
  /// the paper's problem, single shooting (solvers/README-nlp.md): CPU per evaluation 42 ms at
  /// n = 300, 0.10 s at 399, 0.17 s at 501, 0.49 s at 600, 5.1 s at 1200 (peak +112 MB); runs
  /// that converge need 120-250 evaluations. So n = 500 converges in under a minute, n = 600
  /// takes minutes and the paper's grid (N = 400, n = 1200) would hit maxtime (10-20 min).
  int slsqp_max_variables = 500;
  /// LD_MMA / LD_CCSAQ (also as AUGLAG_EQ's local algorithm with inequalities): refuse when the
  /// number of inequality constraints exceeds this. Their dual subproblem grows with m: on the
  /// paper's problem the first evaluations from u = 0 cost 0.25-1 s each at m >= 100 (measured:
  /// 7 and 8 evaluations in 2 s at m = 100, 2-3 at m = 200..800), and the full default maxeval
  /// took 23 s / 10 s at m = 100 and 106 s / 42 s at m = 200 (MMA / CCSAQ), never converging
  /// (gap ~7e-4).
  int mma_max_inequalities = 200;

  /// Record a history row per objective evaluation.
  bool record_history = true;

  /// True when every field satisfies Schema()'s rule; else false with the reason in *error.
  bool IsValid(std::string* error) const;
  /// Every key (the field names above), with its default and rule ("algorithm" and
  /// "local_algorithm" are names of NloptAlgorithmNames()).
  static const OptionSchema& Schema();
  /// `base` with `options` applied (resolved by Schema()), then IsValid. Throws
  /// std::invalid_argument naming the key and the rule, listing the valid keys for an unknown
  /// one.
  static NloptOptions Apply(const OptionMap& options, NloptOptions base);
};

/// The algorithm names NloptOptions accepts.
std::vector<std::string> NloptAlgorithmNames();

/// NLopt's name for a result code ("SUCCESS", "FTOL_REACHED", "ROUNDOFF_LIMITED", ...).
std::string NloptResultName(int nlopt_result);
/// OCPBench's grouping of an NLopt result code:
///   SUCCESS, STOPVAL_REACHED, FTOL_REACHED, XTOL_REACHED -> kConverged
///   MAXEVAL_REACHED, MAXTIME_REACHED                     -> kMaxTime
///   ROUNDOFF_LIMITED                                      -> kRoundoffLimited (x is kept; the
///                                    message gives its relative KKT residual)
///   INVALID_ARGS                                          -> kInvalidInput
///   FORCED_STOP                                           -> kNumericalFailure when OCPBench
///                                    stopped NLopt because an evaluation failed, else kError
///   FAILURE, OUT_OF_MEMORY, unknown                       -> kError
SolveStatus MapNloptResult(int nlopt_result, bool evaluation_failed);

/// Runs NLopt on `nlp` from `z0` (clipped into the variable bounds). Constraints: rows with
/// g_l = g_u become one equality mconstraint g - g_l = 0; the others become one-sided
/// inequalities g - g_u <= 0 and g_l - g <= 0 for each finite side. Jacobians are scattered into
/// dense row-major m x n arrays. Refuses up front (kNotApplicable, reason in the message) when the
/// algorithm cannot take the constraint kinds present or a size limit of NloptOptions is exceeded.
/// Every NLopt exception (roundoff_limited, forced_stop, std::invalid_argument, std::bad_alloc,
/// std::runtime_error) is caught and mapped; a failed evaluation (false from the Nlp) stops NLopt
/// with forced_stop and gives kNumericalFailure. A stop at the starting point (the returned
/// point is the start, or no evaluation succeeded) with a converged, step-too-small or
/// roundoff-limited code is kNumericalFailure unless the start is feasible and stationary (a
/// warm start at an optimum): NLopt's ROUNDOFF_LIMITED after one evaluation is no answer.
/// NLopt has no multipliers: lambda stays empty. iterations = objective evaluations. Throws
/// std::invalid_argument only for invalid options or a z0 of the wrong size.
NlpSolution SolveNlpWithNlopt(const Nlp& nlp, const Vec& z0, const NloptOptions& options);

}  // namespace ocpb
