#include "solvers/judge.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "solvers/message_number.h"
#include "solvers/registry.h"

namespace ocpb {
namespace {

// Numbers in messages (solvers/message_number.h), 4 significant digits.
std::string JudgeNumber(double v) { return MessageNumber(v, 4); }

// The grid and horizon the solution is judged on: for a free final time the end of the method's own
// state grid (collocation, indirect Newton), else of its controls' grid; the problem's tf
// otherwise. A method that chose its own mesh (adaptive refinement) is judged on that mesh.
TimeGrid JudgedGrid(const Ocp& ocp, const SolveRequest& request, const SolveResult& result) {
  const TimeGrid& grid = result.mesh.size() >= 2 ? result.mesh : request.grid;
  if (!ocp.free_final_time()) return grid;
  const double T =
      result.state_grid.size() >= 2 ? result.state_grid.tf() : result.controls.grid().tf();
  return grid.StretchedTo(T);
}

// The solver's stopping tolerance as used: the request's value, else its schema's default.
void RecordAccuracyOption(const SolveRequest& request, const SolveResult& result, Judgement* j) {
  const SolverInfo* info = nullptr;
  for (const SolverInfo& s : Solvers()) {
    if (s.name == result.solver) info = &s;
  }
  if (!info || info->accuracy_option.empty()) return;
  j->accuracy_option = info->accuracy_option;
  j->accuracy_note = info->accuracy_note;
  const OptionSpec* spec = info->options.Find(info->accuracy_option);
  if (!spec) return;
  OptionValue value = spec->default_value;
  if (const OptionValue* given = request.options.Find(info->accuracy_option)) {
    value = spec->Resolve(*given);
  }
  if (value.kind() == OptionValue::Kind::kNumber) j->accuracy_value = value.number();
  if (value.kind() == OptionValue::Kind::kInteger) {
    j->accuracy_value = static_cast<double>(value.integer());
  }
}

void AddDiscretizationWarning(const SolveRequest& request,
                              const SolveResult& result,
                              const JudgeOptions& options,
                              Judgement* j) {
  // A failed solve has no objective of its own to compare (SolveResult's -1: not computed).
  if (result.status == SolveStatus::kNumericalFailure || result.status == SolveStatus::kError ||
      result.status == SolveStatus::kInvalidInput) {
    return;
  }
  const bool penalty = request.terminal == TerminalMode::kPenalty;
  const double fine = penalty ? j->fine.J : j->fine.Jbar;
  const double own = result.objective;
  if (!std::isfinite(fine) || !std::isfinite(own)) return;
  j->discretization_gap = std::abs(own - fine) / std::max({std::abs(own), std::abs(fine), 1e-8});
  if (!(j->discretization_gap > options.discretization_tolerance)) return;
  const auto reformulated = result.solver_stats.find("reformulated");
  const bool reform = reformulated != result.solver_stats.end() && reformulated->second == 1.0;
  j->warnings.push_back(
      {"discretization",
       "the method's own objective " + JudgeNumber(own) + " and the fine re-simulation's " +
           (penalty ? "J " : "Jbar ") + JudgeNumber(fine) + " differ by " +
           JudgeNumber(j->discretization_gap) + " relative (> " +
           JudgeNumber(options.discretization_tolerance) + "): on this grid" +
           (reform ? " (and through the reformulation the method solved)" : "") +
           " the discrete problem is not the continuous one; refine the grid or use a "
           "higher-order scheme"});
}

void AddReformulatedWarning(const SolveResult& result, Judgement* j) {
  if (result.status == SolveStatus::kNumericalFailure || result.status == SolveStatus::kError ||
      result.status == SolveStatus::kInvalidInput) {
    return;
  }
  const auto reformulated = result.solver_stats.find("reformulated");
  if (reformulated == result.solver_stats.end() || reformulated->second != 1.0) return;
  j->warnings.push_back(
      {"reformulated",
       "the method solved the problem's Hamiltonian reformulation (path constraints as "
       "penalties, or H regularized): its status is about that problem, whose optimum is not "
       "this one's; judge the answer by the fine re-simulation's Jbar and violations"});
}

void AddFeasibilityWarning(const SolveRequest& request, const JudgeOptions& options, Judgement* j) {
  std::vector<std::string> violated;
  const double tol = options.feasibility_tolerance;
  auto check = [&](const char* what, double violation) {
    if (violation > tol) violated.push_back(std::string(what) + " " + JudgeNumber(violation));
  };
  check("control set U", j->fine.control_violation);
  check("path constraints", j->fine.path_violation);
  check("state bounds", j->fine.state_bound_violation);
  check("boundary constraints", j->fine.boundary_violation);  // hard in both terminal forms
  if (request.terminal == TerminalMode::kHard) {
    check("terminal constraints", j->fine.terminal_violation);
  }
  if (violated.empty()) return;
  std::string list;
  for (const std::string& v : violated) list += (list.empty() ? "" : ", ") + v;
  j->warnings.push_back({"infeasible",
                         "the controls re-simulated on the fine grid violate " + list + " (> " +
                             JudgeNumber(tol) +
                             "): the answer is not feasible, whatever the "
                             "status says"});
}

// The re-simulation on the method's grid (explicit Euler by default) may diverge where the
// method's own scheme and the fine RK4 do not: say which evaluations are finite.
void AddNotFiniteWarning(const JudgeOptions& options, Judgement* j) {
  if (j->own_grid.finite) return;
  std::string message = std::string("the controls re-simulated with ") +
                        ToString(options.integrator) + " on the method's grid (" +
                        std::to_string(j->grid.intervals()) +
                        " intervals) give a trajectory or cost that is not finite";
  if (j->fine.finite) {
    message += "; the fine RK4 re-simulation is finite (J fine " + JudgeNumber(j->fine.J) +
               "): judge by it";
  } else {
    message += ", and so does the fine RK4 re-simulation: the answer cannot be evaluated";
  }
  j->warnings.push_back({"not_finite", message});
}

}  // namespace

bool Judgement::HasWarning(const std::string& code) const {
  return std::any_of(
      warnings.begin(), warnings.end(), [&](const JudgeWarning& w) { return w.code == code; });
}

Judgement JudgeResult(const Ocp& ocp,
                      const SolveRequest& request,
                      const SolveResult& result,
                      const JudgeOptions& options) {
  if (options.refine < 1) throw std::invalid_argument("JudgeOptions.refine: must be >= 1");
  if (!(options.discretization_tolerance > 0.0) ||
      !std::isfinite(options.discretization_tolerance)) {
    throw std::invalid_argument("JudgeOptions.discretization_tolerance: must be a number > 0");
  }
  if (!(options.feasibility_tolerance > 0.0) || !std::isfinite(options.feasibility_tolerance)) {
    throw std::invalid_argument("JudgeOptions.feasibility_tolerance: must be a number > 0");
  }
  Judgement j;
  if (result.status == SolveStatus::kNotApplicable) {
    j.not_judged = "the method did not run (not applicable)";
    return j;
  }
  if (result.controls.nu() != ocp.nu()) {
    j.not_judged = "the result has controls of dimension " + std::to_string(result.controls.nu()) +
                   ", the problem nu = " + std::to_string(ocp.nu());
    return j;
  }
  j.judged = true;
  j.grid = JudgedGrid(ocp, request, result);
  j.final_time = j.grid.tf();
  // A free initial state is judged from the x(t0) the method chose; a fixed one from x0.
  if (result.initial_state.size() != 0 && result.initial_state.size() != ocp.nx()) {
    throw std::invalid_argument("JudgeResult: the result's initial_state has " +
                                std::to_string(result.initial_state.size()) +
                                " components, the problem nx = " + std::to_string(ocp.nx()));
  }
  const Vec start = result.initial_state.size() == ocp.nx() ? result.initial_state : ocp.x0();
  j.own_grid = Evaluate(ocp, result.controls, j.grid, options.integrator, start);
  j.fine = Evaluate(ocp, result.controls, j.grid.Refined(options.refine), Integrator::kRk4, start);
  const bool has_states = result.states.rows() == ocp.nx() &&
                          result.states.cols() == result.state_grid.size() &&
                          result.state_grid.size() >= 2;
  if (has_states) {
    j.resimulation_defect =
        ResimulationDefect(ocp, result.controls, result.state_grid, result.states, options.refine);
  }
  RecordAccuracyOption(request, result, &j);
  if (request.terminal == TerminalMode::kPenalty && !ocp.terminal_weights_chosen()) {
    j.warnings.push_back(
        {"terminal_weights_default",
         "penalty form, and problem " + ocp.name() +
             " never chose its terminal weights (w = 1 by default): terminal violation " +
             JudgeNumber(j.fine.terminal_violation) +
             " on the fine grid; set them (SetTerminalWeights) or solve the hard form"});
  }
  AddNotFiniteWarning(options, &j);
  AddDiscretizationWarning(request, result, options, &j);
  AddFeasibilityWarning(request, options, &j);
  AddReformulatedWarning(result, &j);
  return j;
}

}  // namespace ocpb
