// The problems OCPBench knows by name.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/ocp.h"
#include "core/parameters.h"

namespace ocpb {

/// A registered problem: how to build it, its parameters, and what is known about its optimum.
struct ProblemInfo {
  std::string name;
  std::string description;
  std::vector<ParameterSpec> parameters;
  /// Builds the problem. `seed` picks any random ingredient (a channel realization); problems
  /// without randomness ignore it.
  std::function<std::unique_ptr<Ocp>(const Parameters& params, std::uint64_t seed)> make;
  int default_intervals = 100;           ///< the grid a suite uses when it names none
  std::optional<double> reference_value; ///< published optimum of the cost below, if known
  std::string reference_quantity = "J";  ///< "J" (hard terminal form) or "tf" etc.
  std::string reference_source;          ///< where the reference value comes from
  bool uses_seed = false;                ///< true when `seed` changes the problem
};

/// Every registered problem, in a fixed order.
const std::vector<ProblemInfo>& Problems();
/// The problem called `name`; throws std::invalid_argument listing the valid names.
const ProblemInfo& FindProblem(const std::string& name);
/// Builds `name` with `assignments` ("key=value") applied over the defaults.
std::unique_ptr<Ocp> MakeProblem(const std::string& name, const std::vector<std::string>& assignments,
                                 std::uint64_t seed, Parameters* resolved = nullptr);

}  // namespace ocpb
