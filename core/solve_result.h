// Status and result types every solver returns.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "core/control_trajectory.h"
#include "core/types.h"

namespace ocpb {

/// OCPBench's summary of how a solve ended. The backend's own code is kept verbatim in
/// SolveResult::solver_status; this enum only groups it, it never replaces it.
enum class SolveStatus {
  kConverged,         ///< the solver's convergence test passed
  kAcceptable,        ///< converged to the solver's "acceptable" (looser) level
  kMaxIterations,     ///< iteration limit reached; controls are the last iterate
  kMaxTime,           ///< time or evaluation limit reached; controls are the last iterate
  kStepTooSmall,      ///< line search failed (e.g. Armijo exponent beyond its limit)
  kRoundoffLimited,   ///< progress limited by roundoff after some progress (a stop at the
                      ///< start is kNumericalFailure); check the solver's message
  kInfeasible,        ///< the solver declared the problem (locally) infeasible
  kNumericalFailure,  ///< NaN/inf or a solver-internal numerical error
  kInvalidInput,      ///< the request was rejected before solving
  kNotApplicable,     ///< the method cannot solve this problem (stated reason in message)
  kError,             ///< any other failure reported by the backend
};

const char* ToString(SolveStatus status);
/// Converged or acceptable: the solver's own test passed, at its tight or at its looser level.
/// Summaries and records keep the two apart (status "acceptable" is never shown as
/// "converged"); compare with == kConverged where only the tight level will do.
bool IsSuccess(SolveStatus status);

/// One row of a solver's iteration history. Fields a solver does not have stay NaN / -1.
struct IterationRecord {
  int iteration = 0;
  double J = -1.0;           ///< the solver's objective at this iterate
  double theta = NAN;        ///< Hamiltonian descent: theta(u) = int H(u*) - H(u) dt
  int armijo_j = -1;         ///< Hamiltonian descent: Armijo exponent accepted
  double primal_inf = NAN;   ///< NLP solvers: constraint violation
  double dual_inf = NAN;     ///< NLP solvers: dual infeasibility
  double cpu_seconds = 0.0;  ///< cumulative CPU time since the solve started
};

/// Everything a user needs from a solve. Numbers start at -1 ("not computed").
struct SolveResult {
  std::string solver;  ///< registry name ("hamiltonian", "ipopt", ...)
  SolveStatus status = SolveStatus::kError;
  std::string solver_status;   ///< the backend's own status, verbatim
  std::string message;         ///< human-readable detail
  ControlTrajectory controls;  ///< the controls the evaluator judges
  TimeGrid state_grid;         ///< grid of `states` / `costates`; for a free final time it
                               ///< spans [t0, the solution's tf]
  Mat states;                  ///< the method's own states (nx x points), if it has them
  Mat costates;                ///< costates or multiplier-based estimates, if any
  double objective = -1.0;     ///< the objective value the method reports about itself
  int iterations = -1;
  std::vector<IterationRecord> history;
  double cpu_seconds = -1.0;
  double wall_seconds = -1.0;
  /// Backend-specific numbers by name (for example "ipopt_cpu_seconds", "ipopt_dual_inf");
  /// empty when the solver reports none.
  std::map<std::string, double> solver_stats;
  /// Where `costates` come from, in a few words ("NLP multipliers (lgr)", "discrete adjoint
  /// (euler)"); empty when there are none.
  std::string costate_source;
};

}  // namespace ocpb
