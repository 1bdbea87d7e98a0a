#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>

#include "bench/cli/app.h"
#include "problems/registry.h"
#include "solvers/registry.h"

namespace ocpb {

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
}

}  // namespace ocpb
