// `ocpbench online`: one online re-planning run (bench/cli/online_case.h) from the command line.
#include <array>
#include <iostream>
#include <memory>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "bench/cli/app.h"
#include "bench/cli/case_runner.h"
#include "bench/cli/io.h"
#include "bench/cli/output_place.h"

namespace ocpb {
namespace {

std::string OnlineNumber(double v) { return fmt::format("{:.6g}", v); }

void PrintOnlineReport(const Record& r) {
  std::cout << fmt::format("online {} / {}{}  seed {}: status {}\n",
                           r.problem,
                           r.solver,
                           r.transcription.empty() ? "" : " + " + r.transcription,
                           r.seed,
                           r.status);
  if (!r.online || r.online->cycles.empty()) {
    std::cout << "  message: " << r.message << "\n";
    return;
  }
  const OnlineOutcome& o = *r.online;
  std::cout << "  cycle     t0  meas  predict_s    solve_s  iters  status            plan Jbar"
               "   segment true / predicted\n";
  int i = 0;
  for (const nlohmann::json& c : o.cycles) {
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
  std::cout << fmt::format(
      "  online : energy on the true channel {}  (predicted {}), terminal violation {}\n",
      OnlineNumber(o.energy_true),
      OnlineNumber(o.energy_predicted),
      OnlineNumber(r.terminal_violation));
  std::cout << fmt::format(
      "  offline: energy on the true channel {}  (predicted {}), terminal violation {}\n",
      OnlineNumber(o.offline_energy_true),
      OnlineNumber(o.offline_energy_predicted),
      OnlineNumber(o.offline_terminal_violation));
  std::cout << fmt::format("  online / offline true energy = {}   (transmission part: {} / {})\n",
                           OnlineNumber(o.energy_ratio),
                           OnlineNumber(o.transmit_energy_true),
                           OnlineNumber(o.offline_transmit_energy_true));
}

}  // namespace

void AddOnlineCommand(CLI::App& app) {
  auto spec = std::make_shared<CaseSpec>();
  auto json_path = std::make_shared<std::string>();
  auto seed = std::make_shared<std::string>("1");
  auto options = std::make_shared<std::vector<std::string>>();
  auto replan = std::make_shared<std::vector<std::string>>();
  auto settings = std::make_shared<OptionMap>();
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
  cmd->add_option("--seed", *seed, "channel realization and measurement draws (0 to 2^64 - 1)")
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
        flag, [settings, k](const std::string& v) { settings->Set(k, v); }, help);
  }
  cmd->add_flag("--no-refresh", *no_refresh, "never refresh the prediction (control experiment)");
  cmd->add_option("--json", *json_path, "write the JSON record to this file");
  cmd->add_flag("--no-trajectory", *no_trajectory, "leave paths, plans and maps out of the JSON");
  cmd->callback([=]() {
    CaseSpec s = *spec;
    if (n_option->count() > 0 && s.intervals < 1) throw std::invalid_argument("N: must be >= 1");
    s.online = *settings;
    if (*no_refresh) s.online.Set("refresh", 0);
    s.keep_trajectory = !*no_trajectory;
    s.options = ParseKeyValues(*options, "--option");
    s.replan_options = ParseKeyValues(*replan, "--replan-option");
    s.seed = ParseSeed(*seed, "--seed");
    // Every input and the output place are checked before anything is simulated or solved.
    const ResolvedCase resolved = ResolveAndValidate(s);
    // No output (--json, a solver's own output file) may be an input or another output.
    FilePlan plan;
    AddCaseFiles(resolved.spec, "", &plan);
    if (!json_path->empty()) plan.Output(*json_path, "--json");
    plan.Check();
    if (!json_path->empty()) CheckOutputFile(*json_path, "--json");
    const Record record = RunCase(resolved);
    PrintOnlineReport(record);
    if (!json_path->empty()) WriteFileAtomically(*json_path, record.ToJson().dump(1) + "\n");
    if (IsFailure(record.status)) ReportSomeFailed();
  });
}

}  // namespace ocpb
