// Tables derived from a suite's records: never edited by hand.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/cli/record.h"

namespace ocpb {

/// The fields of the target rule for one record (summary.md states the rule too):
///  - group: problem | seed | parameters | terminal form (cases that solve the same problem);
///  - final_J: the record's J_fine (the common evaluator's RK4 on the 10x finer grid: the one
///    cost that is comparable across methods, whose own objectives use different quadratures and
///    grids), or its J where J_fine is missing; NaN when neither is finite;
///  - best_J: the lowest final_J in the group; in the hard terminal form only records whose
///    status is "converged" count. NaN when no record qualifies;
///  - reached_target: final_J is within 1% of best_J, |final_J - best_J| <= 0.01 |best_J|;
///  - time_to_target: for a record that reached the target, the CPU seconds of its first history
///    entry whose J (the method's own objective) is within 1% of best_J and whose primal_inf,
///    where reported, is <= 1e-6 (in either terminal form), entries of another grid than the
///    request's (IterationRecord::intervals set: a grid-sequenced solve's coarser grids) left
///    out, or the record's total CPU seconds when no entry qualifies; NaN ("never") for a record
///    that did not reach it;
///  - section and method_label: the summary table and the row the record is shown in (the
///    plotting script labels its figures with them).
struct DerivedFields {
  std::string group, section, method_label;
  double final_J = NAN;
  double best_J = NAN;
  bool reached_target = false;
  double time_to_target = NAN;
};

/// The cases that solve the same problem: "problem|seed=S|{parameters}|terminal form".
std::string GroupKey(const Record& r);

/// |the record's value - reference| / |reference|: for a continuous optimum the record's Jbar
/// fine (the continuous-time cost of its controls), for a discrete one (a scheme's NLP at a
/// grid) its own objective, only when the record solved that NLP (same transcription and N,
/// hard terminal form); NaN otherwise or when the reference is 0 or not finite.
double ReferenceError(const Record& r, const RecordReference& ref);

/// The derived fields of every record, in order.
std::vector<DerivedFields> DeriveTargets(const std::vector<Record>& records);

/// derived.jsonl's rows: every record's JSON with its derived fields added (final_J, best_J,
/// reached_target, time_to_target, group, section, method_label; null for NaN), for the
/// plotting scripts. records.jsonl stays raw.
std::vector<nlohmann::json> DerivedRecordsJson(const std::vector<Record>& records);

/// summary.md: one table per problem and setting (the parameters that differ between a problem's
/// records), methods as rows (aggregated over seeds). `expected_cases`, when > 0, is the number
/// of cases of the whole suite: a summary of fewer records says that it covers part of it.
std::string SummaryMarkdown(const std::string& suite_name,
                            const std::vector<Record>& records,
                            size_t expected_cases = 0);
/// records.csv: one row per record, scalar fields and the derived fields.
std::string RecordsCsv(const std::vector<Record>& records);

}  // namespace ocpb
