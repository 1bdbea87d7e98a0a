// `ocpbench run SUITE.json` and `ocpbench merge DIR`: suites, records, summaries.
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "bench/cli/app.h"
#include "bench/cli/case_runner.h"
#include "bench/cli/io.h"
#include "bench/cli/suite.h"
#include "bench/cli/summary.h"

namespace ocpb {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct RunArgs {
  std::string suite_path;
  std::string out;
  std::string shard;
  bool resume = false;
  bool overwrite = false;
};

// Reads a JSON Lines file of records (JSON objects). A last line cut short by a killed run is
// dropped (*dropped_partial); any other malformed line is an error. *unterminated tells that the
// file does not end with a newline (a whole last record whose '\n' was never written): the
// next append would glue onto it, so the caller rewrites the file first.
std::vector<json> ReadRecords(const std::string& path,
                              bool* dropped_partial,
                              bool* unterminated = nullptr) {
  std::vector<json> records;
  *dropped_partial = false;
  if (unterminated) *unterminated = false;
  if (!fs::exists(path)) return records;
  const std::string text = ReadFile(path);
  if (unterminated) *unterminated = !text.empty() && text.back() != '\n';
  std::vector<std::string> lines;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty()) lines.push_back(line);
  }
  for (size_t i = 0; i < lines.size(); ++i) {
    json record;
    try {
      record = json::parse(lines[i]);
    } catch (const json::exception&) {  // parse_error, or out_of_range (1e999)
    }
    if (record.is_object()) {
      records.push_back(std::move(record));
    } else if (i + 1 == lines.size()) {
      *dropped_partial = true;
    } else {
      throw std::invalid_argument(fmt::format("{}: line {} is not a JSON record", path, i + 1));
    }
  }
  return records;
}

std::string JoinLines(const std::vector<json>& records) {
  std::string text;
  for (const json& r : records) text += r.dump() + "\n";
  return text;
}

void ParseShard(const std::string& s, int* index, int* count) {
  const auto slash = s.find('/');
  try {
    if (slash == std::string::npos) throw std::invalid_argument("");
    size_t a = 0, b = 0;
    *index = std::stoi(s.substr(0, slash), &a);
    *count = std::stoi(s.substr(slash + 1), &b);
    if (a != slash || b != s.size() - slash - 1) throw std::invalid_argument("");
  } catch (const std::exception&) {
    throw std::invalid_argument("--shard '" + s + "': expected i/n with 0 <= i < n");
  }
  if (*count < 1 || *index < 0 || *index >= *count) {
    throw std::invalid_argument("--shard '" + s + "': expected i/n with 0 <= i < n");
  }
}

void WriteSummaries(const std::string& dir, const std::string& name, std::vector<json> records) {
  DeriveTargets(&records);
  WriteFileAtomically(dir + "/summary.md", SummaryMarkdown(name, records));
  WriteFileAtomically(dir + "/records.csv", RecordsCsv(records));
  // Derived fields (best_J, time_to_target) for the plotting script; records.jsonl stays raw.
  WriteFileAtomically(dir + "/derived.jsonl", JoinLines(records));
  json meta{{"suite", name}, {"records", records.size()}};
  WriteFileAtomically(dir + "/suite.json", meta.dump(1) + "\n");
}

std::string Clock(double seconds) {
  const int s = static_cast<int>(seconds + 0.5);
  return fmt::format("{}:{:02d}:{:02d}", s / 3600, (s / 60) % 60, s % 60);
}

void Run(const RunArgs& args) {
  const Suite suite = LoadSuite(args.suite_path);
  const std::string dir = args.out.empty() ? "results/" + suite.name : args.out;
  int shard = 0, shards = 1;
  if (!args.shard.empty()) ParseShard(args.shard, &shard, &shards);
  if (args.resume && args.overwrite)
    throw std::invalid_argument("--resume and --overwrite exclude each other");
  const std::string records_path =
      shards == 1 ? dir + "/records.jsonl"
                  : fmt::format("{}/records.shard-{}-of-{}.jsonl", dir, shard, shards);

  std::set<std::string> done;
  std::vector<json> records;
  if (fs::exists(records_path) && fs::file_size(records_path) > 0) {
    if (args.overwrite) {
      fs::rename(records_path, records_path + ".prev");
      std::cerr << "ocpbench: previous records kept as " << records_path << ".prev\n";
    } else if (!args.resume) {
      throw std::invalid_argument(records_path +
                                  " exists: pass --resume to continue it or --overwrite to " +
                                  "start over (the old file is kept as .prev)");
    } else {
      bool dropped = false, unterminated = false;
      records = ReadRecords(records_path, &dropped, &unterminated);
      if (dropped) {
        std::cerr << "ocpbench: dropped a partial last record in " << records_path
                  << " (its case runs again)\n";
      }
      if (dropped || unterminated) WriteFileAtomically(records_path, JoinLines(records));
      for (const json& r : records) done.insert(r.value("key", ""));
    }
  }

  std::vector<const CaseSpec*> todo;
  int total_in_shard = 0;
  for (size_t i = 0; i < suite.cases.size(); ++i) {
    if (static_cast<int>(i % shards) != shard) continue;
    ++total_in_shard;
    if (!done.count(suite.cases[i].Key())) todo.push_back(&suite.cases[i]);
  }
  const bool tty = ::isatty(STDERR_FILENO);
  if (!done.empty()) {
    std::cerr << fmt::format("ocpbench: resuming: {} of {} cases already recorded\n",
                             total_in_shard - todo.size(),
                             total_in_shard);
  }
  const auto start = std::chrono::steady_clock::now();
  int failed = 0;
  for (size_t i = 0; i < todo.size(); ++i) {
    const CaseSpec& spec = *todo[i];
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (tty) {
      const double eta = i > 0 ? elapsed / i * (todo.size() - i) : 0.0;
      std::cerr << fmt::format("\r\033[Kcase {} of {}  elapsed {}  remaining ~{}  {} / {}{}",
                               i + 1,
                               todo.size(),
                               Clock(elapsed),
                               i > 0 ? Clock(eta) : "?",
                               spec.problem,
                               spec.solver,
                               spec.transcription.empty() ? "" : " + " + spec.transcription)
                << std::flush;
    }
    // One case never stops the suite: whatever it throws becomes its record.
    json record = RunCaseRecordingFailures(spec);
    if (IsFailure(record.value("status", ""))) ++failed;
    AppendLineDurably(records_path, record.dump());
    records.push_back(std::move(record));
  }
  if (tty) std::cerr << "\r\033[K";
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cerr << fmt::format("ocpbench: {} cases run in {}, {} failed; records in {}\n",
                           todo.size(),
                           Clock(elapsed),
                           failed,
                           records_path);
  if (shards == 1) {
    WriteSummaries(dir, suite.name, records);
    std::cerr << "ocpbench: summary in " << dir << "/summary.md\n";
  } else {
    std::cerr << "ocpbench: shard done; join shards with `ocpbench merge " << dir << "`\n";
  }
  if (failed > 0) ReportSomeFailed();
}

void Merge(const std::string& dir, const std::string& name_arg) {
  if (!fs::is_directory(dir)) throw std::invalid_argument("merge: no such directory " + dir);
  std::vector<std::string> shard_files;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string f = e.path().filename().string();
    if (f.rfind("records.shard-", 0) == 0 && f.size() > 6 && f.substr(f.size() - 6) == ".jsonl") {
      shard_files.push_back(e.path().string());
    }
  }
  if (shard_files.empty())
    throw std::invalid_argument("merge: no records.shard-*.jsonl files in " + dir);
  std::sort(shard_files.begin(), shard_files.end());
  std::vector<json> merged;
  std::set<std::string> keys;
  for (const std::string& f : shard_files) {
    bool dropped = false;
    for (json& r : ReadRecords(f, &dropped)) {
      if (keys.insert(r.value("key", "")).second) merged.push_back(std::move(r));
    }
    if (dropped) std::cerr << "ocpbench: merge: ignored a partial last record in " << f << "\n";
  }
  const std::string records_path = dir + "/records.jsonl";
  if (fs::exists(records_path)) fs::rename(records_path, records_path + ".prev");
  WriteFileAtomically(records_path, JoinLines(merged));
  const std::string name = name_arg.empty() ? fs::path(dir).filename().string() : name_arg;
  WriteSummaries(dir, name, merged);
  std::cerr << fmt::format("ocpbench: merged {} records from {} shards into {}\n",
                           merged.size(),
                           shard_files.size(),
                           records_path);
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
  run->add_option("--shard", args->shard, "run only cases i, i+n, i+2n, ... (i/n)");
  run->callback([args]() { Run(*args); });

  auto dir = std::make_shared<std::string>();
  auto name = std::make_shared<std::string>();
  CLI::App* merge = app.add_subcommand("merge", "Join the shard records of a suite directory");
  merge->add_option("dir", *dir, "suite output directory")->required();
  merge->add_option("--name", *name, "suite name for the summary (default: directory name)");
  merge->callback([dir, name]() { Merge(*dir, *name); });
}

}  // namespace ocpb
