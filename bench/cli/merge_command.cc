// `ocpbench merge DIR` (join the shards of a suite into one records file and its tables) and
// `ocpbench status DIR` (how far the shards are): both know the suite (shards.json, written by
// `run --shard`, or --suite) and report missing shards and missing or duplicated cases by key.
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <unordered_map>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "bench/cli/app.h"
#include "bench/cli/case_runner.h"
#include "bench/cli/io.h"
#include "bench/cli/output_place.h"
#include "bench/cli/records_file.h"
#include "bench/cli/run_outputs.h"
#include "bench/cli/shard.h"
#include "bench/cli/shard_coverage.h"
#include "bench/cli/shard_manifest.h"
#include "bench/cli/suite.h"
#include "core/input_file.h"

namespace ocpb {
namespace {

namespace fs = std::filesystem;

/// Keys of each kind listed by merge and status before "... and K more".
constexpr size_t kListedKeys = 20;

struct MergeArgs {
  std::string dir;
  std::string suite_path;  ///< empty: the suite in DIR/shards.json
  std::string name;        ///< empty: the suite's name
};

/// A sharded output folder: its suite, shard count and the shards' records files.
struct Sweep {
  Suite suite;
  int shards = 0;
  std::map<int, std::string> files;  ///< shard number -> records file
};

Sweep ReadSweep(const std::string& command, const MergeArgs& args) {
  // A folder given by a loop of links (or an over-long path) is refused as such, before any
  // other test of it.
  FilePlan().Input(args.dir, command);
  if (!args.suite_path.empty()) FilePlan().Input(args.suite_path, "--suite");
  if (!fs::is_directory(args.dir)) {
    throw std::invalid_argument(command + ": no such directory " + args.dir);
  }
  const std::optional<ShardManifest> manifest = ReadShardManifest(args.dir);
  Sweep sweep;
  if (!args.suite_path.empty()) {
    sweep.suite = LoadSuite(args.suite_path);
    // A --suite that is not the one the shards ran would merge nothing of theirs and replace
    // the merged records: refused, as `run --shard` refuses it.
    if (manifest) CheckShardManifest(args.dir, sweep.suite, manifest->shards);
  } else if (manifest) {
    sweep.suite = ParseSuite(manifest->suite, ShardManifestPath(args.dir) + ": suite");
  } else {
    throw std::invalid_argument(fmt::format(
        "{}: {} has no shards.json (written by `ocpbench run --shard`): pass --suite SUITE.json",
        command,
        args.dir));
  }
  std::map<int, std::string> by_count;  // a file of each shard count found
  for (const auto& e : fs::directory_iterator(args.dir)) {
    const std::string name = e.path().filename().string();
    const std::optional<Shard> shard = ShardOfRecordsFileName(name);  // throws for 0-based names
    if (!shard) continue;
    by_count.emplace(shard->count, name);
    sweep.files[shard->index] = e.path().string();
    sweep.shards = shard->count;
  }
  if (manifest) sweep.shards = manifest->shards;
  for (const auto& [count, name] : by_count) {
    if (count != sweep.shards) {
      throw std::invalid_argument(fmt::format(
          "{}: {} holds shards of {} counts ({} and a sweep of {} shards){}: keep one sweep per "
          "folder",
          command,
          args.dir,
          by_count.size() > 1 ? "different" : "another",
          name,
          sweep.shards,
          manifest ? " in shards.json" : ""));
    }
  }
  if (sweep.files.empty()) {
    throw std::invalid_argument(
        fmt::format("{}: no records.shard-*.jsonl files in {}", command, args.dir));
  }
  return sweep;
}

std::vector<std::string> SuiteKeys(const Suite& suite) {
  std::vector<std::string> keys;
  for (const CaseSpec& c : suite.cases) keys.push_back(c.Key());
  return keys;
}

void PrintCoverage(const std::string& command, const ShardCoverage& coverage) {
  for (const std::string& line : DescribeShardCoverage(coverage, kListedKeys)) {
    std::cerr << "ocpbench: " << command << ": " << line << "\n";
  }
}

void Merge(const MergeArgs& args) {
  const Sweep sweep = ReadSweep("merge", args);
  // The folder's exclusive lock before anything is written (no shard may still be running
  // there); after the sweep is read, so that a refused merge leaves no lock file behind.
  // Every file merge reads (the shards, shards.json, --suite) may not be one it writes.
  FilePlan plan;
  if (!args.suite_path.empty()) plan.Input(args.suite_path, "--suite");
  const std::string manifest = ShardManifestPath(args.dir);
  if (fs::exists(manifest)) plan.Input(manifest, "the shard manifest");
  for (const auto& [index, path] : sweep.files) {
    plan.Input(path, fmt::format("the records of shard {}", index));
  }
  const OutputFolderLock lock = ClaimMergeFolder(args.dir, std::move(plan));
  const std::vector<std::string> suite_keys = SuiteKeys(sweep.suite);
  std::unordered_map<std::string, size_t> position;
  for (size_t i = 0; i < suite_keys.size(); ++i) position.emplace(suite_keys[i], i);

  // Read everything before writing anything: a damaged file stops the merge with nothing changed.
  std::map<int, std::vector<std::string>> keys_by_shard;
  std::vector<std::optional<std::pair<Record, std::string>>> merged(suite_keys.size());
  for (const auto& [index, path] : sweep.files) {
    RecordFile file = ReadRecords(path);
    if (file.dropped_partial) {
      std::cerr << "ocpbench: merge: ignored a partial last record in " << path
                << " (a shard still running or killed)\n";
    }
    std::vector<std::string>& keys = keys_by_shard[index];
    for (size_t i = 0; i < file.records.size(); ++i) {
      keys.push_back(file.records[i].key);
      const auto it = position.find(file.records[i].key);
      // The first record of a case is kept; duplicates and strangers are reported below.
      if (it != position.end() && !merged[it->second]) {
        merged[it->second].emplace(SummaryPart(std::move(file.records[i])),
                                   std::move(file.lines[i]));
      }
    }
  }
  const ShardCoverage coverage = ComputeShardCoverage(suite_keys, sweep.shards, keys_by_shard);

  std::vector<Record> records;
  std::vector<std::string> lines;
  bool some_failed = false;
  for (auto& m : merged) {
    if (!m) continue;
    some_failed = some_failed || IsFailure(m->first.status);
    records.push_back(std::move(m->first));
    lines.push_back(std::move(m->second));
  }
  const std::string records_path = args.dir + "/records.jsonl";
  const std::string text = JoinLines(lines);
  // Every earlier version stays (records.jsonl.prev the latest, records.jsonl.1.prev, .2.prev,
  // ... the older ones): records a resumed unsharded run appended there are never lost. A merge
  // that changes nothing keeps no copy.
  std::error_code ec;
  const bool unchanged = fs::file_size(records_path, ec) == text.size() && !ec &&
                         ReadInputFile(records_path, text.size(), "records file") == text;
  if (fs::exists(records_path) && !unchanged) {
    std::cerr << "ocpbench: merge: previous records kept as " << KeepPreviousVersion(records_path)
              << "\n";
  }
  WriteFileAtomically(records_path, text);
  WriteRunSummaries(args.dir,
                    args.name.empty() ? sweep.suite.name : args.name,
                    records,
                    sweep.suite.cases.size());
  std::cerr << fmt::format("ocpbench: merged {} records from {} of {} shards into {}\n",
                           records.size(),
                           sweep.files.size(),
                           sweep.shards,
                           records_path);
  PrintCoverage("merge", coverage);
  if (!coverage.Complete()) ReportIncomplete();
  if (some_failed) ReportSomeFailed();
}

void Status(const MergeArgs& args) {
  const Sweep sweep = ReadSweep("status", args);
  std::map<int, std::vector<std::string>> keys_by_shard;
  for (const auto& [index, path] : sweep.files) {
    // A shard still running may have half a record at the end: ReadRecords leaves it out.
    for (Record& r : ReadRecords(path).records) keys_by_shard[index].push_back(std::move(r.key));
  }
  const ShardCoverage coverage =
      ComputeShardCoverage(SuiteKeys(sweep.suite), sweep.shards, keys_by_shard);
  std::cout << fmt::format(
      "suite {}: {} cases in {} shards\n", sweep.suite.name, coverage.expected, coverage.shards);
  for (const ShardProgress& p : coverage.progress) {
    std::cout << fmt::format("shard {} of {}: {} of {} cases recorded{}\n",
                             p.index,
                             coverage.shards,
                             p.recorded,
                             p.expected,
                             p.file_present ? "" : " (no records file yet)");
  }
  PrintCoverage("status", coverage);
  if (!coverage.Complete()) ReportIncomplete();
}

void AddSweepOptions(CLI::App* command, const std::shared_ptr<MergeArgs>& args) {
  command->add_option("dir", args->dir, "output directory of the shards")->required();
  command->add_option("--suite",
                      args->suite_path,
                      "the suite file the shards ran (default: the one `run --shard` recorded "
                      "in DIR/shards.json)");
}

}  // namespace

void AddMergeCommand(CLI::App& app) {
  auto args = std::make_shared<MergeArgs>();
  CLI::App* merge = app.add_subcommand(
      "merge", "Join the shard records of a suite directory; report missing and duplicated cases");
  AddSweepOptions(merge, args);
  merge->add_option("--name", args->name, "suite name for the summary (default: the suite's)");
  merge->callback([args]() { Merge(*args); });

  auto status_args = std::make_shared<MergeArgs>();
  CLI::App* status = app.add_subcommand(
      "status", "How many of a suite's cases each shard has recorded (while it runs, or after)");
  AddSweepOptions(status, status_args);
  status->callback([status_args]() { Status(*status_args); });
}

}  // namespace ocpb
