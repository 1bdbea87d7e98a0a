// Continuation from the penalty form to the hard terminal form: the penalty solution is the
// start of the hard solve. Hard problems that take hundreds of Ipopt iterations (and land on
// different local optima) from u = 0 often need a few dozen from the penalty solution.
#pragma once

#include "core/ocp.h"
#include "core/solve_result.h"
#include "solvers/solver.h"

namespace ocpb {

/// Both stages of a continuation.
struct ContinuationResult {
  /// The penalty-form solve (the request with terminal = kPenalty), as the solver returned it.
  SolveResult penalty;
  /// The hard-form solve started from the penalty solution, with the totals of both stages:
  /// cpu_seconds and wall_seconds are the sums, each history row's cpu_seconds is offset by the
  /// penalty stage's CPU time (so times to target count the whole continuation), iterations
  /// are the hard stage's, and solver_stats gains "continuation_penalty_iterations" and
  /// "continuation_penalty_cpu_seconds". When the penalty stage gives no start (its status is
  /// not applicable, invalid input, error, numerical failure or infeasible, or it returned no
  /// controls), this is a copy of that stage's result with the message saying that the hard
  /// form was not solved.
  SolveResult hard;
};

/// Solves `request` (whose terminal must be TerminalMode::kHard; std::invalid_argument
/// otherwise) with `solver` in two stages: first the penalty form (same grid, options and
/// initial guess), then the hard form from the penalty solution: its controls as
/// SolveRequest::initial_guess, its own states and costates (where it returned them on its
/// state grid) as initial_states and initial_costates, and for a free final time its T, with
/// `warm_options` (a solver's SolverInfo::replan_defaults: Ipopt's mu_init = 1e-4) under the
/// request's own options. A penalty stage stopped by a limit (iterations, time, line search)
/// still gives its last iterate as the start. The problem's terminal weights shape the start
/// only; the answer is the hard form's.
ContinuationResult SolveHardFromPenalty(const Solver& solver,
                                        const Ocp& ocp,
                                        const SolveRequest& request,
                                        const OptionMap& warm_options = OptionMap());

}  // namespace ocpb
