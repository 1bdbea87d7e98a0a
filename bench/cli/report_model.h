// What `ocpbench report` shows, as data: a suite's records read (with the checks every input
// gets before any page is written) and turned into the JSON the pages' script draws from. The
// pages themselves are in report_site.h; the numbers come from the same functions as summary.md
// (DeriveTargets) and `ocpbench compare` (Compare), so the site never disagrees with them.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/cli/record.h"

namespace ocpb {

/// One input of `ocpbench report`: a result folder of `run` or `merge` (or a records file).
struct ReportInput {
  std::string path;          ///< as given
  std::string records_path;  ///< the records file read
  std::string suite;         ///< the suite's name (suite.json); the folder's name when absent
  bool suite_named = false;  ///< the name came from suite.json (a records file names none)
  std::vector<Record> records;
  bool dropped_partial = false;      ///< a last line cut short by a killed run was left out
  int shards = 0;                    ///< merged from this many shards (shards.json); 0: one run
  size_t expected_cases = 0;         ///< the sharded suite's case count (shards.json); 0: unknown
  std::string recorded_at;           ///< records file's modification time, UTC ("2026-12-06 14:22")
  std::vector<std::string> figures;  ///< the folder's figures/*.png and *.svg, relative names
};

/// Reads one input. Throws std::invalid_argument with one line naming the path and the rule:
/// no such file or folder, a folder of shards not merged yet, no records.jsonl, no records, a
/// damaged record (FILE:LINE: FIELD: rule), a record without a key or a case recorded twice.
ReportInput LoadReportInput(const std::string& path);

/// The index page's data: {suite, meta, counts, profiles, problems, cases}. `cases` holds one
/// row per record (problem, method, status, warnings, N, tags, J fine, rel. error vs reference,
/// violations, iterations, CPU, time to target, and the page of its problem).
nlohmann::json SuiteIndexData(const ReportInput& input);

/// A problem page's data: the problem's description, references and bounds (from the
/// registry, where it knows the problem), and for each of its records the method, the numbers,
/// the trajectory, costates, convergence history, mesh history and warnings the record keeps.
nlohmann::json ProblemPageData(const ReportInput& input, const std::string& problem);

/// The distinct problems of the records, in order of first appearance.
std::vector<std::string> ReportProblems(const ReportInput& input);

/// The file name of a problem's page: "problem-" and the name with every character outside
/// [A-Za-z0-9_-] replaced by '_' (registry names are already of that form), ".html".
std::string ProblemPageName(const std::string& problem);

}  // namespace ocpb
