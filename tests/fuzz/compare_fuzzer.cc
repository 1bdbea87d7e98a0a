// libFuzzer target: compare's and merge's readers past the records loader (records_fuzzer.cc).
// The input is two records files, BASE and NEW, split at the first form feed ('\f'; all of it
// is BASE and NEW when there is none). Every input must end in a comparison whose reports
// (Markdown and JSON) are written, or in a std::invalid_argument naming the file: never a
// crash, a hang or another exception. The same records, as shards of one sweep, go through
// merge's coverage count and its report.
#include <cstddef>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/cli/compare.h"
#include "bench/cli/compare_report.h"
#include "bench/cli/records_file.h"
#include "bench/cli/shard_coverage.h"

namespace {

// Merge's view: BASE's keys are the suite, NEW's records the shards' (round robin over a shard
// count taken from the input's size).
void MergeCoverage(const ocpb::RecordFile& suite, const ocpb::RecordFile& shards, size_t size) {
  std::vector<std::string> keys;
  for (const ocpb::Record& r : suite.records) keys.push_back(r.key);
  const int count = 1 + static_cast<int>(size % 7);
  std::map<int, std::vector<std::string>> by_shard;
  for (size_t i = 0; i < shards.records.size(); ++i) {
    by_shard[1 + static_cast<int>(i % static_cast<size_t>(count))].push_back(shards.records[i].key);
  }
  const ocpb::ShardCoverage coverage = ocpb::ComputeShardCoverage(keys, count, by_shard);
  (void)ocpb::DescribeShardCoverage(coverage, 20);
  (void)coverage.Complete();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const size_t split = text.find('\f');
  const std::string_view base_text = split == std::string_view::npos ? text : text.substr(0, split);
  const std::string_view next_text =
      split == std::string_view::npos ? text : text.substr(split + 1);
  ocpb::RecordFile base_file, next_file;
  try {
    base_file = ocpb::ParseRecords(base_text, "base");
    next_file = ocpb::ParseRecords(next_text, "new");
  } catch (const std::invalid_argument&) {
    return 0;
  }
  MergeCoverage(base_file, next_file, size);
  try {
    ocpb::CompareSide base, next;
    base.path = base.records_path = "base";
    next.path = next.records_path = "new";
    base = ocpb::CompareSideOfRecords(std::move(base), std::move(base_file));
    next = ocpb::CompareSideOfRecords(std::move(next), std::move(next_file));
    ocpb::CompareOptions options;
    const ocpb::Comparison comparison = ocpb::Compare(base, next, options);
    (void)ocpb::CompareMarkdown(comparison);
    (void)ocpb::CompareJson(comparison).dump();
  } catch (const std::invalid_argument&) {
    return 0;
  }
  return 0;
}
