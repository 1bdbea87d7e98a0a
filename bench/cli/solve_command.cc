// `ocpbench solve`: one problem, one method, one JSON record.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>

#include <fmt/format.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "bench/cli/app.h"
#include "bench/cli/case_runner.h"
#include "bench/cli/io.h"
#include "bench/cli/output_place.h"

namespace ocpb {
namespace {

struct SolveArgs {
  CaseSpec spec;
  std::string terminal = "penalty";
  std::string integrator = "euler";
  std::string evaluate_with = "euler";
  std::vector<std::string> options;
  std::string seed = "1";
  std::string json_path;
  bool no_trajectory = false;
};

std::string Fmt(double v) { return std::isfinite(v) ? fmt::format("{:.10g}", v) : "n/a"; }

void PrintReport(const Record& r) {
  std::cout << fmt::format("{} / {}{}: status {} ({})\n",
                           r.problem,
                           r.solver,
                           r.transcription.empty() ? "" : " + " + r.transcription,
                           r.status,
                           r.solver_status);
  std::cout << fmt::format("  J = {}   Jbar = {}   terminal violation = {}\n",
                           Fmt(r.J),
                           Fmt(r.Jbar),
                           Fmt(r.terminal_violation));
  std::cout << fmt::format("  fine RK4: J = {}   Jbar = {}   re-simulation defect = {}\n",
                           Fmt(r.J_fine),
                           Fmt(r.Jbar_fine),
                           Fmt(r.resimulation_defect));
  std::cout << fmt::format("  iterations = {}   CPU = {} s   N = {}   final time = {}\n",
                           r.iterations,
                           Fmt(r.cpu_seconds),
                           r.N,
                           Fmt(r.final_time));
  if (!r.initial_state.empty()) {
    std::cout << "  initial state (chosen) = " << nlohmann::json(r.initial_state).dump() << "\n";
  }
  if (!r.static_parameters.empty()) {
    std::cout << "  static parameters = " << nlohmann::json(r.static_parameters).dump() << "\n";
  }
  if (!r.final_state.empty()) {
    std::cout << "  final state = " << nlohmann::json(r.final_state).dump() << "\n";
  }
  if (r.truth) {
    std::cout << fmt::format(
        "  on the {}: energy = {} (transmission {})   J = {}\n"
        "  path: max distance from S-D = {} m   closest to the base = {} m\n",
        r.truth->model,
        Fmt(r.truth->energy_true),
        Fmt(r.truth->transmit_energy_true),
        Fmt(r.truth->J_true),
        Fmt(r.truth->max_distance_from_segment),
        Fmt(r.truth->min_distance_to_base));
  }
  if (!r.message.empty()) std::cout << "  message: " << r.message << "\n";
  if (r.continuation) {
    std::cout << fmt::format("  continuation: the {} form first: status {} ({}), {} iterations\n",
                             r.continuation->from,
                             r.continuation->status,
                             r.continuation->solver_status,
                             r.continuation->iterations);
  }
  if (r.mesh) {
    std::cout << fmt::format(
        "  mesh refinement: {} ({} meshes)\n", r.mesh->stop_reason, r.mesh->history.size());
    for (const MeshIterationRecord& m : r.mesh->history) {
      std::cout << fmt::format(
          "    N = {:5}  NLP {} x {}  largest estimate {}  {} iterations  CPU {} s  {}\n",
          m.intervals,
          m.nlp_variables,
          m.nlp_constraints,
          Fmt(m.max_error),
          m.iterations,
          Fmt(m.cpu_seconds),
          m.solver_status);
      if (!m.degrees.empty()) {
        const auto [lo, hi] = std::minmax_element(m.degrees.begin(), m.degrees.end());
        int points = 0;
        for (int d : m.degrees) points += d;
        std::cout << fmt::format(
            "              degrees {}..{}, {} collocation points\n", *lo, *hi, points);
      }
    }
  }
  for (const RecordWarning& w : r.warnings) {
    std::cout << "  warning (" << w.code << "): " << w.message << "\n";
  }
}

}  // namespace

void AddSolveCommand(CLI::App& app) {
  auto args = std::make_shared<SolveArgs>();
  CLI::App* cmd = app.add_subcommand("solve", "Solve one problem with one method");
  cmd->add_option("--problem", args->spec.problem, "problem name (ocpbench list problems)")
      ->required();
  cmd->add_option("--solver", args->spec.solver, "solver name (ocpbench list solvers)")->required();
  cmd->add_option("--transcription",
                  args->spec.transcription,
                  "NLP solvers: transcription (ocpbench list transcriptions)");
  cmd->add_option("--algorithm", args->spec.algorithm, "NLopt algorithm (LD_SLSQP, LD_MMA, ...)");
  CLI::Option* n_option =
      cmd->add_option("--N", args->spec.intervals, "grid intervals (default: the problem's)");
  CLI::Option* degree_option =
      cmd->add_option("--degree", args->spec.degree, "LGR collocation degree")
          ->capture_default_str();
  cmd->add_option("--terminal", args->terminal, "terminal constraints: penalty | hard")
      ->capture_default_str();
  cmd->add_option("--integrator", args->integrator, "Hamiltonian descent integrator: euler | rk4")
      ->capture_default_str();
  cmd->add_option("--evaluate-with",
                  args->evaluate_with,
                  "common evaluator's integrator on the method's grid: euler | rk4")
      ->capture_default_str();
  cmd->add_option(
      "--set", args->spec.set, "problem parameter, key=value or key=v1,v2 (repeatable)");
  cmd->add_option("--option", args->options, "solver option, key=value (repeatable)");
  cmd->add_option("--seed", args->seed, "channel realization (0 to 2^64 - 1)")
      ->capture_default_str();
  cmd->add_option("--repeats", args->spec.repeats, "timing repeats (median CPU reported)")
      ->capture_default_str();
  cmd->add_option("--json", args->json_path, "write the JSON record to this file");
  cmd->add_flag("--no-trajectory", args->no_trajectory, "leave t, x, u out of the JSON");
  cmd->add_option("--initial-guess",
                  args->spec.initial_guess,
                  "start from a previous `solve --json` record: its controls (trajectory.u) "
                  "and, for the methods that take them, its own states and costates "
                  "(trajectory.own), sampled onto this grid");
  cmd->add_option("--continuation",
                  args->spec.continuation,
                  "penalty: solve the penalty form first and start the hard form from its "
                  "solution (needs --terminal hard)");
  cmd->callback([args, n_option, degree_option]() {
    CaseSpec spec = args->spec;
    spec.degree_given = degree_option->count() > 0;
    if (n_option->count() > 0 && spec.intervals < 1) {
      throw std::invalid_argument("N: must be >= 1 (or omitted for the problem's default)");
    }
    try {
      spec.terminal = ParseTerminal(args->terminal);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("--") + e.what());
    }
    spec.integrator = ParseFlagIntegrator("--integrator", args->integrator);
    spec.evaluate_with = ParseFlagIntegrator("--evaluate-with", args->evaluate_with);
    spec.seed = ParseSeed(args->seed, "--seed");
    spec.keep_trajectory = !args->no_trajectory;
    spec.options = ParseKeyValues(args->options, "--option");
    if (spec.continuation == "none") spec.continuation.clear();
    // Every input and the output place are checked before anything is solved.
    const ResolvedCase resolved = ResolveAndValidate(spec);
    // No output (--json, a solver's own output file) may be an input or another output.
    FilePlan plan;
    AddCaseFiles(resolved.spec, "", &plan);
    if (!args->json_path.empty()) plan.Output(args->json_path, "--json");
    plan.Check();
    if (!args->json_path.empty()) CheckOutputFile(args->json_path, "--json");
    const Record record = RunCase(resolved);
    PrintReport(record);
    if (!args->json_path.empty()) {
      WriteFileAtomically(args->json_path, record.ToJson().dump(1) + "\n");
    }
    if (IsFailure(record.status)) ReportSomeFailed();
  });
}

}  // namespace ocpb
