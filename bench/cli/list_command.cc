// `ocpbench list` (names, one per line: scripts read it) and `ocpbench describe` (what a
// problem, solver or transcription accepts: every option with its default and rule).
#include <algorithm>
#include <iostream>
#include <memory>

#include <fmt/format.h>
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

std::string JoinTags(const std::vector<std::string>& tags) {
  std::string out;
  for (const std::string& t : tags) out += (out.empty() ? "" : ", ") + t;
  return out;
}

bool HasEveryTag(const ProblemInfo& p, const std::vector<std::string>& tags) {
  for (const std::string& t : tags) {
    if (std::find(p.tags.begin(), p.tags.end(), t) == p.tags.end()) return false;
  }
  return true;
}

void DescribeProblem(const std::string& name) {
  const ProblemInfo& p = FindProblem(name);
  OptionSchema parameters("parameters of " + p.name);
  for (const ParameterSpec& spec : p.parameters) parameters.Add(ToOptionSpec(spec));
  std::cout << "problem " << p.name << ": " << p.description << "\n";
  std::cout << "default grid: N = " << p.default_intervals
            << (p.uses_seed ? "; --seed picks the channel realization" : "") << "\n";
  if (!p.origin.empty()) std::cout << "origin: " << p.origin << "\n";
  std::cout << "tags: " << (p.tags.empty() ? "none" : JoinTags(p.tags)) << "\n";
  const auto print_reference = [](const std::string& quantity,
                                  double value,
                                  const std::string& scheme,
                                  int intervals,
                                  const std::string& source,
                                  const std::vector<std::pair<std::string, std::string>>& options) {
    std::cout << "reference " << quantity << " = " << fmt::format("{:.12g}", value) << " ("
              << (scheme == "continuous" ? scheme
                                         : fmt::format("{} NLP at N = {}", scheme, intervals))
              << "; " << source << ")\n";
    if (options.empty()) return;
    std::string line;
    for (const auto& [key, v] : options) line += (line.empty() ? "" : " ") + key + "=" + v;
    std::cout << "  ipopt options its NLP needs: " << line << "\n";
  };
  if (p.reference_value) {
    print_reference(p.reference_quantity,
                    *p.reference_value,
                    p.reference_scheme,
                    p.reference_intervals,
                    p.reference_source,
                    p.reference_options);
  }
  for (const ProblemReference& r : p.additional_references)
    print_reference(r.quantity, r.value, r.scheme, r.intervals, r.source, r.options);
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
                          " (ipopt and nlopt on a collocation transcription take them, and "
                          "riccati-ip on euler and trapezoid; "
                          "indirect-newton and the Hamiltonian family (forward Euler) a free "
                          "initial state and a free final time where the problem has a "
                          "closed-form Hamiltonian minimizer; methods that do not say "
                          "not_applicable)")
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
  auto tags = std::make_shared<std::vector<std::string>>();
  list->add_option("what", *what, "problems | solvers | transcriptions | tags")
      ->required()
      ->check(CLI::IsMember({"problems", "solvers", "transcriptions", "tags"}));
  list->add_option("--tag",
                   *tags,
                   "with `list problems`: only the problems carrying every tag given (repeatable; "
                   "`ocpbench list tags` lists them)");
  list->callback([what, tags]() {
    if (!tags->empty() && *what != "problems") {
      throw std::invalid_argument("list --tag: filters problems only (got `list " + *what + "`)");
    }
    for (const std::string& tag : *tags) CheckProblemTag("list --tag", tag);
    if (*what == "problems") {
      for (const ProblemInfo& p : Problems()) {
        if (HasEveryTag(p, *tags)) std::cout << p.name << "\n";
      }
    } else if (*what == "tags") {
      // Name, then what it means and how many problems carry it (scripts split on the tab).
      for (const ProblemTag& t : ProblemTags()) {
        int count = 0;
        for (const ProblemInfo& p : Problems()) count += HasEveryTag(p, {t.name}) ? 1 : 0;
        std::cout << t.name << "\t" << t.meaning << " (" << count << " problems)\n";
      }
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
