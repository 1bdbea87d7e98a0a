// Suite files: which problems, seeds, methods and grids `ocpbench run` solves.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/cli/case_runner.h"
#include "bench/cli/json_input.h"

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

/// The most cases one suite file may expand to (seeds x N x methods over its groups), counted
/// before any case is built; `ocpbench run` also refuses a suite whose records, held for its
/// summary, would not fit in memory (EstimateRecordBytes).
inline constexpr long kMaxSuiteCases = 1000000;

/// Parses and validates; throws std::invalid_argument "SUITE: field: rule" on any error. The
/// cases read their fields in place (CaseFields): nothing of the document is copied. A null
/// value is refused wherever it stands (a key is omitted to take its default).
/// With `lines` (the document's JsonLines), each error names the line of the value it is
/// about: "SUITE:LINE: groups[0].methods[1].seed: rule".
Suite ParseSuite(const nlohmann::json& j,
                 const std::string& source,
                 const JsonLines* lines = nullptr);
/// Reads (at most kMaxSuiteFileBytes, nesting at most kMaxJsonDepth: bench/cli/json_input.h),
/// parses and validates a suite file; every error is an std::invalid_argument naming the file.
Suite LoadSuite(const std::string& path);

}  // namespace ocpb
