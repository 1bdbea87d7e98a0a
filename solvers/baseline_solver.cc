#include "solvers/baseline_solver.h"

#include <stdexcept>

#include "core/evaluator.h"
#include "core/timer.h"

namespace ocpb {

OptionSchema BaselineSolver::Schema() { return OptionSchema("baseline"); }

SolveResult BaselineSolver::Solve(const Ocp& ocp, const SolveRequest& request) const {
  Schema().Resolve(request.options);  // no options: any key is refused by name
  if (std::optional<SolveResult> na = FeaturesNotApplicable(ocp, name(), ProblemFeatures())) {
    return *na;
  }
  const Stopwatch watch;
  SolveResult r;
  r.solver = name();
  std::string why_not;
  const std::optional<ControlTrajectory> plan = ocp.BaselinePlan(request.grid, &why_not);
  if (!plan) {
    r.status = SolveStatus::kNotApplicable;
    r.solver_status = "not_applicable";
    r.message = why_not;
  } else {
    const Evaluation ev = Evaluate(ocp, *plan, request.grid, Integrator::kEuler);
    r.status = SolveStatus::kConverged;
    r.solver_status = "baseline_plan";
    r.message = "the problem's baseline plan, evaluated, not optimized";
    r.controls = *plan;
    r.objective = request.terminal == TerminalMode::kHard ? ev.Jbar : ev.J;
    r.iterations = 0;
  }
  r.cpu_seconds = watch.cpu();
  r.wall_seconds = watch.wall();
  return r;
}

}  // namespace ocpb
