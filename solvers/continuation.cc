#include "solvers/continuation.h"

#include <optional>
#include <stdexcept>
#include <string>

namespace ocpb {
namespace {

// Statuses after which the penalty stage's controls are no start for the hard form.
bool GivesNoStart(const SolveResult& r, const Ocp& ocp) {
  switch (r.status) {
    case SolveStatus::kNotApplicable:
    case SolveStatus::kInvalidInput:
    case SolveStatus::kError:
    case SolveStatus::kNumericalFailure:
    case SolveStatus::kInfeasible:
      return true;
    default:
      return r.controls.nu() != ocp.nu();
  }
}

// The method's own trajectory on its state grid (states or costates), when it has one.
std::optional<ControlTrajectory> OwnTrajectory(const SolveResult& r, const Mat& values, int nx) {
  if (values.rows() != nx || r.state_grid.size() < 2 || values.cols() != r.state_grid.size() ||
      !values.allFinite()) {
    return std::nullopt;
  }
  return ControlTrajectory::PiecewiseLinear(r.state_grid, values);
}

}  // namespace

ContinuationResult SolveHardFromPenalty(const Solver& solver,
                                        const Ocp& ocp,
                                        const SolveRequest& request,
                                        const OptionMap& warm_options) {
  if (request.terminal != TerminalMode::kHard) {
    throw std::invalid_argument(
        "continuation: the penalty-to-hard continuation solves the hard terminal form (terminal "
        "= hard)");
  }
  ContinuationResult out;
  SolveRequest penalty = request;
  penalty.terminal = TerminalMode::kPenalty;
  out.penalty = solver.Solve(ocp, penalty);
  const SolveResult& p = out.penalty;
  const std::string stage = "continuation: penalty form " + p.solver_status + " after " +
                            std::to_string(p.iterations) + " iterations";
  if (GivesNoStart(p, ocp)) {
    out.hard = p;
    out.hard.message = stage + ", no start for the hard form, which was not solved (" +
                       ToString(p.status) + ": " + p.message + ")";
    return out;
  }
  SolveRequest hard = request;
  hard.initial_guess = p.controls;
  hard.initial_states = OwnTrajectory(p, p.states, ocp.nx());
  hard.initial_costates = OwnTrajectory(p, p.costates, ocp.nx());
  std::string applied;
  for (const auto& [key, value] : warm_options) {
    if (hard.options.Has(key)) continue;
    hard.options.Set(key, value);
    applied += (applied.empty() ? "" : ", ") + key + "=" + value.ToText();
  }
  out.hard = solver.Solve(ocp, hard);
  SolveResult& h = out.hard;
  const double offset = p.cpu_seconds > 0.0 ? p.cpu_seconds : 0.0;
  for (IterationRecord& row : h.history) row.cpu_seconds += offset;
  if (h.cpu_seconds >= 0.0) h.cpu_seconds += offset;
  if (h.wall_seconds >= 0.0 && p.wall_seconds > 0.0) h.wall_seconds += p.wall_seconds;
  h.solver_stats["continuation_penalty_iterations"] = p.iterations;
  h.solver_stats["continuation_penalty_cpu_seconds"] = p.cpu_seconds;
  h.message = stage + "; then the hard form" +
              (applied.empty() ? std::string() : " (warm-start options " + applied + ")") + ": " +
              h.message;
  return out;
}

}  // namespace ocpb
