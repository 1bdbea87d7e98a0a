// `ocpbench list` (names, one per line: scripts read it) and `ocpbench describe` (what a
// problem, solver or transcription accepts: every option with its default and rule).
#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>

#include "bench/cli/app.h"
#include "bench/cli/compare.h"
#include "core/input_file.h"
#include "core/parameters.h"
#include "drivers/online/online_scenario.h"
#include "problems/registry.h"
#include "solvers/registry.h"
#include "solvers/solver.h"

namespace ocpb {
namespace {

void DescribeProblem(const std::string& name) {
  const ProblemInfo& p = FindProblem(name);
  OptionSchema parameters("parameters of " + p.name);
  for (const ParameterSpec& spec : p.parameters) parameters.Add(ToOptionSpec(spec));
  std::cout << "problem " << p.name << ": " << p.description << "\n";
  std::cout << "default grid: N = " << p.default_intervals
            << (p.uses_seed ? "; --seed picks the channel realization" : "") << "\n";
  if (p.reference_value) {
    std::cout << "reference " << p.reference_quantity << " = " << *p.reference_value << " ("
              << p.reference_source << "; " << p.reference_scheme << ")\n";
  }
  if (!p.hamiltonian_note.empty()) std::cout << "hamiltonian: " << p.hamiltonian_note << "\n";
  // The problem as its defaults build it (make_for_checks: without its expensive parts): its
  // sizes and which parts of the problem class it uses, which decide the methods that take it.
  const Parameters defaults(p.parameters);
  const std::unique_ptr<Ocp> ocp =
      p.make_for_checks ? p.make_for_checks(defaults, 1) : p.make(defaults, 1);
  std::cout << "sizes: nx = " << ocp->nx() << ", nu = " << ocp->nu() << ", terminal constraints "
            << ocp->num_terminal() << ", path constraints " << ocp->num_path()
            << ", boundary constraints " << ocp->num_boundary() << ", static parameters "
            << ocp->num_static_parameters() << "\n";
  const ProblemFeatures f = ProblemFeatures::Of(*ocp);
  std::string features;
  const auto add = [&](bool on, const char* what) {
    if (on) features += (features.empty() ? "" : ", ") + std::string(what);
  };
  add(f.free_final_time, "free final time");
  add(f.free_initial_state, "free initial state");
  add(f.state_bounds, "state bounds");
  add(f.boundary_constraints, "boundary constraints");
  std::cout << "features: "
            << (features.empty()
                    ? "none (fixed horizon, fixed x(t0), no state bounds or boundary constraints)"
                    : features +
                          " (ipopt and nlopt on a collocation transcription take them; "
                          "methods that do not say not_applicable)")
            << "\n";
  std::cout << "parameters (--set key=value, suite \"set\"):\n" << parameters.Describe();
}

void DescribeSolver(const std::string& name) {
  const SolverInfo& s = FindSolver(name);
  std::cout << "solver " << s.name << ": " << s.description << "\n";
  std::cout << (s.uses_transcription ? "needs a transcription (--transcription)\n"
                                     : "takes no transcription\n");
  if (!s.accuracy_option.empty()) {
    std::cout << "accuracy: option " << s.accuracy_option << ": " << s.accuracy_note << "\n";
  }
  std::cout << "options (--option key=value, suite \"options\"):\n" << s.options.Describe();
  if (!s.replan_defaults.empty()) {
    std::cout << "re-plan defaults (online re-planning):";
    for (const auto& [k, v] : s.replan_defaults) std::cout << " " << k << "=" << v.ToText();
    std::cout << "\n";
  }
}

void DescribeTranscription(const std::string& name) {
  const TranscriptionInfo& t = FindTranscription(name);
  std::cout << "transcription " << t.name << ": " << t.description << "\n";
  std::cout << "options (--option key=value with an NLP solver; LGR's degree also --degree):\n"
            << t.options.Describe();
}

}  // namespace

void AddListCommand(CLI::App& app) {
  CLI::App* list = app.add_subcommand("list", "List registered names, one per line");
  // The option's storage lives as long as the callback that reads it (the app owns both).
  auto what = std::make_shared<std::string>();
  list->add_option("what", *what, "problems | solvers | transcriptions")
      ->required()
      ->check(CLI::IsMember({"problems", "solvers", "transcriptions"}));
  list->callback([what]() {
    if (*what == "problems") {
      for (const ProblemInfo& p : Problems()) std::cout << p.name << "\n";
    } else if (*what == "solvers") {
      for (const SolverInfo& s : Solvers()) std::cout << s.name << "\n";
    } else {
      for (const TranscriptionInfo& t : Transcriptions()) std::cout << t.name << "\n";
    }
  });

  CLI::App* describe = app.add_subcommand(
      "describe", "Every option of a problem, solver or transcription, with default and rule");
  auto kind = std::make_shared<std::string>();
  auto name = std::make_shared<std::string>();
  describe->add_option("what", *kind, "problem | solver | transcription | online | compare")
      ->required()
      ->check(CLI::IsMember({"problem", "solver", "transcription", "online", "compare"}));
  describe->add_option("name", *name, "its registered name (not for online, compare)");
  describe->callback([kind, name]() {
    if ((*kind == "online" || *kind == "compare") && !name->empty()) {
      throw std::invalid_argument("describe " + *kind + ": takes no name (got '" + OneLine(*name) +
                                  "'): `ocpbench describe " + *kind + "` lists its settings");
    }
    if (*kind == "online") {
      std::cout << "online scenario settings (suite \"online\"; ocpbench online flags):\n"
                << OnlineScenarioSchema().Describe();
      return;
    }
    if (*kind == "compare") {
      std::cout << "thresholds of ocpbench compare (flags --NAME, '_' written '-'):\n"
                << CompareThresholdSchema().Describe();
      return;
    }
    if (name->empty()) throw std::invalid_argument("describe " + *kind + ": a name is required");
    if (*kind == "problem") {
      DescribeProblem(*name);
    } else if (*kind == "solver") {
      DescribeSolver(*name);
    } else {
      DescribeTranscription(*name);
    }
  });
}

}  // namespace ocpb
