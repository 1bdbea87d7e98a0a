#include "bench/cli/case_runner.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>

#include <fmt/format.h>

#include "bench/cli/channel_sample.h"
#include "bench/cli/initial_guess.h"
#include "bench/cli/online_command.h"
#include "bench/cli/version.h"
#include "core/evaluator.h"
#include "core/parameters.h"
#include "core/timer.h"
#include "problems/comm_path2d.h"
#include "problems/registry.h"
#include "solvers/hamiltonian_descent.h"
#include "solvers/indirect_newton.h"
#include "solvers/ipopt_adapter.h"
#include "solvers/nlopt_adapter.h"
#include "solvers/nlp_solve.h"
#include "solvers/registry.h"

namespace ocpb {
namespace {

using nlohmann::json;

// NaN and infinities have no JSON form: they become null ("not computed" / "never").
json Number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json MatrixRows(const Mat& m) {
  json rows = json::array();
  for (int i = 0; i < m.rows(); ++i) {
    json row = json::array();
    for (int j = 0; j < m.cols(); ++j) row.push_back(Number(m(i, j)));
    rows.push_back(std::move(row));
  }
  return rows;
}

json VectorJson(const Vec& v) {
  json a = json::array();
  for (int i = 0; i < v.size(); ++i) a.push_back(Number(v[i]));
  return a;
}

double Median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

TerminalMode ParseTerminal(const std::string& s) {
  if (s == "penalty") return TerminalMode::kPenalty;
  if (s == "hard") return TerminalMode::kHard;
  throw std::invalid_argument("terminal: unknown form '" + s + "' (valid: penalty, hard)");
}

std::string OptionValueToString(const json& v, const std::string& where) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number_integer()) return std::to_string(v.get<long long>());
  if (v.is_number_float()) {
    const double d = v.get<double>();
    if (!std::isfinite(d)) throw std::invalid_argument(where + ": must be finite");
    return fmt::format("{}", d);
  }
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  throw std::invalid_argument(where + ": must be a string, number or boolean");
}

std::string Bytes(double b) {
  const char* units[] = {"bytes", "kB", "MB", "GB", "TB", "PB"};
  int i = 0;
  while (b >= 1000.0 && i < 5) {
    b /= 1000.0;
    ++i;
  }
  return fmt::format("{:.3g} {}", b, units[i]);
}

// The solver's own option parser, run without solving, so that an unknown key, a bad value or
// an unknown NLopt algorithm fails before anything runs, with the solver's message.
void CheckSolverOptions(const std::string& solver,
                        const std::string& algorithm,
                        const std::map<std::string, std::string>& options) {
  if (!algorithm.empty() && solver != "nlopt") {
    throw std::invalid_argument("algorithm: only the nlopt solver takes one (solver '" + solver +
                                "')");
  }
  NlpScaling scaling;
  if (solver == "hamiltonian") {
    HamiltonianDescent::ParseOptions(options, HamiltonianDescent::Options());
  } else if (solver == "indirect-newton") {
    const IndirectNewton::Options o =
        IndirectNewton::ParseOptions(options, IndirectNewton::Options());
    HamiltonianDescent::ParseOptions(o.warm_start_options, HamiltonianDescent::Options());
  } else if (solver == "ipopt") {
    IpoptOptions::FromStrings(ExtractScalingOptions(options, &scaling), IpoptOptions());
  } else if (solver == "nlopt") {
    std::map<std::string, std::string> strings = ExtractScalingOptions(options, &scaling);
    if (!algorithm.empty()) strings["algorithm"] = algorithm;
    NloptOptions::FromStrings(strings, NloptOptions());
  } else {
    FindSolver(solver);  // unknown: the error lists the valid names
    throw std::logic_error("CheckSolverOptions: no option parser for solver '" + solver + "'");
  }
}

}  // namespace

std::string CaseSpec::Key() const {
  std::string key = fmt::format("{}|seed={}|{}|{}|{}|N={}|deg={}|{}|{}|eval={}",
                                problem,
                                seed,
                                solver,
                                transcription,
                                algorithm,
                                intervals,
                                degree,
                                ToString(terminal),
                                ToString(integrator),
                                ToString(evaluate_with));
  for (const std::string& s : set) key += "|set:" + s;
  for (const auto& [k, v] : options) key += "|opt:" + k + "=" + v;
  if (!initial_guess.empty()) key += "|guess=" + initial_guess;
  if (kind != "solve") {
    key += "|kind=" + kind;
    for (const auto& [k, v] : online) key += "|online:" + k + "=" + v;
    for (const auto& [k, v] : replan_options) key += "|replan:" + k + "=" + v;
  }
  return key;
}

void CaseSpec::Validate() const {
  if (problem.empty()) throw std::invalid_argument("problem: required");
  if (solver.empty()) throw std::invalid_argument("solver: required");
  if (intervals < 0) throw std::invalid_argument("N: must be >= 1 (or omitted for the default)");
  if (degree < 1 || degree > 20) throw std::invalid_argument("degree: must be in 1..20");
  if (repeats < 1 || repeats > 1000) throw std::invalid_argument("repeats: must be in 1..1000");
  if (kind == "online") {
    ValidateOnlineCase(*this);
  } else if (kind != "solve") {
    throw std::invalid_argument("kind: unknown '" + kind + "' (valid: solve, online)");
  } else if (!online.empty() || !replan_options.empty()) {
    throw std::invalid_argument("online, replan_options: only for kind \"online\"");
  }
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
  const double m = spec.transcription == "hermite-simpson" ? 2.0
                   : spec.transcription == "lgr"           ? spec.degree
                                                           : 1.0;
  const double nodes = static_cast<double>(intervals) * m + 1.0;
  const double w = nx + nu;
  double bytes = 512.0 * w * nodes;
  if (spec.solver == "ipopt" || spec.solver == "indirect-newton") {
    bytes += 320.0 * nodes * w * (w + (m + 1.0) * nx);
  }
  return bytes;
}

double CaseMemoryBudgetBytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  const long page_size = ::sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page_size <= 0) return 4.0 * (1 << 30);
  return 0.5 * static_cast<double>(pages) * static_cast<double>(page_size);
}

void ValidateCase(const CaseSpec& spec) {
  spec.Validate();
  if (spec.kind == "online") {
    CheckSolverOptions(spec.solver, spec.algorithm, spec.options);
    // ValidateOnlineCase (in Validate) checked the scenario; the re-plans run with the
    // replan_options over the options.
    std::map<std::string, std::string> replan = spec.options;
    for (const auto& [k, v] : spec.replan_options) replan[k] = v;
    try {
      CheckSolverOptions(spec.solver, spec.algorithm, replan);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("replan_options: ") + e.what());
    }
    return;
  }
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
  CheckSolverOptions(spec.solver, spec.algorithm, spec.options);
  Parameters params(pinfo.parameters);
  for (const std::string& a : spec.set) params.SetFromString(a);
  // The problem's own cross-field rules (t0 < tf, S and D in the workspace, the channel's
  // options, ...), without simulating a channel.
  const std::unique_ptr<Ocp> ocp = pinfo.make_for_checks ? pinfo.make_for_checks(params, spec.seed)
                                                         : pinfo.make(params, spec.seed);
  if (!ocp) throw std::logic_error("problem '" + spec.problem + "': make returned no problem");
  const int N = spec.intervals > 0 ? spec.intervals : pinfo.default_intervals;
  const double need = EstimateCaseMemoryBytes(spec, ocp->nx(), ocp->nu(), N);
  const double budget = CaseMemoryBudgetBytes();
  if (need > budget) {
    throw std::invalid_argument(fmt::format(
        "N: {} intervals need about {} by OCPBench's estimate (nx = {}, nu = {}, {}), beyond this "
        "machine's memory budget of {} (half its physical memory)",
        N,
        Bytes(need),
        ocp->nx(),
        ocp->nu(),
        spec.solver + (spec.transcription.empty() ? "" : " + " + spec.transcription),
        Bytes(budget)));
  }
}

json RunCaseRecordingFailures(const CaseSpec& spec,
                              const std::function<json(const CaseSpec&)>& run) {
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
  return json{{"problem", spec.problem},
              {"seed", spec.seed},
              {"solver", spec.solver},
              {"transcription", spec.transcription},
              {"algorithm", spec.algorithm},
              {"N", spec.intervals},
              {"terminal", ToString(spec.terminal)},
              {"key", spec.Key()},
              {"status", ToString(status)},
              {"solver_status", status == SolveStatus::kError ? "exception" : ""},
              {"message", message},
              {"history", json::array()},
              {"versions", VersionsJson()}};
}

CaseSpec ParseCaseSpec(const json& j, const std::string& where) {
  if (!j.is_object()) throw std::invalid_argument(where + ": a case must be a JSON object");
  static const std::set<std::string> kKeys = {"problem",
                                              "set",
                                              "seed",
                                              "solver",
                                              "transcription",
                                              "algorithm",
                                              "N",
                                              "degree",
                                              "terminal",
                                              "integrator",
                                              "evaluate_with",
                                              "options",
                                              "repeats",
                                              "keep_trajectory",
                                              "kind",
                                              "online",
                                              "replan_options"};
  for (const auto& [k, v] : j.items()) {
    if (!kKeys.count(k)) {
      std::string valid;
      for (const auto& key : kKeys) valid += (valid.empty() ? "" : ", ") + key;
      throw std::invalid_argument(where + ": unknown key '" + k + "' (valid: " + valid + ")");
    }
  }
  auto field = [&](const char* name) { return where + "." + name; };
  auto get_string = [&](const char* name, std::string* out) {
    if (!j.contains(name)) return;
    if (!j[name].is_string()) throw std::invalid_argument(field(name) + ": must be a string");
    *out = j[name].get<std::string>();
  };
  auto get_int = [&](const char* name, long long lo, long long hi, long long* out) {
    if (!j.contains(name)) return;
    const json& v = j[name];
    if (!v.is_number_integer()) {
      throw std::invalid_argument(field(name) + ": must be an integer");
    }
    const long long x = v.get<long long>();
    if (x < lo || x > hi) {
      throw std::invalid_argument(
          fmt::format("{}: {} out of range [{}, {}]", field(name), x, lo, hi));
    }
    *out = x;
  };
  CaseSpec spec;
  get_string("problem", &spec.problem);
  get_string("solver", &spec.solver);
  get_string("transcription", &spec.transcription);
  get_string("algorithm", &spec.algorithm);
  long long seed = 1, n = 0, degree = 3, repeats = 1;
  get_int("seed", 0, (1LL << 53), &seed);
  get_int("N", 1, std::numeric_limits<int>::max(), &n);  // the memory check is ValidateCase's
  get_int("degree", 1, 20, &degree);
  get_int("repeats", 1, 1000, &repeats);
  spec.seed = static_cast<std::uint64_t>(seed);
  spec.intervals = static_cast<int>(n);
  spec.degree = static_cast<int>(degree);
  spec.repeats = static_cast<int>(repeats);
  std::string s;
  if (j.contains("terminal")) {
    get_string("terminal", &s);
    try {
      spec.terminal = ParseTerminal(s);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(where + "." + e.what());
    }
  }
  for (const char* name : {"integrator", "evaluate_with"}) {
    if (!j.contains(name)) continue;
    s.clear();
    get_string(name, &s);
    try {
      (std::string(name) == "integrator" ? spec.integrator : spec.evaluate_with) =
          ParseIntegrator(s);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(field(name) + ": " + e.what());
    }
  }
  if (j.contains("keep_trajectory")) {
    if (!j["keep_trajectory"].is_boolean()) {
      throw std::invalid_argument(field("keep_trajectory") + ": must be true or false");
    }
    spec.keep_trajectory = j["keep_trajectory"].get<bool>();
  }
  if (j.contains("set")) {
    const json& set = j["set"];
    if (!set.is_object()) {
      throw std::invalid_argument(field("set") +
                                  ": must be an object {\"key\": value or [values]}");
    }
    for (const auto& [k, v] : set.items()) {
      const std::string where_k = field("set") + "." + k;
      std::vector<double> values;
      auto push = [&](const json& x) {
        if (!x.is_number())
          throw std::invalid_argument(where_k + ": must be a number or a list of numbers");
        const double d = x.get<double>();
        if (!std::isfinite(d)) throw std::invalid_argument(where_k + ": must be finite");
        values.push_back(d);
      };
      if (v.is_array()) {
        if (v.empty()) throw std::invalid_argument(where_k + ": empty list");
        for (const json& x : v) push(x);
      } else {
        push(v);
      }
      std::string text = k + "=";
      for (size_t i = 0; i < values.size(); ++i)
        text += (i ? "," : "") + fmt::format("{}", values[i]);
      spec.set.push_back(text);
    }
  }
  get_string("kind", &spec.kind);
  auto get_map = [&](const char* name, std::map<std::string, std::string>* out) {
    if (!j.contains(name)) return;
    const json& opts = j[name];
    if (!opts.is_object()) throw std::invalid_argument(field(name) + ": must be an object");
    for (const auto& [k, v] : opts.items()) {
      (*out)[k] = OptionValueToString(v, field(name) + "." + k);
    }
  };
  get_map("options", &spec.options);
  get_map("online", &spec.online);
  get_map("replan_options", &spec.replan_options);
  if (spec.problem.empty()) throw std::invalid_argument(field("problem") + ": required");
  if (spec.solver.empty()) throw std::invalid_argument(field("solver") + ": required");
  return spec;
}

json VersionsJson() {
  return json{{"ocpbench", OCPB_VERSION},
              {"commit", GitCommit()},
              {"compiler", CompilerVersion()},
              {"ipopt", IpoptVersion()},
              {"nlopt", NloptVersion()}};
}

json RunCase(const CaseSpec& spec) {
  // Every check before any solving (or channel simulation): bad input fails fast and whole.
  ValidateCase(spec);
  if (spec.kind == "online") return RunOnlineCase(spec);
  const ProblemInfo& pinfo = FindProblem(spec.problem);
  const SolverInfo& sinfo = FindSolver(spec.solver);
  std::optional<ControlTrajectory> guess;
  if (!spec.initial_guess.empty()) guess = ReadInitialGuess(spec.initial_guess);
  Parameters params;
  const std::unique_ptr<Ocp> ocp = MakeProblem(spec.problem, spec.set, spec.seed, &params);
  const int N = spec.intervals > 0 ? spec.intervals : pinfo.default_intervals;
  const TimeGrid grid = TimeGrid::Uniform(ocp->t0(), ocp->tf(), N);

  SolveRequest request;
  request.grid = grid;
  request.terminal = spec.terminal;
  request.integrator = spec.integrator;
  request.transcription = spec.transcription;
  request.algorithm = spec.algorithm;
  request.degree = spec.degree;
  request.options = spec.options;
  if (guess) {
    CheckInitialGuess(*guess, *ocp, spec.initial_guess);
    request.initial_guess = guess;
  }

  const std::unique_ptr<Solver> solver = sinfo.make();
  SolveResult result;
  std::vector<double> cpu, wall;
  for (int r = 0; r < spec.repeats; ++r) {
    try {
      result = solver->Solve(*ocp, request);
    } catch (const std::invalid_argument&) {
      throw;  // an invalid request (options): bad input, reported by the caller
    } catch (const std::exception& e) {
      result = SolveResult();
      result.solver = spec.solver;
      result.status = SolveStatus::kError;
      result.solver_status = "exception";
      result.message = e.what();
    }
    cpu.push_back(result.cpu_seconds);
    wall.push_back(result.wall_seconds);
  }

  json rec;
  rec["problem"] = spec.problem;
  json pj = json::object();
  for (const auto& [k, v] : params.values()) pj[k] = v.size() == 1 ? json(v[0]) : json(v);
  rec["parameters"] = pj;
  rec["seed"] = spec.seed;
  rec["uses_seed"] = pinfo.uses_seed;
  rec["solver"] = spec.solver;
  rec["transcription"] = spec.transcription;
  rec["algorithm"] = spec.algorithm;
  rec["N"] = N;
  if (spec.transcription == "lgr") rec["degree"] = spec.degree;
  rec["terminal"] = ToString(spec.terminal);
  rec["integrator"] = ToString(spec.integrator);
  rec["evaluated_with"] = ToString(spec.evaluate_with);
  json oj = json::object();
  for (const auto& [k, v] : spec.options) oj[k] = v;
  rec["options"] = oj;
  if (!spec.initial_guess.empty()) rec["initial_guess"] = spec.initial_guess;
  rec["key"] = spec.Key();
  rec["status"] = ToString(result.status);
  rec["solver_status"] = result.solver_status;
  rec["message"] = result.message;
  rec["objective"] = Number(result.objective);
  rec["iterations"] = result.iterations;
  rec["cpu_seconds"] = Number(Median(cpu));
  rec["cpu_seconds_repeats"] = cpu;
  rec["wall_seconds"] = Number(Median(wall));
  rec["repeats"] = spec.repeats;
  json stats = json::object();
  for (const auto& [k, v] : result.solver_stats) stats[k] = Number(v);
  rec["solver_stats"] = stats;

  // A method that did not run has nothing to judge (its "controls" would be the start).
  const bool has_controls =
      result.controls.nu() == ocp->nu() && result.status != SolveStatus::kNotApplicable;
  // A free final time is judged on the solution's own horizon [t0, T] (the end of its
  // state_grid): the request's grid stretched to T; a fixed horizon on the request's grid.
  const bool free_time = ocp->free_final_time().has_value() && result.state_grid.size() >= 2;
  const TimeGrid judged = free_time ? grid.StretchedTo(result.state_grid.tf()) : grid;
  rec["final_time"] = has_controls ? Number(judged.tf()) : json(nullptr);
  rec["final_time_free"] = ocp->free_final_time().has_value();
  if (has_controls) {
    const Evaluation ev = Evaluate(*ocp, result.controls, judged, spec.evaluate_with);
    const Evaluation fine = Evaluate(*ocp, result.controls, judged.Refined(10), Integrator::kRk4);
    rec["J"] = Number(ev.J);
    rec["Jbar"] = Number(ev.Jbar);
    rec["terminal_violation"] = Number(ev.terminal_violation);
    rec["terminal_residual"] = VectorJson(ev.terminal_residual);
    rec["control_violation"] = Number(ev.control_violation);
    rec["path_violation"] = Number(ev.path_violation);
    rec["final_state"] = VectorJson(ev.X.col(N));
    rec["J_fine"] = Number(fine.J);
    rec["Jbar_fine"] = Number(fine.Jbar);
    rec["terminal_violation_fine"] = Number(fine.terminal_violation);
    const bool has_states = result.states.rows() == ocp->nx() &&
                            result.states.cols() == result.state_grid.size() &&
                            result.state_grid.size() >= 2;
    rec["resimulation_defect"] =
        has_states
            ? Number(ResimulationDefect(*ocp, result.controls, result.state_grid, result.states))
            : json(nullptr);
    if (!ev.finite && !IsFailure(result.status) && result.status != SolveStatus::kNotApplicable) {
      rec["status"] = ToString(SolveStatus::kNumericalFailure);
      rec["message"] = result.message + " (evaluator: trajectory or cost not finite)";
    }
    if (spec.keep_trajectory) {
      json traj;
      traj["t"] = judged.points();
      traj["x"] = MatrixRows(ev.X);
      traj["u"] = MatrixRows(result.controls.SampleIntervals(judged));
      traj["u_rule"] = "value at each interval's left end; piecewise " +
                       std::string(result.controls.InterpolationName());
      rec["trajectory"] = traj;
      if (const auto* comm = dynamic_cast<const CommPath2d*>(ocp.get())) {
        rec["s_map"] = ChannelSampleJson(comm->channel(), comm->options().workspace);
      }
    }
  } else {
    for (const char* k : {"J",
                          "Jbar",
                          "terminal_violation",
                          "control_violation",
                          "path_violation",
                          "J_fine",
                          "Jbar_fine",
                          "terminal_violation_fine",
                          "resimulation_defect"}) {
      rec[k] = nullptr;
    }
    rec["final_state"] = json::array();
  }
  if (pinfo.reference_value) {
    json ref{{"value", *pinfo.reference_value},
             {"quantity", pinfo.reference_quantity},
             {"source", pinfo.reference_source},
             {"scheme", pinfo.reference_scheme}};
    if (pinfo.reference_scheme != "continuous") ref["N"] = pinfo.reference_intervals;
    rec["reference"] = ref;
  }
  json hist = json::array();
  for (const IterationRecord& h : result.history) {
    hist.push_back(json{{"iteration", h.iteration},
                        {"J", Number(h.J)},
                        {"theta", Number(h.theta)},
                        {"armijo_j", h.armijo_j},
                        {"primal_inf", Number(h.primal_inf)},
                        {"dual_inf", Number(h.dual_inf)},
                        {"cpu_seconds", Number(h.cpu_seconds)}});
  }
  rec["history"] = hist;
  rec["versions"] = VersionsJson();
  return rec;
}

}  // namespace ocpb
