#include "bench/cli/online_command.h"

#include <array>
#include <cmath>
#include <iostream>
#include <memory>
#include <set>
#include <stdexcept>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "bench/cli/app.h"
#include "bench/cli/io.h"
#include "core/parameters.h"
#include "problems/online/online_replanning.h"
#include "problems/registry.h"
#include "solvers/registry.h"

namespace ocpb {
namespace {

using nlohmann::json;

json Number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json Rows(const Mat& m, int rows) {
  json out = json::array();
  for (int i = 0; i < rows; ++i) {
    json row = json::array();
    for (int j = 0; j < m.cols(); ++j) row.push_back(Number(m(i, j)));
    out.push_back(std::move(row));
  }
  return out;
}

json VectorJson(const Vec& v) {
  json a = json::array();
  for (int i = 0; i < v.size(); ++i) a.push_back(Number(v[i]));
  return a;
}

// Everything an online case needs, resolved from a CaseSpec.
struct OnlineSetup {
  CommPath2d::Options problem;
  OnlineChannelOptions channel;
  OnlineReplanningOptions replanning;
  Parameters params;
  double smap_resolution = 1.0;
  json settings;  // resolved scenario settings, for the record
};

double ParseNumber(const std::string& key, const std::string& text) {
  size_t used = 0;
  double v = NAN;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || used == 0 || !std::isfinite(v)) {
    throw std::invalid_argument("online." + key + ": '" + text + "' is not a finite number");
  }
  return v;
}

int ParseInteger(const std::string& key, const std::string& text) {
  const double v = ParseNumber(key, text);
  if (v != std::floor(v) || std::abs(v) > 1e9) {
    throw std::invalid_argument("online." + key + ": '" + text + "' is not an integer");
  }
  return static_cast<int>(v);
}

OnlineSetup Resolve(const CaseSpec& spec) {
  if (spec.problem != "comm-path2d") {
    throw std::invalid_argument(
        "problem: online re-planning is defined for comm-path2d only, got '" + spec.problem + "'");
  }
  static const std::set<std::string> kKeys = {"update_period",
                                              "initial_measurements",
                                              "measurements_per_update",
                                              "placement",
                                              "map_resolution",
                                              "truth_resolution",
                                              "workspace",
                                              "refresh",
                                              "region_margin",
                                              "smap_resolution",
                                              "estimator"};
  for (const auto& [k, v] : spec.online) {
    if (!kKeys.count(k)) {
      std::string valid;
      for (const std::string& key : kKeys) valid += (valid.empty() ? "" : ", ") + key;
      throw std::invalid_argument("online: unknown setting '" + k + "' (valid: " + valid + ")");
    }
  }
  auto get = [&](const char* key, const std::string& fallback) {
    const auto it = spec.online.find(key);
    return it == spec.online.end() ? fallback : it->second;
  };
  OnlineSetup s;
  const ProblemInfo& pinfo = FindProblem(spec.problem);
  s.params = Parameters(pinfo.parameters);
  for (const std::string& a : spec.set) {
    const std::string name = a.substr(0, a.find('='));
    if (name == "samples" || name == "channel" || name == "t0") {
      throw std::invalid_argument("set " + name +
                                  ": not used by online re-planning (the channel is the GP map of "
                                  "the measurements so far; the run starts at t0 = 0; see "
                                  "--initial-measurements)");
    }
    s.params.SetFromString(a);
  }
  s.problem = CommPath2dOptionsFromParameters(s.params);

  OnlineReplanningOptions& r = s.replanning;
  r.update_period = ParseNumber("update_period", get("update_period", "10"));
  r.initial_measurements = ParseInteger("initial_measurements", get("initial_measurements", "100"));
  r.measurements_per_update =
      ParseInteger("measurements_per_update", get("measurements_per_update", "100"));
  try {
    r.placement = MeasurementPlacementFromString(get("placement", "random"));
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("online.") + e.what());
  }
  r.intervals = spec.intervals > 0 ? spec.intervals : pinfo.default_intervals;
  r.solver = spec.solver;
  const SolverInfo& sinfo = FindSolver(spec.solver);
  r.transcription = spec.transcription;
  if (sinfo.uses_transcription && r.transcription.empty()) r.transcription = "euler";
  if (sinfo.uses_transcription) FindTranscription(r.transcription);
  if (!sinfo.uses_transcription && !r.transcription.empty()) {
    throw std::invalid_argument("solver '" + spec.solver + "' takes no transcription");
  }
  r.offline_options = spec.options;
  r.replan_options = spec.options;
  // The paper's re-plans take "under 50 iterations"; the plan at t0 = 0 keeps the solver's default.
  if (spec.solver == "hamiltonian" && !spec.options.count("max_iterations")) {
    r.replan_options["max_iterations"] = "50";
  }
  // A warm start is near the optimum: a small initial barrier parameter saves Ipopt iterations
  // (seed 1: 8-12 instead of 11-14 per re-plan).
  if (spec.solver == "ipopt" && !spec.options.count("mu_init"))
    r.replan_options["mu_init"] = "1e-4";
  for (const auto& [k, v] : spec.replan_options) r.replan_options[k] = v;
  std::string error;
  if (!r.IsValid(&error)) throw std::invalid_argument("online." + error);

  // The problem's channel parameters (--set workspace=..., grid_step=..., estimator=...) are the
  // defaults of the scenario's own settings of the same meaning.
  const double workspace =
      ParseNumber("workspace", get("workspace", fmt::format("{}", s.params.Scalar("workspace"))));
  const double truth_h = ParseNumber(
      "truth_resolution", get("truth_resolution", fmt::format("{}", s.params.Scalar("grid_step"))));
  if (!(workspace > 0.0) || !(truth_h > 0.0) || workspace / truth_h > 5000.0 ||
      workspace / truth_h < 8.0) {
    throw std::invalid_argument(
        "online.workspace, online.truth_resolution: need > 0 and 8 to 5000 cells per side");
  }
  s.problem.workspace = workspace;
  OnlineChannelOptions& c = s.channel;
  c.truth.k_pl = s.params.Scalar("K_PL");
  c.truth.n_pl = s.params.Scalar("n_PL");
  c.truth.xi = s.params.Scalar("xi");
  c.truth.eta = s.params.Scalar("eta");
  c.truth.rho = s.params.Scalar("rho");
  c.truth.base_station = s.params.Vector("base");
  c.truth.distance_floor = s.params.Scalar("distance_floor");
  c.simulation.multipath.rician_k = s.params.Scalar("rician_K");
  c.predictor.units.noise_dbm = s.params.Scalar("N0_dBm");
  c.estimate = s.params.Integer("estimate") == 1;
  c.simulation.grid = GridSpec::Workspace(workspace, workspace, truth_h);
  if (!c.simulation.grid.Contains(c.truth.base_station)) {
    throw std::invalid_argument(fmt::format("base: ({}, {}) lies outside the workspace [0, {}]^2",
                                            c.truth.base_station.x(),
                                            c.truth.base_station.y(),
                                            workspace));
  }
  c.map_resolution = ParseNumber("map_resolution", get("map_resolution", "0.5"));
  if (!(c.map_resolution >= truth_h) || workspace / c.map_resolution < 4.0) {
    throw std::invalid_argument(
        "online.map_resolution: must be >= truth_resolution and give >= 4 cells per side");
  }
  c.region_margin = ParseNumber("region_margin", get("region_margin", "10"));
  try {
    c.estimation.method = EstimationMethodFromString(
        get("estimator", ToString(EstimationMethodFromCode(s.params.Integer("estimator")))));
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("online.estimator: ") + e.what());
  }
  const int refresh = ParseInteger("refresh", get("refresh", "1"));
  if (refresh != 0 && refresh != 1) throw std::invalid_argument("online.refresh: must be 0 or 1");
  c.refresh = refresh == 1;
  if (!c.IsValid(&error)) throw std::invalid_argument("online: " + error);
  s.smap_resolution = ParseNumber("smap_resolution", get("smap_resolution", "1"));
  if (!(s.smap_resolution >= truth_h) || workspace / s.smap_resolution < 2.0) {
    throw std::invalid_argument("online.smap_resolution: must be >= truth_resolution");
  }
  // The initial state and the problem's own rules, checked now (before a channel is simulated).
  if (!s.problem.IsValid(&error)) throw std::invalid_argument("comm-path2d: " + error);
  if (s.problem.t0 != 0.0) throw std::invalid_argument("t0: the online scenario starts at 0");
  const double h = s.problem.tf / r.intervals;
  const double steps = r.update_period / h;
  if (std::abs(steps - std::round(steps)) > 1e-6 * std::max(1.0, steps) || std::round(steps) < 1) {
    throw std::invalid_argument(
        fmt::format("online.update_period: {} s is not a positive multiple of the step tf/N = {} s",
                    r.update_period,
                    h));
  }
  const long cells = std::lround(workspace / truth_h) * std::lround(workspace / truth_h);
  const long updates = static_cast<long>(std::ceil(r.intervals / std::round(steps))) - 1;
  const long needed = r.initial_measurements + updates * r.measurements_per_update;
  if (2 * needed > cells) {
    throw std::invalid_argument(
        fmt::format("online: {} measurements in all need at least {} truth cells (have {})",
                    needed,
                    2 * needed,
                    cells));
  }

  s.settings = json{{"update_period", r.update_period},
                    {"initial_measurements", r.initial_measurements},
                    {"measurements_per_update", r.measurements_per_update},
                    {"placement", ToString(r.placement)},
                    {"map_resolution", c.map_resolution},
                    {"truth_resolution", truth_h},
                    {"workspace", workspace},
                    {"refresh", c.refresh ? 1 : 0},
                    {"region_margin", c.region_margin},
                    {"smap_resolution", s.smap_resolution},
                    {"estimator", ToString(c.estimation.method)}};
  return s;
}

json ParametersJson(const Parameters& params) {
  json pj = json::object();
  for (const auto& [k, v] : params.values()) pj[k] = v.size() == 1 ? json(v[0]) : json(v);
  return pj;
}

json ChannelJson(const ChannelParameters& p) {
  return json{{"K_PL", p.k_pl}, {"n_PL", p.n_pl}, {"xi", p.xi}, {"eta", p.eta}, {"rho", p.rho}};
}

std::string AggregateStatus(const OnlineResult& r) {
  for (const OnlineCycle& c : r.cycles) {
    if (IsFailure(c.status)) return ToString(c.status);
  }
  for (const OnlineCycle& c : r.cycles) {
    if (!IsSuccess(c.status)) return ToString(c.status);
  }
  return ToString(SolveStatus::kConverged);
}

std::string Fmt(double v) { return fmt::format("{:.6g}", v); }

void PrintReport(const json& r) {
  std::cout << fmt::format("online {} / {}{}  seed {}: status {}\n",
                           r["problem"].get<std::string>(),
                           r["solver"].get<std::string>(),
                           r["transcription"].get<std::string>().empty()
                               ? ""
                               : " + " + r["transcription"].get<std::string>(),
                           r["seed"].get<std::uint64_t>(),
                           r["status"].get<std::string>());
  if (!r.contains("cycles")) {
    std::cout << "  message: " << r["message"].get<std::string>() << "\n";
    return;
  }
  std::cout << "  cycle     t0  meas  predict_s    solve_s  iters  status            plan Jbar"
               "   segment true / predicted\n";
  int i = 0;
  for (const json& c : r["cycles"]) {
    std::cout << fmt::format(
        "  {:5d} {:6.1f} {:5d} {:10.4f} {:10.4f} {:6d}  {:<16} {:10.3f}   "
        "{:.3f} / {:.3f}\n",
        i++,
        c["t0"].get<double>(),
        c["measurements"].get<int>(),
        c["predict_seconds"].get<double>(),
        c["solve_seconds"].get<double>(),
        c["iterations"].get<int>(),
        c["status"].get<std::string>(),
        c["planned_energy"].is_number() ? c["planned_energy"].get<double>() : NAN,
        c["segment_energy_true"].get<double>(),
        c["segment_energy_predicted"].get<double>());
  }
  auto num = [&](const char* k) { return r[k].is_number() ? r[k].get<double>() : NAN; };
  std::cout << fmt::format(
      "  online : energy on the true channel {}  (predicted {}), terminal "
      "violation {}\n",
      Fmt(num("energy_true")),
      Fmt(num("energy_predicted")),
      Fmt(num("terminal_violation")));
  std::cout << fmt::format(
      "  offline: energy on the true channel {}  (predicted {}), terminal "
      "violation {}\n",
      Fmt(num("offline_energy_true")),
      Fmt(num("offline_energy_predicted")),
      Fmt(num("offline_terminal_violation")));
  std::cout << fmt::format("  online / offline true energy = {}   (transmission part: {} / {})\n",
                           Fmt(num("energy_ratio")),
                           Fmt(num("transmit_energy_true")),
                           Fmt(num("offline_transmit_energy_true")));
}

}  // namespace

void ValidateOnlineCase(const CaseSpec& spec) { Resolve(spec); }

json RunOnlineCase(const CaseSpec& spec) {
  const OnlineSetup s = Resolve(spec);
  OnlineChannel channel(spec.seed, s.channel);
  OnlineResult r;
  std::string failure;
  try {
    r = RunOnlineReplanning(s.problem, &channel, spec.seed, s.replanning);
  } catch (const std::invalid_argument&) {
    throw;  // the caller's input
  } catch (const std::exception& e) {
    failure = e.what();  // e.g. the robot left the workspace: recorded, a suite goes on
  }

  json rec;
  rec["kind"] = "online";
  rec["problem"] = spec.problem;
  rec["parameters"] = ParametersJson(s.params);
  rec["seed"] = spec.seed;
  rec["uses_seed"] = true;
  rec["solver"] = spec.solver;
  rec["transcription"] = s.replanning.transcription;
  rec["algorithm"] = spec.algorithm;
  rec["N"] = s.replanning.intervals;
  rec["terminal"] = ToString(TerminalMode::kPenalty);
  rec["integrator"] = ToString(Integrator::kEuler);
  rec["evaluated_with"] = ToString(Integrator::kEuler);
  json opts = json::object(), replan = json::object();
  for (const auto& [k, v] : s.replanning.offline_options) opts[k] = v;
  for (const auto& [k, v] : s.replanning.replan_options) replan[k] = v;
  rec["options"] = opts;
  rec["replan_options"] = replan;
  rec["online"] = s.settings;
  rec["key"] = spec.Key();
  if (!failure.empty()) {
    rec["status"] = ToString(SolveStatus::kError);
    rec["solver_status"] = "exception";
    rec["message"] = failure;
    rec["history"] = json::array();
    rec["versions"] = VersionsJson();
    return rec;
  }
  rec["status"] = AggregateStatus(r);
  rec["solver_status"] = "";
  rec["message"] =
      fmt::format("{} cycles; energy on the true channel: online {:.6g}, offline {:.6g}",
                  r.cycles.size(),
                  r.energy_true,
                  r.offline_energy_true);
  json cycles = json::array();
  double cpu = 0.0;
  int iterations = 0;
  for (const OnlineCycle& c : r.cycles) {
    json cj{{"t0", c.t0},
            {"first_step", c.first_step},
            {"steps_executed", c.steps_executed},
            {"predict_seconds", c.predict.total()},
            {"estimate_seconds", c.predict.estimate_seconds},
            {"factor_seconds", c.predict.factor_seconds},
            {"grid_seconds", c.predict.grid_seconds},
            {"map_seconds", c.predict.map_seconds},
            {"estimation_failed", c.predict.estimation_failed},
            {"map_region",
             {c.map_grid.x_min, c.map_grid.y_min, c.map_grid.x_max(), c.map_grid.y_max()}},
            {"solve_seconds", c.solve_seconds},
            {"iterations", c.iterations},
            {"status", ToString(c.status)},
            {"solver_status", c.solver_status},
            {"new_measurements", c.new_measurements},
            {"measurements", c.measurements},
            {"measurement_stream", c.measurement_stream},
            {"estimated", ChannelJson(c.estimated)},
            {"planned_energy", Number(c.planned_energy)},
            {"planned_J", Number(c.planned_J)},
            {"segment_energy_true", Number(c.segment_energy_true)},
            {"segment_energy_predicted", Number(c.segment_energy_predicted)}};
    if (spec.keep_trajectory) {
      cj["plan"] = json{{"t", c.plan_times}, {"x", Rows(c.plan_states, 2)}};
    }
    cycles.push_back(std::move(cj));
    cpu += c.predict.total() + c.solve_seconds;
    iterations += std::max(c.iterations, 0);
  }
  rec["cycles"] = cycles;
  rec["energy_true"] = Number(r.energy_true);
  rec["energy_predicted"] = Number(r.energy_predicted);
  rec["transmit_energy_true"] = Number(r.transmit_energy_true);
  rec["offline_transmit_energy_true"] = Number(r.offline_transmit_energy_true);
  rec["transmit_energy_ratio"] = Number(r.transmit_energy_true / r.offline_transmit_energy_true);
  rec["J_true"] = Number(r.J_true);
  rec["terminal_violation"] = Number(r.terminal_violation);
  rec["terminal_residual"] = VectorJson(r.terminal_residual);
  rec["final_state"] = VectorJson(r.X.col(r.X.cols() - 1));
  rec["offline_energy_true"] = Number(r.offline_energy_true);
  rec["offline_energy_predicted"] = Number(r.offline_energy_predicted);
  rec["offline_J_true"] = Number(r.offline_J_true);
  rec["offline_terminal_violation"] = Number(r.offline_terminal_violation);
  rec["offline_terminal_residual"] = VectorJson(r.offline_terminal_residual);
  rec["offline_solve_seconds"] = Number(r.offline_solve_seconds);
  rec["energy_ratio"] = Number(r.energy_true / r.offline_energy_true);
  // For the suite summary's columns: J and Jbar of what was executed, on the true channel.
  rec["J"] = Number(r.J_true);
  rec["Jbar"] = Number(r.energy_true);
  rec["iterations"] = iterations;
  rec["cpu_seconds"] = Number(cpu);
  rec["repeats"] = 1;
  rec["history"] = json::array();
  if (spec.keep_trajectory) {
    const json t = r.grid.points();
    rec["executed"] = json{{"t", t}, {"x", Rows(r.X, 5)}, {"u", Rows(r.U, 3)}};
    rec["offline"] = json{{"t", t}, {"x", Rows(r.offline_X, 5)}, {"u", Rows(r.offline_U, 3)}};
    json mx = json::array(), my = json::array(), mc = json::array();
    const MeasurementSet& m = channel.measurements();
    size_t k = 0;
    for (size_t ci = 0; ci < r.cycles.size(); ++ci) {
      for (int j = 0; j < r.cycles[ci].new_measurements; ++j, ++k) {
        mx.push_back(m.positions[k].x());
        my.push_back(m.positions[k].y());
        mc.push_back(ci);
      }
    }
    rec["measurements"] = json{{"x", mx}, {"y", my}, {"cycle", mc}};
    std::vector<double> x, y;
    Eigen::MatrixXd predicted, truth;
    channel.SampleLog10(s.smap_resolution, &x, &y, &predicted, &truth);
    rec["s_map"] = json{{"x", x},
                        {"y", y},
                        {"log10_s", Rows(truth, static_cast<int>(truth.rows()))},
                        {"log10_s_predicted", Rows(predicted, static_cast<int>(predicted.rows()))},
                        {"what",
                         "log10_s: the true channel's 1/CNR (W); log10_s_predicted: the "
                         "last prediction's E[1/CNR]"}};
  }
  rec["versions"] = VersionsJson();
  return rec;
}

void AddOnlineCommand(CLI::App& app) {
  auto spec = std::make_shared<CaseSpec>();
  auto json_path = std::make_shared<std::string>();
  auto options = std::make_shared<std::vector<std::string>>();
  auto replan = std::make_shared<std::vector<std::string>>();
  auto settings = std::make_shared<std::map<std::string, std::string>>();
  auto no_trajectory = std::make_shared<bool>(false);
  auto no_refresh = std::make_shared<bool>(false);
  spec->kind = "online";
  CLI::App* cmd = app.add_subcommand(
      "online",
      "Re-plan online with channel updates (paper Sec. IV); judged on the true channel against "
      "the offline plan");
  cmd->add_option("--problem", spec->problem, "problem (comm-path2d)")->required();
  cmd->add_option("--solver", spec->solver, "hamiltonian | ipopt (ocpbench list solvers)")
      ->required();
  cmd->add_option("--transcription", spec->transcription, "NLP solvers (default: euler)");
  CLI::Option* n_option = cmd->add_option("--N", spec->intervals, "intervals on [0, tf] (400)");
  cmd->add_option("--seed", spec->seed, "channel realization and measurement draws")
      ->capture_default_str();
  cmd->add_option("--set", spec->set, "problem parameter, key=value (repeatable)");
  cmd->add_option("--option", *options, "solver option of every solve, key=value (repeatable)");
  cmd->add_option("--replan-option", *replan, "solver option of the re-plans only (repeatable)");
  for (const auto& [flag, key, help] : std::vector<std::array<std::string, 3>>{
           {"--period", "update_period", "seconds between channel updates (10)"},
           {"--initial-measurements", "initial_measurements", "measurements at t0 = 0 (100)"},
           {"--per-update", "measurements_per_update", "new measurements per update (100)"},
           {"--placement",
            "placement",
            "random | path (driven since the last update) | plan (rest of the plan) (random)"},
           {"--estimator",
            "estimator",
            "channel parameter estimator: binned | ml | reml (the channel library's default)"},
           {"--map-resolution", "map_resolution", "grid of the re-predicted s map, m (0.5)"},
           {"--truth-resolution", "truth_resolution", "grid of the simulated channel, m (0.1)"},
           {"--workspace", "workspace", "side of the simulated square workspace, m (50)"},
           {"--region-margin",
            "region_margin",
            "re-predict only around the robot, D and its plan, grown by this margin, m (10; 0: "
            "everywhere)"},
           {"--smap-resolution", "smap_resolution", "grid of the s maps in the JSON, m (1)"}}) {
    const std::string k = key;
    cmd->add_option_function<std::string>(
        flag, [settings, k](const std::string& v) { (*settings)[k] = v; }, help);
  }
  cmd->add_flag("--no-refresh", *no_refresh, "never refresh the prediction (control experiment)");
  cmd->add_option("--json", *json_path, "write the JSON record to this file");
  cmd->add_flag("--no-trajectory", *no_trajectory, "leave paths, plans and maps out of the JSON");
  cmd->callback([=]() {
    CaseSpec s = *spec;
    if (n_option->count() > 0 && s.intervals < 1) throw std::invalid_argument("N: must be >= 1");
    s.online = *settings;
    if (*no_refresh) s.online["refresh"] = "0";
    s.keep_trajectory = !*no_trajectory;
    auto parse = [](const std::vector<std::string>& list,
                    const char* flag,
                    std::map<std::string, std::string>* out) {
      for (const std::string& o : list) {
        const auto eq = o.find('=');
        if (eq == std::string::npos || eq == 0) {
          throw std::invalid_argument(std::string("malformed ") + flag + " '" + o +
                                      "': expected key=value");
        }
        (*out)[o.substr(0, eq)] = o.substr(eq + 1);
      }
    };
    parse(*options, "--option", &s.options);
    parse(*replan, "--replan-option", &s.replan_options);
    const json record = RunCase(s);
    PrintReport(record);
    if (!json_path->empty()) WriteFileAtomically(*json_path, record.dump(1) + "\n");
    const std::string status = record["status"].get<std::string>();
    for (SolveStatus st : {SolveStatus::kNumericalFailure,
                           SolveStatus::kInfeasible,
                           SolveStatus::kError,
                           SolveStatus::kInvalidInput}) {
      if (status == ToString(st)) ReportSomeFailed();
    }
  });
}

}  // namespace ocpb
