#include "bench/cli/case_runner.h"

#include <unistd.h>

#include <cmath>
#include <exception>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>

#include "bench/cli/initial_guess.h"
#include "bench/cli/json_values.h"
#include "bench/cli/online_case.h"
#include "core/costate_error.h"
#include "core/evaluator.h"
#include "core/field_sample.h"
#include "core/memory_budget.h"
#include "core/parameters.h"
#include "problems/registry.h"
#include "solvers/continuation.h"
#include "solvers/judge.h"
#include "solvers/registry.h"

namespace ocpb {
namespace {

using nlohmann::json;

std::string Bytes(double b) {
  const char* units[] = {"bytes", "kB", "MB", "GB", "TB", "PB"};
  int i = 0;
  while (b >= 1000.0 && i < 5) {
    b /= 1000.0;
    ++i;
  }
  return fmt::format("{:.3g} {}", b, units[i]);
}

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
  std::unique_ptr<Ocp> ocp;
  TimeGrid grid;
  SolveRequest request;
  MethodOptions options;
};

PreparedCase Prepare(const CaseSpec& spec) {
  PreparedCase p;
  const ProblemInfo& pinfo = FindProblem(spec.problem);
  std::optional<InitialGuess> guess;
  if (!spec.initial_guess.empty()) guess = ReadInitialGuess(spec.initial_guess);
  p.ocp = MakeProblem(spec.problem, spec.set, spec.seed, &p.params);
  const int N = spec.intervals > 0 ? spec.intervals : pinfo.default_intervals;
  p.grid = TimeGrid::Uniform(p.ocp->t0(), p.ocp->tf(), N);
  p.options = ResolveMethodOptions(spec);
  p.request.grid = p.grid;
  p.request.terminal = spec.terminal;
  p.request.integrator = spec.integrator;
  p.request.transcription = spec.transcription;
  p.request.transcription_options = p.options.transcription;
  p.request.options = p.options.solver;
  if (guess) {
    CheckInitialGuess(*guess, *p.ocp, spec.initial_guess);
    p.request.initial_guess = guess->controls;
    p.request.initial_states = guess->states;
    p.request.initial_costates = guess->costates;
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

void CheckTranscriptionFits(const CaseSpec& spec, int nx, int nu) {
  if (spec.transcription.empty() || !FindSolver(spec.solver).uses_transcription) return;
  const TranscriptionInfo& tinfo = FindTranscription(spec.transcription);
  const TranscriptionOptions options = tinfo.Configure(ResolveMethodOptions(spec).transcription);
  std::string error;
  if (!options.scaling.IsValidFor(nx, nu, &error)) {
    throw std::invalid_argument("options: " + tinfo.name + " " + error);
  }
}

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

double EstimateCaseMemoryBytes(const CaseSpec& spec, int nx, int nu, int intervals) {
  double m = 1.0;
  if (!spec.transcription.empty()) {
    m = FindTranscription(spec.transcription)
            .PointsPerInterval(ResolveMethodOptions(spec).transcription);
  }
  return EstimateMethodMemoryBytes(spec.solver, m, nx, nu, intervals);
}

double EstimateMethodMemoryBytes(
    const std::string& solver, double points_per_interval, int nx, int nu, int intervals) {
  const double m = points_per_interval;
  const double nodes = static_cast<double>(intervals) * m + 1.0;
  const double w = nx + nu;
  double bytes = 512.0 * w * nodes;
  if (FindSolver(solver).factorizes_sparse_matrices) {
    bytes += 320.0 * nodes * w * (w + (m + 1.0) * nx);
  }
  return bytes;
}

double CaseMemoryBudgetBytes() { return MemoryBudgetBytes(); }

double EstimateRecordBytes(const CaseSpec& spec, int /*nx*/, int /*nu*/, int /*intervals*/) {
  // `run` holds each record's SummaryPart (bench/cli/run_outputs.h): its fields and its
  // history, one row (an IterationRecord, 56 bytes, and the vector's slack) per iteration, at
  // most the iteration limit the case's options give, and 1000 rows when they give none.
  double rows = 1000.0;
  MethodOptions options;
  try {
    options = ResolveMethodOptions(spec);
  } catch (const std::invalid_argument&) {
    // refused by ValidateCase with its own message
  }
  for (const char* limit : {"max_iterations", "max_iter"}) {
    const OptionValue* v = options.solver.Find(limit);
    if (v != nullptr && v->kind() == OptionValue::Kind::kInteger) {
      rows = std::min(rows, static_cast<double>(std::max<std::int64_t>(v->integer(), 0)) + 1.0);
    }
  }
  return 2048.0 + 64.0 * rows;
}

// The horizon must be long enough for its grid: each step of the judge's 10x finer grid a
// normal double, resolvable next to the horizon's ends (else the grids collapse at solve time,
// with a message about a "time grid" that names no input).
void CheckHorizonSteps(double t0, double tf, int N, const std::string& which) {
  const double fine_step = (tf - t0) / N / 10.0;
  const double scale = std::max(std::abs(t0), std::abs(tf));
  if (!(fine_step >= std::numeric_limits<double>::min()) || !(fine_step >= 1e-12 * scale)) {
    throw std::invalid_argument(fmt::format(
        "tf: the horizon [t0, tf] = [{:g}, {:g}] is too short for {} = {} intervals: a tenth of "
        "each step (tf - t0) / N must be a normal number (>= {:g}) and at least 1e-12 "
        "max(|t0|, |tf|) (choose a larger tf, --set tf=..., or fewer intervals)",
        t0,
        tf,
        which,
        N,
        std::numeric_limits<double>::min()));
  }
}

CaseEstimate ValidateCase(const CaseSpec& spec) {
  spec.Validate();
  // A file a solve writes (Ipopt's output_file) must be writable where it is named, checked
  // here as any output place is (the name's length, the folder, permissions), not when the
  // solver opens it after the work before the solve.
  for (const OptionMap* options : {&spec.options, &spec.replan_options}) {
    for (const auto& [name, value] : *options) {
      if (FilePlan::IsOutputFileOption(name) && !value.empty() && !value.ToText().empty()) {
        CheckOutputFile(value.ToText(), "options: " + name);
      }
    }
  }
  // A solver that keeps a history row per iteration may reserve them all before its first
  // iteration (the Hamiltonian descent does): its iteration limit is a size too, of every
  // solve and of online re-plans.
  for (const auto& [options, field] :
       {std::pair{&spec.options, "options: max_iterations"},
        std::pair{&spec.replan_options, "replan_options: max_iterations"}}) {
    const OptionValue* limit = options->Find("max_iterations");
    if (limit == nullptr) continue;
    std::optional<double> rows;
    if (limit->kind() == OptionValue::Kind::kInteger) {
      rows = static_cast<double>(limit->integer()) + 1.0;
    } else if (limit->kind() == OptionValue::Kind::kText) {
      rows = ParseNumberText(limit->text());  // refused by the solver's schema if not a count
      if (rows) *rows += 1.0;
    }
    if (rows && *rows > 0.0) {
      CheckMemoryEstimate(
          64.0 * *rows, field, fmt::format("{:.0f} history rows (one per iteration)", *rows));
    }
  }
  if (spec.kind == "online") return ValidateOnlineCase(spec);
  const ProblemInfo& pinfo = FindProblem(spec.problem);
  const SolverInfo& sinfo = FindSolver(spec.solver);
  if (sinfo.uses_transcription) {
    if (spec.transcription.empty()) {
      throw std::invalid_argument("solver '" + spec.solver +
                                  "' needs a transcription (--transcription)");
    }
    FindTranscription(spec.transcription);
  } else if (!spec.transcription.empty()) {
    throw std::invalid_argument("solver '" + spec.solver + "' takes no transcription");
  }
  ResolveMethodOptions(spec);
  Parameters params(pinfo.parameters);
  for (const std::string& a : spec.set) params.SetFromString(a);
  // The problem's own cross-field rules (t0 < tf, S and D in the workspace, the channel's
  // options, ...), without simulating a channel.
  const std::unique_ptr<Ocp> ocp = pinfo.make_for_checks ? pinfo.make_for_checks(params, spec.seed)
                                                         : pinfo.make(params, spec.seed);
  if (!ocp) throw std::logic_error("problem '" + spec.problem + "': make returned no problem");
  CheckTranscriptionFits(spec, ocp->nx(), ocp->nu());
  if (!spec.initial_guess.empty()) {
    CheckInitialGuess(ReadInitialGuess(spec.initial_guess), *ocp, spec.initial_guess);
  }
  int N = spec.intervals > 0 ? spec.intervals : pinfo.default_intervals;
  // Mesh refinement may solve meshes up to mesh_max_nodes nodes: the largest one sets the size.
  std::string which = "N";
  if (!spec.transcription.empty()) {
    const MeshRefinementOptions mesh = FindTranscription(spec.transcription)
                                           .Configure(ResolveMethodOptions(spec).transcription)
                                           .mesh;
    if (mesh.enabled() && mesh.max_nodes - 1 > N) {
      N = mesh.max_nodes - 1;
      which = "mesh_max_nodes";
    }
  }
  CheckHorizonSteps(ocp->t0(), ocp->tf(), N, which);
  const double need = EstimateCaseMemoryBytes(spec, ocp->nx(), ocp->nu(), N);
  const double budget = CaseMemoryBudgetBytes();
  CaseEstimate estimate;
  estimate.memory_bytes = need;
  estimate.record_bytes = EstimateRecordBytes(spec, ocp->nx(), ocp->nu(), N);
  if (need > budget) {
    throw std::invalid_argument(fmt::format(
        "{}: {} intervals need about {} by OCPBench's estimate (nx = {}, nu = {}, {}), beyond "
        "this machine's memory budget of {} (half its physical memory)",
        which,
        N,
        Bytes(need),
        ocp->nx(),
        ocp->nu(),
        spec.solver + (spec.transcription.empty() ? "" : " + " + spec.transcription),
        Bytes(budget)));
  }
  const MethodOptions method = ResolveMethodOptions(spec);
  if (!spec.transcription.empty()) {
    // h-refinement builds each refined mesh whole (each interval split in up to
    // 1 + mesh_max_new_points pieces) before comparing it with mesh_max_nodes: that mesh is
    // sized here, before anything is solved.
    const MeshRefinementOptions mesh =
        FindTranscription(spec.transcription).Configure(method.transcription).mesh;
    const bool new_points = method.transcription.Has("mesh_max_new_points");
    if (mesh.enabled() && new_points) {
      if (mesh.max_new_points > mesh.max_nodes) {
        throw std::invalid_argument(fmt::format(
            "options: mesh_max_new_points: must be at most mesh_max_nodes = {} (a refined mesh "
            "has at most that many nodes), got {}",
            mesh.max_nodes,
            mesh.max_new_points));
      }
      const double refined_points = static_cast<double>(N) * (1.0 + mesh.max_new_points) + 1.0;
      CheckMemoryEstimate(
          16.0 * refined_points,
          "mesh_max_new_points",
          fmt::format("refined meshes of up to {:.4g} points ({} intervals, each split in up to "
                      "1 + {} pieces)",
                      refined_points,
                      N,
                      mesh.max_new_points));
    }
  }
  return estimate;
}

Record CaseIdentityRecord(const CaseSpec& spec) {
  Record rec;
  rec.kind = spec.kind;
  rec.key = spec.Key();
  rec.problem = spec.problem;
  rec.seed = spec.seed;
  rec.solver = spec.solver;
  rec.transcription = spec.transcription;
  rec.algorithm = spec.algorithm;
  rec.N = spec.intervals;
  rec.terminal = ToString(spec.terminal);
  rec.integrator = ToString(spec.integrator);
  rec.evaluated_with = ToString(spec.evaluate_with);
  rec.options = spec.options.ToText();
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

Record RunCase(const CaseSpec& given) {
  // Every check before any solving (or channel simulation): bad input fails fast and whole.
  const CaseSpec spec = ResolveCase(given);
  ValidateCase(spec);
  if (spec.kind == "online") return RunOnlineCase(spec);
  const ProblemInfo& pinfo = FindProblem(spec.problem);
  const PreparedCase p = Prepare(spec);
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
