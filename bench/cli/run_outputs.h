// What `run` and `merge` write beside a suite's records: summary.md, records.csv, derived.jsonl
// and suite.json (the suite's name and record count).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "bench/cli/record.h"

namespace ocpb {

/// `record` without the parts the tables never read (trajectories, costates, the channel map,
/// the online cycles, paths and measurements): what `run` and `merge` hold of each record
/// once its line is written (EstimateRecordBytes counts this part).
Record SummaryPart(Record record);

/// Writes the tables of `records` into `dir`, each atomically. `expected_cases`, when > 0, is
/// the suite's case count: a summary of fewer records says it covers part of the suite.
void WriteRunSummaries(const std::string& dir,
                       const std::string& suite_name,
                       const std::vector<Record>& records,
                       size_t expected_cases);

}  // namespace ocpb
