// Judging a solver's result: the one public way, used by `ocpbench` (every record), the user
// example and the documentation alike. It takes the result itself, so the horizon cannot be
// picked wrong: a free final time is judged on the solution's own [t0, T].
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "core/evaluator.h"
#include "core/ocp.h"
#include "core/solve_result.h"
#include "core/time_grid.h"
#include "solvers/solver.h"

namespace ocpb {

/// Something about a result that its status does not say. `code` is stable (scripts and the
/// summary match it); `message` is one line for people.
///  - "terminal_weights_default": penalty form, terminal constraints, and the problem never
///    chose its weights (Ocp::terminal_weights_chosen(): w = 1 by default);
///  - "discretization": the method's own objective and the fine re-simulation of its controls
///    disagree by more than JudgeOptions::discretization_tolerance (the grid, not the method,
///    limits the answer: refine it, or use a higher-order scheme).
///  - "infeasible": the controls re-simulated on the fine grid violate U, a path constraint, the
///    state bounds (or the initial-state bounds at t0), the boundary constraints, or
///    (hard form) the terminal constraints by more than JudgeOptions::feasibility_tolerance,
///    whatever the status says (a minimizer that forgets the bounds, a scheme that does not
///    enforce a path constraint at tf, a penalty reformulation).
///  - "not_finite": the controls re-simulated on the method's grid with JudgeOptions::integrator
///    (the record's J, Jbar) give a trajectory or cost that is not finite. The message says
///    whether the fine RK4 re-simulation is finite (then judge by its values: an explicit
///    integrator on a coarse grid diverged, not necessarily the method). `ocpbench` records the
///    status numerical_failure when the fine one is not finite either, or when the method's own
///    scheme is the judge's integrator (its transcription is, or it has none).
///  - "reformulated": the method solved the problem's Hamiltonian reformulation (the solver's
///    solver_stats["reformulated"] = 1: path constraints as penalties, H regularized where it is
///    linear in u), so its status is about that problem, whose optimum is not this one's
///    (bryson-denham: the family's RK4 polish converged 0.7 % below the constrained optimum,
///    within the fine grid's 1e-3 feasibility). Not for a method that failed (numerical_failure,
///    error, invalid_input).
struct JudgeWarning {
  std::string code;
  std::string message;
};

/// How to judge. Defaults are what `ocpbench` records.
struct JudgeOptions {
  /// The common evaluator's integrator on the method's grid (the record's J, Jbar): forward
  /// Euler, the paper's discretization.
  Integrator integrator = Integrator::kEuler;
  /// The fine judge: RK4 on the method's grid with every interval split this many times (>= 1).
  int refine = 10;
  /// Warn "discretization" when |objective - fine| > discretization_tolerance max(|objective|,
  /// |fine|, 1e-8), with `fine` the fine re-simulation's J in the penalty form and its Jbar in
  /// the hard form (what the method's objective measures). 1 %: the summary's target rule.
  double discretization_tolerance = 1e-2;
  /// Warn "infeasible" when the fine re-simulation's control_violation, path_violation,
  /// state_bound_violation or boundary_violation, or
  /// in the hard form its terminal_violation, exceeds this (absolute, in the constraint's own
  /// units). 1e-3: far above what a converged NLP leaves (1e-8 and below), below what changes
  /// an answer visibly; the violations themselves are in Judgement::fine.
  double feasibility_tolerance = 1e-3;
};

/// What the common evaluator says about a result.
struct Judgement {
  /// False when the result has no controls to judge (not applicable, or controls of the wrong
  /// size): every number below then stays NaN / empty, and `not_judged` says why.
  bool judged = false;
  std::string not_judged;
  /// The method's grid on the solution's horizon: the result's own mesh when it chose one
  /// (SolveResult::mesh, adaptive refinement), else the request's grid; for a free final time
  /// stretched to the result's T (the end of its state_grid, else of its controls' grid).
  TimeGrid grid;
  double final_time = std::numeric_limits<double>::quiet_NaN();
  Evaluation own_grid;  ///< the controls re-simulated on `grid` with options.integrator
  Evaluation fine;      ///< RK4 on `grid` refined options.refine times
  /// max |the method's own states - an RK4 re-simulation of its controls| on its state grid
  /// (ResimulationDefect), for methods that carry states; NaN otherwise.
  double resimulation_defect = std::numeric_limits<double>::quiet_NaN();
  /// |objective - fine| / max(|objective|, |fine|, 1e-8) (see JudgeOptions); NaN when either
  /// is not finite or the solve failed (numerical failure, error, invalid input).
  double discretization_gap = std::numeric_limits<double>::quiet_NaN();
  /// The option of the solver whose value stops it (SolverInfo::accuracy_option, for example
  /// Ipopt's "tol"), its value in this solve, and what it bounds; empty for a solver that
  /// names none.
  std::string accuracy_option;
  double accuracy_value = std::numeric_limits<double>::quiet_NaN();
  std::string accuracy_note;
  std::vector<JudgeWarning> warnings;

  /// True when a warning with this code was given.
  bool HasWarning(const std::string& code) const;
};

/// Judges `result`, the answer of a solver to `request` on `ocp` (the problem as posed, not a
/// reformulation a method solved in its place): re-simulates its controls on the method's grid
/// and on the fine grid, measures the re-simulation defect, and adds the warnings above.
/// Throws std::invalid_argument when options are out of range (refine < 1, a tolerance not in
/// (0, inf)), or when the controls do not cover the horizon they claim (a solver's bug).
Judgement JudgeResult(const Ocp& ocp,
                      const SolveRequest& request,
                      const SolveResult& result,
                      const JudgeOptions& options = JudgeOptions());

}  // namespace ocpb
