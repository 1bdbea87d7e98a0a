// `ocpbench compare BASE NEW`: two runs of one suite side by side, case by case ("did my change
// make the method better?"). The comparison is a library function with a result struct; the
// Markdown and JSON reports are in compare_report.h, the command in compare_command.cc.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "bench/cli/mann_whitney.h"
#include "bench/cli/record.h"
#include "bench/cli/records_file.h"
#include "core/option_schema.h"
#include "core/option_value.h"

namespace ocpb {

/// When a change counts as a regression, or as an improvement (the same rule the other way).
/// Each is an option of CompareThresholdSchema() (`ocpbench describe compare`; `ocpbench compare
/// --cost X ...`).
struct CompareThresholds {
  /// The cost (a case's final J fine, or its J where J fine is missing: the measure of the
  /// summary's target rule) is worse when it rises by more than this fraction of |base|. In the
  /// hard terminal form costs are compared only when both sides converged (a hard-form result
  /// that did not converge can sit below every feasible cost).
  double cost = 1e-4;
  /// A violation (terminal violation fine, path violation) is worse when it rises by more than
  /// violation_abs and by more than violation_rel times its base value: both, so that changes
  /// far below any feasibility tolerance (1e-12 -> 1e-9) and small relative changes of a
  /// penalty-form miss (0.149 -> 0.150) are not regressions.
  double violation_abs = 1e-6;
  double violation_rel = 0.01;
  /// CPU is worse when the ratio new / base of median CPU times exceeds this and the two-sided
  /// Mann-Whitney U test of the timing repeats rejects "same distribution" at level alpha
  /// (better: below 1 / cpu_ratio, likewise). Per case (its repeats) and per method and problem
  /// (the geometric mean of its cases' ratios; the test stratified over its cases).
  /// 1.5: two identical runs of the paper suite back to back on the shared 2-core machine
  /// (load 10-12) gave per-method ratios 0.87 to 1.22 (README); on a quiet machine 1.1 works.
  double cpu_ratio = 1.5;
  double alpha = 0.05;
};

/// The thresholds' names, defaults and rules (bound to CompareThresholds' fields).
const OptionSchema& CompareThresholdSchema();
/// The defaults with `given` applied; std::invalid_argument "compare option 'NAME': must be
/// RULE (got 'TEXT')" for a bad value, "compare: unknown option ..." for an unknown name.
CompareThresholds ResolveCompareThresholds(const OptionMap& given);

/// One side of a comparison, read: a result folder of `ocpbench run` / `merge` (its
/// records.jsonl, and the suite's name from its suite.json) or a records file.
struct CompareSide {
  std::string path;          ///< as given
  std::string records_path;  ///< the records file read
  std::string suite;         ///< the suite's name; empty when unknown (a records file)
  std::vector<Record> records;
  bool dropped_partial = false;  ///< a last line cut short by a killed run was left out
};

/// Reads one side. Throws std::invalid_argument with one line naming the file (and the line and
/// field where a record is damaged): no such file or folder, a folder without records.jsonl, no
/// records, a record without a key, a case recorded twice, a damaged suite.json.
CompareSide LoadCompareSide(const std::string& path);
/// The second half of LoadCompareSide: `side` (its path, records_path and suite set) with the
/// records of `file`, checked the same way (the fuzzer, tests).
CompareSide CompareSideOfRecords(CompareSide side, RecordFile file);

/// What is compared, and by which rules.
struct CompareOptions {
  CompareThresholds thresholds;
  /// Options whose values may differ between matched cases: keys are matched with these
  /// options left out (an A/B test of one option: `--ignore-option max_iterations`).
  std::vector<std::string> ignore_options;
};

/// A measure of a case or of a method that moved beyond its threshold.
struct Finding {
  std::string measure;  ///< "status", "cost", "terminal viol. fine", "path viol.", "CPU"
  bool worse = true;    ///< a regression; false: an improvement
  std::string detail;   ///< "converged -> max_iterations", "+2.8e+01 (5.96 -> 167)", ...
};

/// One side's numbers of a matched case.
struct CaseSide {
  std::string status, solver_status;
  double cost = NAN;  ///< final J fine (J where J fine is missing)
  double Jbar_fine = NAN;
  double terminal_violation = NAN;  ///< fine (the method-grid value where fine is missing)
  double path_violation = NAN;
  int iterations = -1;
  double cpu_seconds = NAN;         ///< the record's median over its repeats
  std::vector<double> cpu_repeats;  ///< per-repeat CPU seconds
  double time_to_target = NAN;      ///< against the common target; NaN: never reached
  std::map<std::string, std::string> ignored_options;  ///< the ignored options' values
  std::string commit;
};

/// A case present on both sides.
struct CaseComparison {
  std::string key;                     ///< the matching key (ignored options left out)
  std::string section, method, group;  ///< summary table, row, target group (BASE's)
  std::uint64_t seed = 0;
  std::string kind, terminal;  ///< BASE's
  CaseSide base, next;
  double cost_change = NAN;       ///< relative: (new - base) / |base|
  double Jbar_fine_change = NAN;  ///< relative
  double terminal_violation_change = NAN, path_violation_change = NAN;  ///< new - base
  double cpu_ratio = NAN;  ///< new / base median CPU seconds
  RankTestResult cpu_test;
  std::vector<Finding> findings;

  bool Regressed() const;  ///< some finding is worse
  bool Improved() const;   ///< some finding is better and none is worse
};

/// A case present on one side only.
struct UnmatchedCase {
  std::string key, section, method, status;
};

/// The cases of one summary row (problem and setting, method), aggregated.
struct MethodComparison {
  std::string section, method;
  int cases = 0, regressed = 0, improved = 0;
  std::map<std::string, int> status_changes;  ///< "converged -> max_iterations" -> cases
  /// Relative changes over the cases: median, min, max (NaN where no case has both values).
  double cost_change_median = NAN, cost_change_min = NAN, cost_change_max = NAN;
  double Jbar_fine_change_median = NAN, Jbar_fine_change_min = NAN, Jbar_fine_change_max = NAN;
  /// The worst case of each side.
  double terminal_violation_base = NAN, terminal_violation_new = NAN;
  double path_violation_base = NAN, path_violation_new = NAN;
  double iterations_base = NAN, iterations_new = NAN;  ///< medians
  double cpu_ratio = NAN;                              ///< geometric mean of the cases' ratios
  RankTestResult cpu_test;                             ///< stratified over the cases
  /// Medians over the cases that reached the target, and how many did.
  double time_to_target_base = NAN, time_to_target_new = NAN;
  int reached_base = 0, reached_new = 0;
  std::vector<Finding> findings;  ///< the aggregate CPU verdict
};

/// The taus at which performance profiles are reported; infinity: the fraction ever solved.
inline constexpr std::array<double, 5> kProfileTaus = {
    1.0, 2.0, 4.0, 10.0, std::numeric_limits<double>::infinity()};

/// One method's Dolan-More profile of CPU time to target, BASE and NEW: every (method, side) is
/// one solver of a single profile over the matched cases' target groups, so both sides are
/// measured against the same best time.
struct ProfileComparison {
  std::string method;
  int instances = 0;
  std::array<double, kProfileTaus.size()> base{}, next{};  ///< rho(tau) at kProfileTaus
};

/// Everything `ocpbench compare` reports.
struct Comparison {
  CompareOptions options;
  std::string base_path, new_path, base_suite, new_suite;
  size_t base_records = 0, new_records = 0;
  std::vector<std::string> base_commits, new_commits;  ///< distinct, in order of appearance
  bool base_dropped_partial = false, new_dropped_partial = false;
  std::vector<CaseComparison> cases;  ///< matched cases, in BASE's order
  std::vector<UnmatchedCase> only_in_base, only_in_new;
  std::vector<MethodComparison> methods;  ///< in BASE's order of first appearance
  std::vector<ProfileComparison> profiles;
  /// The geometric mean of every matched case's CPU ratio: a shift that every method shares
  /// usually comes from the machine (its load, its clock), not from the code.
  double overall_cpu_ratio = NAN;

  int RegressedCases() const;
  int ImprovedCases() const;
  int RegressedMethods() const;  ///< methods with an aggregate (CPU) regression
  /// A regression beyond the thresholds: a case or a method regressed, or a case of BASE is
  /// missing from NEW (its result is unknown). `ocpbench compare` exits 1 then.
  bool HasRegression() const;
};

/// Compares two sides case by case (matched by Record::key, without the ignored options).
/// Throws std::invalid_argument (one line) when they are not two runs of one suite (different
/// suite names, or no case in common), when an ignored option is set by no case, or when two
/// cases of one side differ only in the ignored options.
Comparison Compare(const CompareSide& base, const CompareSide& next, const CompareOptions& options);

/// "converged", "acceptable", limits (max_iterations, max_time, step_too_small,
/// roundoff_limited and any status that is neither a success nor a failure), "not_applicable",
/// failures (bench/cli/case_runner.h IsFailure): 0 to 4, higher is worse. A change to a higher
/// tier is a regression whatever the cost; within a tier it is reported, not judged.
int StatusTier(const std::string& status);

}  // namespace ocpb
