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
  /// Intervals of the grid this iterate lives on when that is not the request's grid (a
  /// grid-sequenced solve's coarser grids: its J is that grid's discrete J); -1: the request's.
  int intervals = -1;
};

/// One mesh of an adaptive mesh refinement (the collocation transcriptions' mesh_tolerance > 0):
/// the solve on that mesh and the error estimate at its solution.
struct MeshIterationRecord {
  int intervals = 0;       ///< mesh intervals N (nodes N + 1)
  int nlp_variables = -1;  ///< NLP size on this mesh
  int nlp_constraints = -1;
  double max_error = NAN;    ///< largest interval error estimate at this mesh's solution (NaN:
                             ///< not computed, the solve failed or the estimate is not finite)
  int iterations = -1;       ///< the NLP solver's iterations on this mesh
  double cpu_seconds = NAN;  ///< this mesh's CPU: transcription, solve and estimate
  SolveStatus status = SolveStatus::kError;
  std::string solver_status;  ///< the backend's own status on this mesh, verbatim
  /// ph-refinement (LGR): the collocation points of each interval of this mesh; empty for
  /// h-refinement (trapezoid, Hermite-Simpson).
  std::vector<int> degrees;
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
  /// The x(t0) the method chose when the problem's initial state is free
  /// (Ocp::HasFreeInitialState); empty otherwise (x(t0) = x0). The judge starts from it.
  Vec initial_state;
  double objective = -1.0;  ///< the objective value the method reports about itself
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
  /// The grid the method solved on when it chose it itself (adaptive mesh refinement), on the
  /// request's nominal horizon; the evaluator judges on it. Empty (size 0): the request's grid.
  TimeGrid mesh;
  /// Adaptive mesh refinement only: one entry per mesh solved, in order (the last is the one
  /// `controls` come from), and why it stopped (ToString(MeshStopReason): "tolerance_met",
  /// "max_iterations", "max_nodes", "solve_failed", "no_estimate"); empty otherwise.
  std::vector<MeshIterationRecord> mesh_history;
  std::string mesh_stop_reason;
};

}  // namespace ocpb
