// The reports of `ocpbench compare`: Markdown for people (regressions first) and JSON for
// scripts, both from one Comparison (bench/cli/compare.h).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "bench/cli/compare.h"

namespace ocpb {

/// The Markdown report: the two sides and the verdict, regressions (cases, then methods' CPU),
/// cases in one side only, improvements, one row per method and problem, the performance
/// profiles of time to target, every matched case, and how to read it (the rules, the rank test
/// and what the repeats present allow it to say).
std::string CompareMarkdown(const Comparison& comparison);

/// The same as JSON: {"base", "new", "thresholds", "ignore_options", "verdict", "cases",
/// "only_in_base", "only_in_new", "methods", "profiles"}; numbers that were not computed are
/// null. Field names are a contract for scripts (README, "Comparing two runs").
nlohmann::json CompareJson(const Comparison& comparison);

}  // namespace ocpb
