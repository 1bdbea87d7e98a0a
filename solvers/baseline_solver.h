// The "baseline" method: the problem's own unoptimized plan, judged like any method's answer.
#pragma once

#include <string>

#include "core/option_schema.h"
#include "solvers/solver.h"

namespace ocpb {

/// Returns Ocp::BaselinePlan(request.grid) without optimizing anything: the plan a user would
/// run without this toolkit (the comm problems: the straight segment S-D, or the given path,
/// at constant speed, and a constant rate sending c bits by tf). Its record goes through the
/// common evaluator (and, for the comm problems, the true channel) like every method's, so the
/// gain of optimizing is a difference of two records of one suite.
///
/// Status: converged (solver_status "baseline_plan", 0 iterations) when the problem gives a
/// plan: the method did all it does; not_applicable (with the problem's reason) when it gives
/// none, or for a free final time. objective = the plan's J on the request's grid with forward
/// Euler (Jbar in the hard terminal form). No options.
class BaselineSolver final : public Solver {
 public:
  std::string name() const override { return "baseline"; }
  SolveResult Solve(const Ocp& ocp, const SolveRequest& request) const override;
  /// Its option schema: empty.
  static OptionSchema Schema();
};

}  // namespace ocpb
