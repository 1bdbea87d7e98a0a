// Tables derived from a suite's records: never edited by hand.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace ocpb {

/// Adds to every record, in place, the fields of the target rule (summary.md states it too):
///  - "group": problem | seed | parameters | terminal form (cases that solve the same problem);
///  - "final_J": the record's J_fine (the common evaluator's RK4 on the 10x finer grid: the one
///    cost that is comparable across methods, whose own objectives use different quadratures and
///    grids), or its J where J_fine is missing; null when neither is finite;
///  - "best_J": the lowest final_J in the group; in the hard terminal form only records whose
///    status is "converged" count. Null when no record qualifies;
///  - "reached_target": final_J is within 1% of best_J, |final_J - best_J| <= 0.01 |best_J|;
///  - "time_to_target": for a record that reached the target, the CPU seconds of its first history
///    entry whose J (the method's own objective) is within 1% of best_J and whose primal_inf,
///    where reported, is <= 1e-6 (in either terminal form), or the record's total CPU seconds when
///    no entry qualifies; null ("never", infinite) for a record that did not reach it;
///  - "section" and "method_label": the summary table and the row the record is shown in (the
///    plotting script labels its figures with them).
void DeriveTargets(std::vector<nlohmann::json>* records);

/// summary.md: one table per problem and setting (the parameters that differ between a problem's
/// records), methods as rows (aggregated over seeds). Expects records passed through
/// DeriveTargets.
std::string SummaryMarkdown(const std::string& suite_name,
                            const std::vector<nlohmann::json>& records);
/// records.csv: one row per record, scalar fields only.
std::string RecordsCsv(const std::vector<nlohmann::json>& records);

}  // namespace ocpb
