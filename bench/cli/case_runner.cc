#include "bench/cli/case_runner.h"

#include <cmath>
#include <exception>
#include <memory>
#include <optional>
#include <stdexcept>

#include "bench/cli/initial_guess.h"
#include "bench/cli/json_values.h"
#include "bench/cli/online_case.h"
#include "core/costate_error.h"
#include "core/evaluator.h"
#include "core/field_sample.h"
#include "core/parameters.h"
#include "problems/registry.h"
#include "solvers/continuation.h"
#include "solvers/judge.h"
#include "solvers/registry.h"

namespace ocpb {
namespace {

using nlohmann::json;

json OptionsJson(const OptionMap& options) {
  json j = json::object();
  for (const auto& [k, v] : options) j[k] = JsonOptionValue(v);
  return j;
}

// The solver's and the transcription's effective options: their schemas' defaults with the
// case's values over them (what the solve really used).
void RecordEffectiveOptions(const CaseSpec& spec, const MethodOptions& given, Record* rec) {
  auto effective = [](const OptionSchema& schema, const OptionMap& over) {
    OptionMap all;
    for (const OptionSpec& s : schema.specs()) {
      if (!s.default_value.empty()) all.Set(s.name, s.default_value);
    }
    for (const auto& [k, v] : over) all.Set(k, v);
    return all;
  };
  rec->solver_options = OptionsJson(effective(FindSolver(spec.solver).options, given.solver));
  if (!spec.transcription.empty()) {
    rec->transcription_options =
        OptionsJson(effective(FindTranscription(spec.transcription).options, given.transcription));
  }
}

// What one case solves: the problem, its grid and the request.
struct PreparedCase {
  Parameters params;
  std::shared_ptr<const Ocp> ocp;
  TimeGrid grid;
  SolveRequest request;
  MethodOptions options;
};

// The request from the resolved case; the problem is the one its checks built, or built now
// (with its channel) when the checks used a cheaper build.
PreparedCase Prepare(const ResolvedCase& c) {
  const CaseSpec& spec = c.spec;
  PreparedCase p;
  p.params = c.parameters;
  p.ocp = c.built_problem;
  if (!p.ocp) p.ocp = c.problem->make(c.parameters, spec.seed);
  p.grid = TimeGrid::Uniform(p.ocp->t0(), p.ocp->tf(), c.intervals);
  p.options = c.options;
  p.request.grid = p.grid;
  p.request.terminal = spec.terminal;
  p.request.integrator = spec.integrator;
  p.request.transcription = spec.transcription;
  p.request.transcription_options = p.options.transcription;
  p.request.options = p.options.solver;
  if (c.initial_guess) {
    // Checked against the build for checks; a problem built now is checked too.
    if (!c.built_problem) CheckInitialGuess(*c.initial_guess, *p.ocp, spec.initial_guess);
    p.request.initial_guess = c.initial_guess->controls;
    p.request.initial_states = c.initial_guess->states;
    p.request.initial_costates = c.initial_guess->costates;
  }
  return p;
}

// The solve, `repeats` times: the last result, and every repeat's CPU and wall seconds (with a
// continuation: both stages; `penalty_stage` gets the last repeat's first stage). An invalid
// request propagates (bad input); any other exception is the result's error status.
SolveResult SolveRepeatedly(const CaseSpec& spec,
                            const PreparedCase& p,
                            std::vector<double>* cpu,
                            std::vector<double>* wall,
                            std::optional<SolveResult>* penalty_stage) {
  const std::unique_ptr<Solver> solver = FindSolver(spec.solver).make();
  SolveResult result;
  for (int r = 0; r < spec.repeats; ++r) {
    try {
      if (spec.continuation == "penalty") {
        ContinuationResult both = SolveHardFromPenalty(
            *solver, *p.ocp, p.request, FindSolver(spec.solver).replan_defaults);
        result = std::move(both.hard);
        *penalty_stage = std::move(both.penalty);
      } else {
        result = solver->Solve(*p.ocp, p.request);
      }
    } catch (const std::invalid_argument&) {
      throw;
    } catch (const std::exception& e) {
      result = SolveResult();
      result.solver = spec.solver;
      result.status = SolveStatus::kError;
      result.solver_status = "exception";
      result.message = e.what();
    }
    cpu->push_back(result.cpu_seconds);
    wall->push_back(result.wall_seconds);
  }
  return result;
}

// The problem's judgement on its true data (ProblemInfo::judge_on_truth): the controls as the
// Euler evaluator reads them on the judged grid (each interval's left value), executed from the
// problem's initial state.
void RecordTruthFields(const CaseSpec& spec,
                       const PreparedCase& p,
                       const TimeGrid& grid,
                       const SolveResult& result,
                       Record* rec) {
  const ProblemInfo& pinfo = FindProblem(spec.problem);
  if (!pinfo.judge_on_truth) return;
  const std::optional<TruthJudgement> t = pinfo.judge_on_truth(
      p.params, spec.seed, *p.ocp, grid, result.controls.SampleIntervals(grid));
  if (!t) return;
  rec->truth = RecordTruth{t->truth,
                           t->energy_true,
                           t->transmit_energy_true,
                           t->J_true,
                           t->max_distance_from_segment,
                           t->min_distance_to_base};
}

// The common evaluator's fields, by the one public judge (JudgeResult): the controls
// re-simulated on the method's grid (the case's integrator) and with RK4 on a 10x finer grid, on
// the horizon the solution ends at, and the warnings its status does not carry.
void Judge(const CaseSpec& spec, const PreparedCase& p, const SolveResult& result, Record* rec) {
  const Ocp& ocp = *p.ocp;
  rec->final_time_free = ocp.free_final_time().has_value();
  JudgeOptions options;
  options.integrator = spec.evaluate_with;
  const Judgement judged = JudgeResult(ocp, p.request, result, options);
  if (!judged.accuracy_option.empty()) {
    rec->stopping_tolerance = RecordStoppingTolerance{
        judged.accuracy_option, judged.accuracy_value, judged.accuracy_note};
  }
  // A method that did not run has nothing to judge (its "controls" would be the start).
  if (!judged.judged) return;
  const Evaluation& ev = judged.own_grid;
  const Evaluation& fine = judged.fine;
  rec->final_time = judged.final_time;
  rec->J = ev.J;
  rec->Jbar = ev.Jbar;
  rec->terminal_violation = ev.terminal_violation;
  rec->terminal_residual.assign(ev.terminal_residual.data(),
                                ev.terminal_residual.data() + ev.terminal_residual.size());
  rec->control_violation = ev.control_violation;
  rec->path_violation = ev.path_violation;
  const Vec last = ev.X.col(ev.X.cols() - 1);
  rec->final_state.assign(last.data(), last.data() + last.size());
  rec->J_fine = fine.J;
  rec->Jbar_fine = fine.Jbar;
  rec->terminal_violation_fine = fine.terminal_violation;
  rec->resimulation_defect = judged.resimulation_defect;
  if (ocp.HasFreeInitialState()) {
    const Vec first = ev.X.col(0);
    rec->initial_state.assign(first.data(), first.data() + first.size());
    const int np = ocp.num_static_parameters();
    rec->static_parameters.assign(first.data() + first.size() - np, first.data() + first.size());
  }
  if (ocp.HasFreeInitialState() || ocp.state_bounds()) {
    rec->state_bound_violation = fine.state_bound_violation;
  }
  if (ocp.num_boundary() > 0) {
    rec->boundary_residual.assign(fine.boundary_residual.data(),
                                  fine.boundary_residual.data() + fine.boundary_residual.size());
    rec->boundary_violation = fine.boundary_violation;
  }
  rec->discretization_gap = judged.discretization_gap;
  for (const JudgeWarning& w : judged.warnings) rec->warnings.push_back({w.code, w.message});
  if (NotFiniteIsNumericalFailure(spec, ev.finite, fine.finite) && !IsFailure(result.status)) {
    rec->status = ToString(SolveStatus::kNumericalFailure);
    rec->message = result.message + " (evaluator: trajectory or cost not finite)";
  }
  RecordTruthFields(spec, p, judged.grid, result, rec);
  if (spec.keep_trajectory) {
    RecordTrajectory traj;
    traj.t = judged.grid.points();
    traj.x = ev.X;
    traj.u = result.controls.SampleIntervals(judged.grid);
    traj.u_rule = "value at each interval's left end; piecewise " +
                  std::string(result.controls.InterpolationName());
    if (std::isfinite(judged.resimulation_defect)) {  // the method carries its own states
      traj.own_t = result.state_grid.points();
      traj.own_x = result.states;
      if (result.costates.rows() == ocp.nx() && result.costates.cols() == result.states.cols()) {
        traj.own_p = result.costates;
      }
    }
    rec->trajectory = std::move(traj);
    const ProblemInfo& pinfo = FindProblem(spec.problem);
    if (pinfo.sample_for_figures) {
      if (const std::optional<FieldSample> f = pinfo.sample_for_figures(ocp)) {
        rec->s_map = FieldSampleJson(*f);
      }
    }
  }
}

// The costate fields: the method's own source, the costates themselves with the trajectory,
// and the error against the problem's known p* where it applies: the problem's default
// parameters (p* is for those), its fixed horizon, and the problem as posed (the hard terminal
// form, or no terminal constraints: the penalty form's optimum has other costates).
void RecordCostateFields(const CaseSpec& spec,
                         const PreparedCase& p,
                         const SolveResult& result,
                         Record* rec) {
  const bool has_costates = result.costates.rows() == p.ocp->nx() &&
                            result.costates.cols() == result.state_grid.size() &&
                            result.costates.cols() > 0;
  if (!has_costates || result.status == SolveStatus::kNotApplicable) return;
  rec->costate_source = result.costate_source;
  if (spec.keep_trajectory)
    rec->costates = RecordCostates{result.state_grid.points(), result.costates};
  const ProblemInfo& pinfo = FindProblem(spec.problem);
  const bool as_posed = spec.terminal == TerminalMode::kHard || p.ocp->num_terminal() == 0;
  const bool defaults = p.params.values() == Parameters(pinfo.parameters).values();
  if (pinfo.reference_costate && as_posed && defaults && !p.ocp->free_final_time()) {
    rec->costate_error =
        RelativeCostateError(result.costates, result.state_grid, pinfo.reference_costate);
  }
}

}  // namespace

void AddCaseFiles(const CaseSpec& spec, const std::string& where, FilePlan* plan) {
  const std::string of = where.empty() ? "" : " of " + where;
  if (!spec.initial_guess.empty()) plan->Input(spec.initial_guess, "--initial-guess" + of);
  auto outputs = [&](const OptionMap& options, const std::string& flag) {
    for (const auto& [name, value] : options) {
      if (!FilePlan::IsOutputFileOption(name) || value.empty()) continue;
      const std::string path = value.ToText();
      if (path.empty()) continue;
      plan->Output(path, flag + " " + name + of, FilePlan::kSolverLog);
    }
  };
  outputs(spec.options, where.empty() ? "--option" : "option");
  outputs(spec.replan_options, where.empty() ? "--replan-option" : "replan option");
}

bool NotFiniteIsNumericalFailure(const CaseSpec& spec, bool own_finite, bool fine_finite) {
  if (own_finite) return false;
  // Ipopt on the Euler NLP judged by Euler re-simulates its own scheme: a divergence there is
  // the method's. A method without a transcription counts as the judge's scheme.
  const bool own_scheme =
      spec.transcription.empty() || spec.transcription == ToString(spec.evaluate_with);
  return !fine_finite || own_scheme;
}

bool IsFailure(SolveStatus status) {
  return status == SolveStatus::kNumericalFailure || status == SolveStatus::kInfeasible ||
         status == SolveStatus::kError || status == SolveStatus::kInvalidInput;
}

bool IsFailure(const std::string& status) {
  for (SolveStatus s : {SolveStatus::kNumericalFailure,
                        SolveStatus::kInfeasible,
                        SolveStatus::kError,
                        SolveStatus::kInvalidInput}) {
    if (status == ToString(s)) return true;
  }
  return false;
}

Record CaseIdentityRecord(const CaseSpec& spec) {
  Record rec;
  rec.kind = spec.kind;
  rec.key = spec.Key();
  rec.problem = spec.problem;
  rec.seed = spec.seed;
  rec.solver = spec.solver;
  rec.transcription = spec.transcription;
  // NLopt's algorithm has its own field, whichever spelling gave it (CaseSpec::algorithm).
  const OptionValue* algorithm = spec.options.Find("algorithm");
  rec.algorithm = !spec.algorithm.empty() ? spec.algorithm
                  : algorithm != nullptr  ? algorithm->ToText()
                                          : std::string();
  rec.N = spec.intervals;
  rec.terminal = ToString(spec.terminal);
  rec.integrator = ToString(spec.integrator);
  rec.evaluated_with = ToString(spec.evaluate_with);
  rec.options = spec.OptionsBesideCaseFields().ToText();
  if (!spec.initial_guess.empty()) rec.initial_guess = spec.initial_guess;
  rec.repeats = spec.repeats;
  rec.versions = CurrentVersions();
  return rec;
}

Record RunCaseRecordingFailures(const CaseSpec& spec,
                                const std::function<Record(const CaseSpec&)>& run) {
  SolveStatus status = SolveStatus::kError;
  std::string message;
  try {
    return run(spec);
  } catch (const std::invalid_argument& e) {
    // Invalid only once built or run (ValidateCase passed): recorded, the suite goes on.
    status = SolveStatus::kInvalidInput;
    message = e.what();
  } catch (const std::exception& e) {
    status = SolveStatus::kError;
    message = e.what();
  }
  Record rec = CaseIdentityRecord(spec);
  rec.status = ToString(status);
  rec.solver_status = status == SolveStatus::kError ? "exception" : "";
  rec.message = message;
  return rec;
}

Record RunCase(const CaseSpec& spec) {
  // Every check before any solving (or channel simulation): bad input fails fast and whole.
  return RunCase(ResolveAndValidate(spec));
}

Record RunCase(const ResolvedCase& c) {
  const CaseSpec& spec = c.spec;
  if (spec.kind == "online") return RunOnlineCase(spec, *c.online);
  const ProblemInfo& pinfo = *c.problem;
  const PreparedCase p = Prepare(c);
  std::vector<double> cpu, wall;
  std::optional<SolveResult> penalty_stage;
  const SolveResult result = SolveRepeatedly(spec, p, &cpu, &wall, &penalty_stage);

  Record rec = CaseIdentityRecord(spec);
  rec.parameters = p.params.values();
  rec.uses_seed = pinfo.uses_seed;
  rec.N = p.grid.intervals();
  if (!result.mesh_stop_reason.empty()) {
    rec.mesh = RecordMesh{result.mesh_stop_reason, result.mesh.points(), result.mesh_history};
  }
  if (const OptionValue* degree = p.options.transcription.Find("degree")) {
    rec.degree = static_cast<int>(degree->integer());
  }
  RecordEffectiveOptions(spec, p.options, &rec);
  rec.status = ToString(result.status);
  rec.solver_status = result.solver_status;
  rec.message = result.message;
  rec.objective = result.objective;
  rec.iterations = result.iterations;
  rec.cpu_seconds = Median(cpu);
  rec.cpu_seconds_repeats = cpu;
  rec.wall_seconds = Median(wall);
  rec.solver_stats = result.solver_stats;
  rec.history = result.history;
  if (penalty_stage) {
    rec.continuation = RecordContinuation{spec.continuation,
                                          ToString(penalty_stage->status),
                                          penalty_stage->solver_status,
                                          penalty_stage->message,
                                          penalty_stage->iterations,
                                          penalty_stage->cpu_seconds};
  }
  Judge(spec, p, result, &rec);
  RecordCostateFields(spec, p, result, &rec);
  if (pinfo.reference_value) {
    RecordReference ref;
    ref.value = *pinfo.reference_value;
    ref.quantity = pinfo.reference_quantity;
    ref.source = pinfo.reference_source;
    ref.scheme = pinfo.reference_scheme;
    ref.N = pinfo.reference_intervals;
    rec.reference = ref;
  }
  // A peer's NLP is the problem as posed (default parameters, hard terminal conditions) on the
  // peer's scheme and grid; any other case solves another NLP.
  const bool as_posed = spec.terminal == TerminalMode::kHard && spec.set.empty();
  for (const ProblemReference& peer : pinfo.additional_references) {
    if (!as_posed) break;
    if (peer.scheme == rec.transcription && peer.intervals == rec.N && peer.quantity == "J") {
      rec.nlp_reference =
          RecordReference{peer.value, peer.quantity, peer.source, peer.scheme, peer.intervals};
      break;
    }
  }
  return rec;
}

}  // namespace ocpb
