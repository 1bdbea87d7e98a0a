// `ocpbench run SUITE.json`: a suite's cases (or one shard of them) in one process or in N
// worker processes, appending one record per case.
#include <filesystem>
#include <iostream>
#include <memory>
#include <set>
#include <unordered_map>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "bench/cli/app.h"
#include "bench/cli/case_runner.h"
#include "bench/cli/io.h"
#include "bench/cli/output_place.h"
#include "bench/cli/progress.h"
#include "bench/cli/records_file.h"
#include "bench/cli/run_outputs.h"
#include "bench/cli/shard.h"
#include "bench/cli/shard_manifest.h"
#include "bench/cli/suite.h"
#include "bench/cli/worker_pool.h"
#include "core/input_file.h"

namespace ocpb {
namespace {

namespace fs = std::filesystem;

/// The most worker processes `--jobs` takes (a typo such as 1000 should not fork a thousand).
constexpr int kMaxJobs = 256;

struct RunArgs {
  std::string suite_path;
  std::string out;
  std::string shard;
  bool shard_given = false;  ///< --shard was given (an empty value is refused, not ignored)
  std::string jobs = "1";
  bool resume = false;
  bool overwrite = false;
  bool check = false;
};

std::string MethodLabel(const CaseSpec& spec) {
  return spec.problem + " / " + spec.solver +
         (spec.transcription.empty() ? "" : " + " + spec.transcription);
}

// Each case's position in the suite, by key.
std::unordered_map<std::string, size_t> SuitePositions(const Suite& suite) {
  std::unordered_map<std::string, size_t> position;
  for (size_t i = 0; i < suite.cases.size(); ++i) position.emplace(suite.cases[i].Key(), i);
  return position;
}

// The suite position of a key; keys that are no case of the suite come after all cases.
size_t PositionOf(const std::unordered_map<std::string, size_t>& position, const std::string& key) {
  const auto it = position.find(key);
  return it == position.end() ? position.size() : it->second;
}

// Rewrites the records file in the suite's case order when it is not (worker processes finish
// in any order; a resumed run appends after what was there). Lines are kept verbatim; records of
// keys that are no case of the suite stay, after the others. One atomic rename.
void PutInSuiteOrder(const std::string& path,
                     const std::unordered_map<std::string, size_t>& position) {
  RecordFile file = ReadRecords(path);
  std::vector<std::pair<size_t, size_t>> order;  // (suite position, line)
  for (size_t i = 0; i < file.records.size(); ++i) {
    order.emplace_back(PositionOf(position, file.records[i].key), i);
  }
  if (std::is_sorted(order.begin(), order.end())) return;
  std::stable_sort(
      order.begin(), order.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<std::string> lines;
  for (const auto& [pos, line] : order) lines.push_back(std::move(file.lines[line]));
  WriteFileAtomically(path, JoinLines(lines));
}

// `--jobs N`: decimal digits only, 1 to kMaxJobs.
int ParseJobs(const std::string& text) {
  const std::string rule =
      fmt::format("must be an integer from 1 to {} (worker processes)", kMaxJobs);
  if (text.empty() || text.size() > 9 ||
      text.find_first_not_of("0123456789") != std::string::npos) {
    throw std::invalid_argument("--jobs '" + OneLine(text) + "': " + rule);
  }
  const int jobs = std::stoi(text);
  if (jobs < 1 || jobs > kMaxJobs)
    throw std::invalid_argument(fmt::format("--jobs {}: {}", jobs, rule));
  return jobs;
}

void Run(const RunArgs& args) {
  // ---- every check before anything is written ----------------------------------------------
  const Suite suite = LoadSuite(args.suite_path);
  const std::string dir = args.out.empty() ? "results/" + suite.name : args.out;
  const std::optional<Shard> shard = args.shard_given || !args.shard.empty()
                                         ? std::optional<Shard>(ParseShard(args.shard))
                                         : std::nullopt;
  if (args.resume && args.overwrite)
    throw std::invalid_argument("--resume and --overwrite exclude each other");
  const int jobs_wanted = ParseJobs(args.jobs);
  const std::string records_path =
      dir + "/" + (shard ? shard->RecordsFileName() : std::string("records.jsonl"));
  // Every file the run reads or writes, checked against each other (FilePlan) before anything
  // else is looked at in the folder.
  FilePlan plan;
  plan.Input(args.suite_path, "the suite file");
  for (size_t i = 0; i < suite.cases.size(); ++i) {
    if (!shard || shard->Owns(i))
      AddCaseFiles(suite.cases[i], fmt::format("case {}", i + 1), &plan);
  }
  {
    FilePlan checked = plan;
    PlanRunFolder(dir, records_path, shard ? shard->count : 1, &checked);
  }
  if (shard) CheckShardManifest(dir, suite, shard->count);
  if (args.check) {
    std::cerr << fmt::format(
        "ocpbench: suite {} checked: {} cases{}; nothing run\n",
        suite.name,
        suite.cases.size(),
        shard ? fmt::format(", {} in shard {}", shard->CaseCount(suite.cases.size()), shard->Text())
              : "");
    return;
  }
  // Before any work: the folder and its files are usable, and this run is their only writer.
  const OutputFolderLock lock = ClaimRunFolder(
      dir, records_path, shard ? shard->index : 0, shard ? shard->count : 1, std::move(plan));

  std::set<std::string> done;
  std::vector<Record> records;
  RecordFile previous;
  const bool has_records = fs::exists(records_path) && fs::file_size(records_path) > 0;
  if (has_records && !args.overwrite) {
    if (!args.resume) {
      throw std::invalid_argument(records_path +
                                  " exists: pass --resume to continue it or --overwrite to " +
                                  "start over (the old file is kept as .prev)");
    }
    previous = ReadRecords(records_path);
    // A record of a case this run does not hold means the folder belongs to another suite (or
    // another shard): resuming would mix the two in one records file and one summary.
    std::set<std::string> mine;
    for (size_t i = 0; i < suite.cases.size(); ++i) {
      if (!shard || shard->Owns(i)) mine.insert(suite.cases[i].Key());
    }
    for (size_t i = 0; i < previous.records.size(); ++i) {
      if (mine.count(previous.records[i].key)) continue;
      throw std::invalid_argument(fmt::format(
          "{}: record {} (case {}) is not a case of suite '{}'{}: --resume continues a folder "
          "with the suite that wrote it (use another --out, or --overwrite)",
          records_path,
          i + 1,
          previous.records[i].key,
          suite.name,
          shard ? " in shard " + shard->Text() : ""));
    }
  }

  // ---- writes ------------------------------------------------------------------------------
  if (has_records && args.overwrite) {
    // Each earlier version stays (.prev the latest, .1.prev, .2.prev, ... the older ones).
    std::cerr << "ocpbench: previous records kept as " << KeepPreviousVersion(records_path) << "\n";
  }
  if (previous.dropped_partial) {
    std::cerr << "ocpbench: dropped a partial last record in " << records_path
              << " (its case runs again)\n";
  }
  const int duplicates = previous.DropDuplicateKeys();
  if (duplicates > 0) {
    std::cerr << "ocpbench: dropped " << duplicates << " duplicate records in " << records_path
              << " (a case recorded again; the first record of each case stays)\n";
  }
  if (previous.dropped_partial || previous.unterminated || duplicates > 0) {
    WriteFileAtomically(records_path, JoinLines(previous.lines));
  }
  for (Record& r : previous.records) records.push_back(SummaryPart(std::move(r)));
  for (const Record& r : records) done.insert(r.key);
  if (shard) WriteShardManifestIfAbsent(dir, suite, args.suite_path, shard->count);

  std::vector<const CaseSpec*> todo;
  size_t total_in_shard = 0;
  for (size_t i = 0; i < suite.cases.size(); ++i) {
    if (shard && !shard->Owns(i)) continue;
    ++total_in_shard;
    if (!done.count(suite.cases[i].Key())) todo.push_back(&suite.cases[i]);
  }
  if (!done.empty()) {
    std::cerr << fmt::format("ocpbench: resuming: {} of {} cases already recorded\n",
                             total_in_shard - todo.size(),
                             total_in_shard);
  }

  const int jobs = std::min<int>(jobs_wanted, std::max<size_t>(todo.size(), 1));
  RunProgress progress(todo.size(), jobs, shard ? "shard " + shard->Text() + ": " : "");
  int failed = 0;
  // Every finished case, whichever process ran it, is appended here (this process is the file's
  // only writer) and flushed to disk before the next one is taken.
  auto record_done = [&](size_t task, Record record, const std::string& line, size_t running) {
    if (IsFailure(record.status)) ++failed;
    AppendLineDurably(records_path, line);
    records.push_back(SummaryPart(std::move(record)));
    progress.CaseDone(running, MethodLabel(*todo[task]));
  };
  if (jobs == 1) {
    for (size_t i = 0; i < todo.size(); ++i) {
      // One case never stops the suite: whatever it throws becomes its record.
      Record record = RunCaseRecordingFailures(*todo[i]);
      const std::string line = record.ToJson().dump();
      record_done(i, std::move(record), line, i + 1 < todo.size() ? 1 : 0);
    }
  } else {
    WorkerPoolTasks tasks;
    tasks.count = todo.size();
    tasks.run = [&](size_t i) { return RunCaseRecordingFailures(*todo[i]).ToJson().dump(); };
    tasks.died = [&](size_t i, const std::string& why) {
      Record rec = CaseIdentityRecord(*todo[i]);
      rec.status = ToString(SolveStatus::kError);
      rec.solver_status = "worker_died";
      rec.message = "the worker process running this case ended: " + why;
      return rec.ToJson().dump();
    };
    tasks.done = [&](size_t i, std::string line, size_t running) {
      Record record = Record::FromJson(nlohmann::json::parse(line));
      record_done(i, std::move(record), line, running);
    };
    tasks.idle = [&](size_t running) { progress.Tick(running); };
    RunInWorkerProcesses(tasks, jobs);
  }
  progress.Finish();
  const auto position = SuitePositions(suite);
  if (!todo.empty()) PutInSuiteOrder(records_path, position);
  std::stable_sort(records.begin(), records.end(), [&](const Record& a, const Record& b) {
    return PositionOf(position, a.key) < PositionOf(position, b.key);
  });
  std::cerr << fmt::format("ocpbench: {} cases run in {}, {} failed; records in {}\n",
                           todo.size(),
                           ClockText(progress.Elapsed()),
                           failed,
                           records_path);
  if (!shard) {
    WriteRunSummaries(dir, suite.name, records, suite.cases.size());
    std::cerr << "ocpbench: summary in " << dir << "/summary.md\n";
  } else {
    std::cerr << "ocpbench: shard " << shard->Text()
              << " done; join the shards with `ocpbench merge " << dir << "`\n";
  }
  if (failed > 0) ReportSomeFailed();
}

}  // namespace

void AddRunCommand(CLI::App& app) {
  auto args = std::make_shared<RunArgs>();
  CLI::App* run =
      app.add_subcommand("run", "Run a benchmark suite (JSON), appending one record per case");
  run->add_option("suite", args->suite_path, "suite file (JSON)")->required();
  run->add_option("--out", args->out, "output directory (default results/<suite name>)");
  run->add_flag("--resume", args->resume, "skip cases already in the records file");
  run->add_flag(
      "--overwrite", args->overwrite, "start over; the old records file is kept as .prev");
  CLI::Option* shard_option =
      run->add_option("--shard",
                      args->shard,
                      "run only shard i of n (1 <= i <= n): the suite's cases i, i+n, i+2n, ... "
                      "into records.shard-i-of-n.jsonl; join them with `ocpbench merge`");
  run->add_option("--jobs",
                  args->jobs,
                  "worker processes running cases at once (default 1); each case's CPU time "
                  "stays its own, records come out in the suite's order");
  run->add_flag("--check",
                args->check,
                "check the suite (every case) and the output folder's shard rules; run and "
                "write nothing");
  run->callback([args, shard_option]() {
    args->shard_given = shard_option->count() > 0;
    Run(*args);
  });
}

}  // namespace ocpb
