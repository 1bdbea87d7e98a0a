// Suite files: which problems, seeds, methods and grids `ocpbench run` solves.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/cli/case_runner.h"

namespace ocpb {

/// A parsed suite. The file format (documented with an example in the README):
///
///   { "name": "paper", "description": "...",
///     "groups": [ { "problem": "comm-path2d", "set": {"C": [10, 50, 10]},
///                   "seeds": [1, 2, 3], "N": [400],
///                   <any case field as the group's default: terminal, options, repeats, ...>,
///                   "methods": [ {"solver": "hamiltonian"},
///                                {"solver": "ipopt", "transcription": "euler"} ] } ] }
///
/// Cases are the product seeds x N x methods of every group, in file order. A method's fields
/// override the group's. Every case is validated by ValidateCase (names, parameters, the
/// problem's own rules, the solver's options, memory) before anything runs.
struct Suite {
  std::string name;
  std::string description;
  std::vector<CaseSpec> cases;
  /// The suite as parsed (a sharded run keeps it in its output folder for `merge`).
  nlohmann::json document;
};

/// Parses and validates; throws std::invalid_argument "SUITE: field: rule" on any error.
Suite ParseSuite(const nlohmann::json& j, const std::string& source);
Suite LoadSuite(const std::string& path);

}  // namespace ocpb
