#include "bench/cli/run_outputs.h"

#include <nlohmann/json.hpp>

#include "bench/cli/io.h"
#include "bench/cli/summary.h"

namespace ocpb {

Record SummaryPart(Record record) {
  record.trajectory.reset();
  record.costates.reset();
  record.s_map = nullptr;
  if (record.online) {
    record.online->cycles = nlohmann::json::array();
    record.online->executed = nullptr;
    record.online->offline = nullptr;
    record.online->measurements = nullptr;
  }
  return record;
}

void WriteRunSummaries(const std::string& dir,
                       const std::string& suite_name,
                       const std::vector<Record>& records,
                       size_t expected_cases) {
  WriteFileAtomically(dir + "/summary.md", SummaryMarkdown(suite_name, records, expected_cases));
  WriteFileAtomically(dir + "/records.csv", RecordsCsv(records));
  // Derived fields (best_J, time_to_target) for the plotting script; records.jsonl stays raw.
  std::string derived;
  for (const nlohmann::json& j : DerivedRecordsJson(records)) derived += j.dump() + "\n";
  WriteFileAtomically(dir + "/derived.jsonl", derived);
  const nlohmann::json meta{{"suite", suite_name}, {"records", records.size()}};
  WriteFileAtomically(dir + "/suite.json", meta.dump(1) + "\n");
}

}  // namespace ocpb
