// Tables derived from a suite's records: never edited by hand.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace ocpb {

/// Adds to every record, in place:
///  - "group": problem | seed | parameters | terminal form (cases that solve the same problem);
///  - "best_J": the lowest common-evaluator J of any finite record in its group (for the hard
///    form only records with terminal_violation <= 1e-6 qualify);
///  - "time_to_target": the CPU time at which the record's history first came within 1% of
///    best_J (|J - best| <= 0.01 |best|), null when it never did ("infinite").
/// The history holds each method's own objective, which equals the evaluator's J exactly for the
/// Hamiltonian descent and the Euler NLP (same discrete problem), and approximately otherwise.
void DeriveTargets(std::vector<nlohmann::json>* records);

/// summary.md: one table per problem, methods as rows (aggregated over seeds).
std::string SummaryMarkdown(const std::string& suite_name, const std::vector<nlohmann::json>& records);
/// records.csv: one row per record, scalar fields only.
std::string RecordsCsv(const std::vector<nlohmann::json>& records);

}  // namespace ocpb
