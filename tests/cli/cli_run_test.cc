// End-to-end: suites through `ocpbench run`, resume after SIGKILL, shards and merge.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <thread>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/cli/run_ocpbench.h"

namespace ocpb {
namespace {

using nlohmann::json;
using testing::ProgramRun;
using testing::RunOcpbenchProgram;

std::string SeedList(int n) {
  std::string s;
  for (int i = 1; i <= n; ++i) s += (i > 1 ? ", " : "") + std::to_string(i);
  return s;
}

std::string TinySuite(int seeds, int N) {
  return R"({"name": "tiny", "groups": [{"problem": "double-integrator", "N": )" +
         std::to_string(N) + R"(, "seeds": [)" + SeedList(seeds) +
         R"(], "methods": [{"solver": "hamiltonian", "options": {"max_iterations": 30}}]}]})";
}

std::vector<json> ReadJsonLines(const std::string& path) {
  std::vector<json> out;
  std::istringstream in(testing::ReadText(path));
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty()) out.push_back(json::parse(line));
  }
  return out;
}

TEST(CliRun, TinySuiteWritesRecordsSummaryAndCsv) {
  const std::string dir = testing::FreshDirectory("tiny-suite");
  testing::WriteText(dir + "/suite.json", TinySuite(2, 50));
  const ProgramRun run = RunOcpbenchProgram({"run", "suite.json", "--out", "out"}, dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::vector<json> records = ReadJsonLines(dir + "/out/records.jsonl");
  ASSERT_EQ(records.size(), 2u);
  for (const json& r : records) {
    for (const char* key : {"problem",
                            "parameters",
                            "seed",
                            "solver",
                            "N",
                            "status",
                            "J",
                            "Jbar",
                            "terminal_violation",
                            "control_violation",
                            "resimulation_defect",
                            "iterations",
                            "cpu_seconds",
                            "wall_seconds",
                            "history",
                            "versions"}) {
      EXPECT_TRUE(r.contains(key)) << key;
    }
    EXPECT_EQ(r["problem"], "double-integrator");
    EXPECT_EQ(r["N"], 50);
    EXPECT_TRUE(r["J"].is_number());
    EXPECT_FALSE(r["history"].empty());
    EXPECT_TRUE(r["versions"].contains("commit"));
  }
  const std::string summary = testing::ReadText(dir + "/out/summary.md");
  EXPECT_NE(summary.find("## double-integrator"), std::string::npos) << summary;
  EXPECT_NE(summary.find("| hamiltonian, penalty, N=50 | 2 |"), std::string::npos) << summary;
  const std::string csv = testing::ReadText(dir + "/out/records.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 3);  // header + 2 rows

  // A second run refuses to clobber the records; --resume runs nothing new.
  const ProgramRun again = RunOcpbenchProgram({"run", "suite.json", "--out", "out"}, dir);
  EXPECT_EQ(again.exit_code, 2);
  EXPECT_NE(again.err.find("pass --resume"), std::string::npos) << again.err;
  EXPECT_EQ(ReadJsonLines(dir + "/out/records.jsonl").size(), 2u);
  const ProgramRun resumed =
      RunOcpbenchProgram({"run", "suite.json", "--out", "out", "--resume"}, dir);
  EXPECT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_EQ(ReadJsonLines(dir + "/out/records.jsonl").size(), 2u);
}

// Cases of a suite that a test kills mid-run: about 0.8 s each under the sanitizers at N = 1200
// (measured), and at N = 12000 about 0.4 s in Release (0.05 s at N = 1200).
#ifdef OCPB_SANITIZED
constexpr int kKillTestN = 1200;
#else
constexpr int kKillTestN = 12000;
#endif

// The records whose line is complete (ends with '\n'); a line cut short by a kill is not one.
std::vector<json> CompleteRecords(const std::string& path) {
  std::vector<json> out;
  const std::string text = testing::ReadText(path);
  size_t begin = 0;
  for (size_t nl = text.find('\n'); nl != std::string::npos; nl = text.find('\n', begin)) {
    if (nl > begin) out.push_back(json::parse(text.substr(begin, nl - begin)));
    begin = nl + 1;
  }
  return out;
}

TEST(CliRun, KilledRunResumesWithEveryCaseExactlyOnce) {
  const std::string dir = testing::FreshDirectory("killed-suite");
  // Cases long enough for the kill below to land with most of the suite still to run.
  const int cases = 8;
  testing::WriteText(dir + "/suite.json", TinySuite(cases, kKillTestN));
  const int pid = testing::StartOcpbenchProgram({"run", "suite.json", "--out", "out"}, dir);
  const std::string records = dir + "/out/records.jsonl";
  // Kill it once two records are on disk (or when it is done, whichever comes first).
  for (int i = 0; i < 12000; ++i) {
    if (std::filesystem::exists(records) && CompleteRecords(records).size() >= 2) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ::kill(pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL)
      << "the run ended before the kill";
  const size_t before = CompleteRecords(records).size();
  EXPECT_GE(before, 2u);
  EXPECT_LT(before, static_cast<size_t>(cases)) << "the kill did not land mid-run";
  const ProgramRun resumed =
      RunOcpbenchProgram({"run", "suite.json", "--out", "out", "--resume"}, dir);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_NE(
      resumed.err.find(fmt::format("resuming: {} of {} cases already recorded", before, cases)),
      std::string::npos)
      << resumed.err;
  std::map<std::string, int> count;
  for (const json& r : ReadJsonLines(records)) count[r["key"]]++;  // every line whole now
  EXPECT_EQ(count.size(), static_cast<size_t>(cases));
  for (const auto& [key, n] : count) EXPECT_EQ(n, 1) << key;
}

// A run killed in the middle of writing a record leaves half a line: --resume drops it and runs
// that case again; a whole last record whose newline is missing is kept and terminated.
TEST(CliRun, ResumeDropsAHalfWrittenLastRecordAndRunsItsCaseAgain) {
  const std::string dir = testing::FreshDirectory("half-written");
  testing::WriteText(dir + "/suite.json", TinySuite(3, 20));
  ASSERT_EQ(RunOcpbenchProgram({"run", "suite.json", "--out", "out"}, dir).exit_code, 0);
  const std::string records = dir + "/out/records.jsonl";
  const std::vector<json> whole = ReadJsonLines(records);
  ASSERT_EQ(whole.size(), 3u);
  const std::string first_two = whole[0].dump() + "\n" + whole[1].dump() + "\n";
  const std::string last = whole[2].dump();

  testing::WriteText(records, first_two + last.substr(0, last.size() / 2));
  const ProgramRun resumed =
      RunOcpbenchProgram({"run", "suite.json", "--out", "out", "--resume"}, dir);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_NE(resumed.err.find("dropped a partial last record"), std::string::npos) << resumed.err;
  EXPECT_NE(resumed.err.find("1 cases run"), std::string::npos) << resumed.err;
  std::vector<json> after = ReadJsonLines(records);
  ASSERT_EQ(after.size(), 3u);
  std::set<std::string> keys;
  for (const json& r : after) keys.insert(r["key"]);
  EXPECT_EQ(keys.size(), 3u);
  EXPECT_EQ(after[2]["key"], whole[2]["key"]);
  EXPECT_EQ(after[2]["J"], whole[2]["J"]);  // the case ran again, deterministically

  testing::WriteText(records, first_two + last);  // whole, but no '\n'
  const ProgramRun kept =
      RunOcpbenchProgram({"run", "suite.json", "--out", "out", "--resume"}, dir);
  ASSERT_EQ(kept.exit_code, 0) << kept.err;
  EXPECT_NE(kept.err.find("0 cases run"), std::string::npos) << kept.err;
  const std::string text = testing::ReadText(records);
  EXPECT_EQ(text, first_two + last + "\n");

  // Damage anywhere but at the end is not a kill's doing: refused, nothing changed.
  testing::WriteText(records, whole[0].dump() + "\n{\"key\": \n" + last + "\n");
  const ProgramRun refused =
      RunOcpbenchProgram({"run", "suite.json", "--out", "out", "--resume"}, dir);
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("records.jsonl:2: not valid JSON at column 9"), std::string::npos)
      << refused.err;
}

// One case that fails numerically is that case's record; the others still run; exit code 1.
TEST(CliRun, AFailedCaseIsRecordedAndTheSuiteGoesOn) {
  const std::string dir = testing::FreshDirectory("one-fails");
  // C = 1e300 makes the penalty overflow: theta is not finite at the first iteration.
  testing::WriteText(dir + "/suite.json", R"({"name": "mixed", "groups": [
    {"problem": "double-integrator", "N": 20, "seeds": [1, 2],
     "methods": [{"solver": "hamiltonian", "options": {"max_iterations": 30}}]},
    {"problem": "double-integrator", "N": 20, "set": {"C": 1e300},
     "methods": [{"solver": "hamiltonian"}]},
    {"problem": "double-integrator", "N": 20, "seeds": [3],
     "methods": [{"solver": "hamiltonian", "options": {"max_iterations": 30}}]}]})");
  const ProgramRun run = RunOcpbenchProgram({"run", "suite.json", "--out", "out"}, dir);
  EXPECT_EQ(run.exit_code, 1) << run.err;
  EXPECT_NE(run.err.find("4 cases run"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("1 failed"), std::string::npos) << run.err;
  const std::vector<json> records = ReadJsonLines(dir + "/out/records.jsonl");
  ASSERT_EQ(records.size(), 4u);
  EXPECT_EQ(records[2]["status"], "numerical_failure");
  EXPECT_EQ(records[2]["solver_status"], "nonfinite_theta");
  for (int i : {0, 1, 3}) EXPECT_EQ(records[i]["status"], "max_iterations") << i;
  EXPECT_TRUE(std::filesystem::exists(dir + "/out/summary.md"));
}

std::vector<std::string> KeysOf(const std::vector<json>& records) {
  std::vector<std::string> keys;
  for (const json& r : records) keys.push_back(r["key"]);
  return keys;
}

// Shards are numbered 1..n (as Slurm's --array=1-n); merged, they are the unsharded run: the same
// cases in the suite's order, with the same deterministic results.
TEST(CliRun, MergedShardsEqualTheUnshardedRun) {
  const std::string dir = testing::FreshDirectory("sharded-suite");
  testing::WriteText(dir + "/suite.json", TinySuite(5, 40));
  ASSERT_EQ(RunOcpbenchProgram({"run", "suite.json", "--out", "whole"}, dir).exit_code, 0);
  for (const char* shard : {"3/3", "1/3", "2/3"}) {
    const ProgramRun run =
        RunOcpbenchProgram({"run", "suite.json", "--out", "parts", "--shard", shard}, dir);
    ASSERT_EQ(run.exit_code, 0) << run.err;
  }
  EXPECT_EQ(ReadJsonLines(dir + "/parts/records.shard-1-of-3.jsonl").size(), 2u);
  EXPECT_EQ(ReadJsonLines(dir + "/parts/records.shard-3-of-3.jsonl").size(), 1u);
  const ProgramRun status = RunOcpbenchProgram({"status", "parts"}, dir);
  EXPECT_EQ(status.exit_code, 0) << status.err;
  EXPECT_NE(status.out.find("shard 2 of 3: 2 of 2 cases recorded"), std::string::npos)
      << status.out;
  const ProgramRun merge = RunOcpbenchProgram({"merge", "parts"}, dir);
  ASSERT_EQ(merge.exit_code, 0) << merge.err;
  EXPECT_NE(merge.err.find("5 of 5 cases recorded in 3 shards"), std::string::npos) << merge.err;
  const std::vector<json> whole = ReadJsonLines(dir + "/whole/records.jsonl");
  const std::vector<json> parts = ReadJsonLines(dir + "/parts/records.jsonl");
  ASSERT_EQ(whole.size(), 5u);
  EXPECT_EQ(KeysOf(parts), KeysOf(whole));  // the suite's order
  for (size_t i = 0; i < whole.size() && i < parts.size(); ++i) {
    // Deterministic results: the same J and iterations whichever process ran the case.
    EXPECT_EQ(parts[i]["J"], whole[i]["J"]);
    EXPECT_EQ(parts[i]["iterations"], whole[i]["iterations"]);
  }
  const std::string summary = testing::ReadText(dir + "/parts/summary.md");
  EXPECT_NE(summary.find("# Suite `tiny`"), std::string::npos) << summary;  // the suite's name
  EXPECT_EQ(summary.find("Partial"), std::string::npos) << summary;
}

// A shard that never ran, a shard cut short, a case recorded twice, a record of another suite:
// merge and status name each by key and shard and exit 4; the summary says it is partial.
TEST(CliRun, MergeReportsMissingShardsAndMissingOrDuplicatedCasesByKey) {
  const std::string dir = testing::FreshDirectory("incomplete-shards");
  testing::WriteText(dir + "/suite.json", TinySuite(7, 20));  // shards of 3, 2, 2 cases
  for (const char* shard : {"1/3", "3/3"}) {
    ASSERT_EQ(
        RunOcpbenchProgram({"run", "suite.json", "--out", "out", "--shard", shard}, dir).exit_code,
        0);
  }
  const std::string shard1 = dir + "/out/records.shard-1-of-3.jsonl";
  const std::vector<json> first = ReadJsonLines(shard1);
  ASSERT_EQ(first.size(), 3u);
  testing::WriteText(shard1, first[0].dump() + "\n" + first[1].dump() + "\n");  // cut short
  const ProgramRun status = RunOcpbenchProgram({"status", "out"}, dir);
  EXPECT_EQ(status.exit_code, 4) << status.err;
  EXPECT_NE(status.out.find("shard 1 of 3: 2 of 3 cases recorded"), std::string::npos)
      << status.out;
  EXPECT_NE(status.out.find("shard 2 of 3: 0 of 2 cases recorded (no records file yet)"),
            std::string::npos)
      << status.out;

  const ProgramRun merge = RunOcpbenchProgram({"merge", "out"}, dir);
  EXPECT_EQ(merge.exit_code, 4) << merge.err;
  for (const std::string& text :
       {std::string("merged 4 records from 2 of 3 shards"),
        std::string("4 of 7 cases recorded in 3 shards: incomplete"),
        std::string("shard 1 of 3: 2 of 3 cases recorded (records.shard-1-of-3.jsonl)"),
        std::string("shard 2 of 3: missing (no records.shard-2-of-3.jsonl; 2 cases)"),
        "missing case: " + first[2]["key"].get<std::string>(),
        std::string("shards to run again: 1-2")}) {
    EXPECT_NE(merge.err.find(text), std::string::npos) << text << "\n" << merge.err;
  }
  const std::string summary = testing::ReadText(dir + "/out/summary.md");
  EXPECT_NE(summary.find("Partial: 4 of the suite's 7 cases are recorded"), std::string::npos)
      << summary;
  EXPECT_EQ(ReadJsonLines(dir + "/out/records.jsonl").size(), 4u);

  // The missing shards resumed: complete. Then a duplicate and a stranger: incomplete again.
  for (const char* shard : {"1/3", "2/3"}) {
    ASSERT_EQ(
        RunOcpbenchProgram({"run", "suite.json", "--out", "out", "--shard", shard, "--resume"}, dir)
            .exit_code,
        0);
  }
  ASSERT_EQ(RunOcpbenchProgram({"merge", "out"}, dir).exit_code, 0);
  EXPECT_EQ(testing::ReadText(dir + "/out/summary.md").find("Partial"), std::string::npos);
  const std::string shard3 = dir + "/out/records.shard-3-of-3.jsonl";
  json stranger = first[0];
  stranger["key"] = "no-such-case";
  testing::WriteText(shard3,
                     testing::ReadText(shard3) + first[0].dump() + "\n" + stranger.dump() + "\n");
  const ProgramRun dup = RunOcpbenchProgram({"merge", "out"}, dir);
  EXPECT_EQ(dup.exit_code, 4) << dup.err;
  EXPECT_NE(dup.err.find("duplicated case: " + first[0]["key"].get<std::string>()),
            std::string::npos)
      << dup.err;
  EXPECT_NE(dup.err.find("not a case of the suite: no-such-case"), std::string::npos) << dup.err;
  EXPECT_EQ(ReadJsonLines(dir + "/out/records.jsonl").size(), 7u);  // each case once
}

// A folder is one sweep: another shard count or another suite cannot join it, and a folder of
// the earlier 0-based shard numbering is refused; nothing is written (exit 2).
TEST(CliRun, AFolderHoldsOneSweep) {
  const std::string dir = testing::FreshDirectory("one-sweep");
  testing::WriteText(dir + "/suite.json", TinySuite(3, 20));
  testing::WriteText(dir + "/other.json", TinySuite(4, 20));
  ASSERT_EQ(
      RunOcpbenchProgram({"run", "suite.json", "--out", "out", "--shard", "1/2"}, dir).exit_code,
      0);
  const ProgramRun count =
      RunOcpbenchProgram({"run", "suite.json", "--out", "out", "--shard", "1/3"}, dir);
  EXPECT_EQ(count.exit_code, 2);
  EXPECT_NE(count.err.find("holds a sweep of 2 shards, not 3"), std::string::npos) << count.err;
  const ProgramRun other =
      RunOcpbenchProgram({"run", "other.json", "--out", "out", "--shard", "2/2"}, dir);
  EXPECT_EQ(other.exit_code, 2);
  EXPECT_NE(other.err.find("holds shards of another suite document"), std::string::npos)
      << other.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/out/records.shard-2-of-2.jsonl"));
  // merge --suite with another suite than the shards ran: refused before anything is written.
  const ProgramRun foreign = RunOcpbenchProgram({"merge", "out", "--suite", "other.json"}, dir);
  EXPECT_EQ(foreign.exit_code, 2);
  EXPECT_NE(foreign.err.find("holds shards of another suite document"), std::string::npos)
      << foreign.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/out/records.jsonl"));

  std::filesystem::create_directories(dir + "/old");
  testing::WriteText(dir + "/old/records.shard-0-of-2.jsonl", "");
  const ProgramRun old = RunOcpbenchProgram({"merge", "old", "--suite", "suite.json"}, dir);
  EXPECT_EQ(old.exit_code, 2);
  EXPECT_NE(old.err.find("records.shard-0-of-2.jsonl: not a shard of the 1-based numbering"),
            std::string::npos)
      << old.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/old/records.jsonl"));
}

// --resume continues a folder with the suite that wrote it: a suite that grew may resume it
// (every record is one of its cases), one that holds fewer or other cases may not (the records
// file and the summary would mix two suites); nothing is written.
TEST(CliRun, ResumeRefusesAFolderOfAnotherSuite) {
  const std::string dir = testing::FreshDirectory("resume-other-suite");
  testing::WriteText(dir + "/two.json", TinySuite(2, 20));
  testing::WriteText(dir + "/three.json", TinySuite(3, 20));
  testing::WriteText(dir + "/other.json", TinySuite(2, 30));
  ASSERT_EQ(RunOcpbenchProgram({"run", "three.json", "--out", "big"}, dir).exit_code, 0);
  const std::string before = testing::ReadText(dir + "/big/records.jsonl");
  for (const char* smaller : {"two.json", "other.json"}) {
    const ProgramRun run = RunOcpbenchProgram({"run", smaller, "--out", "big", "--resume"}, dir);
    EXPECT_EQ(run.exit_code, 2) << smaller << ": " << run.err;
    EXPECT_NE(run.err.find("is not a case of suite 'tiny'"), std::string::npos) << run.err;
    EXPECT_EQ(testing::ReadText(dir + "/big/records.jsonl"), before) << smaller;
  }
  ASSERT_EQ(RunOcpbenchProgram({"run", "two.json", "--out", "small"}, dir).exit_code, 0);
  const ProgramRun grown =
      RunOcpbenchProgram({"run", "three.json", "--out", "small", "--resume"}, dir);
  EXPECT_EQ(grown.exit_code, 0) << grown.err;
  EXPECT_NE(grown.err.find("resuming: 2 of 3 cases already recorded"), std::string::npos)
      << grown.err;
  EXPECT_EQ(ReadJsonLines(dir + "/small/records.jsonl").size(), 3u);
}

// Timing fields are the only ones that may differ between runs of the same case: the record's
// CPU and wall seconds, each history entry's CPU seconds, the solver's own *_seconds statistics.
json WithoutTimings(json r) {
  r.erase("cpu_seconds");
  r.erase("cpu_seconds_repeats");
  r.erase("wall_seconds");
  for (json& h : r["history"]) h.erase("cpu_seconds");
  if (r.contains("solver_stats") && r["solver_stats"].is_object()) {
    json stats = json::object();
    for (const auto& [k, v] : r["solver_stats"].items()) {
      if (!k.ends_with("_seconds")) stats[k] = v;
    }
    r["solver_stats"] = stats;
  }
  return r;
}

// The top-level fields in which two records differ (a short failure message).
std::string DifferingFields(const json& a, const json& b) {
  std::string out;
  for (const auto& [k, v] : a.items()) {
    if (!b.contains(k) || b[k] != v) out += k + " ";
  }
  for (const auto& [k, v] : b.items()) {
    if (!a.contains(k)) out += k + " ";
  }
  return out;
}

std::string FourMethodSuite() {
  // Two problems, a failing case (C = 1e300 overflows the penalty), an Ipopt method.
  return R"({"name": "mixed", "groups": [
    {"problem": "double-integrator", "N": 30, "seeds": [1, 2, 3],
     "methods": [{"solver": "hamiltonian", "options": {"max_iterations": 40}},
                 {"solver": "ipopt", "transcription": "euler"}]},
    {"problem": "double-integrator", "N": 20, "set": {"C": 1e300},
     "methods": [{"solver": "hamiltonian"}]},
    {"problem": "bryson-denham", "N": 25,
     "methods": [{"solver": "ipopt", "transcription": "hermite-simpson"},
                 {"solver": "hamiltonian", "options": {"max_iterations": 20}}]}]})";
}

// --jobs N: the same records as one process, in the suite's order, apart from timings; each
// case's CPU time its own (not its worker's total: then later cases would exceed their wall time).
TEST(CliRun, JobsGiveTheSerialRecordsInSuiteOrder) {
  const std::string dir = testing::FreshDirectory("jobs");
  testing::WriteText(dir + "/suite.json", FourMethodSuite());
  const ProgramRun serial = RunOcpbenchProgram({"run", "suite.json", "--out", "serial"}, dir);
  ASSERT_EQ(serial.exit_code, 1) << serial.err;  // the overflowing case fails
  const ProgramRun jobs =
      RunOcpbenchProgram({"run", "suite.json", "--out", "jobs", "--jobs", "3"}, dir);
  ASSERT_EQ(jobs.exit_code, 1) << jobs.err;
  EXPECT_NE(jobs.err.find("9 cases run"), std::string::npos) << jobs.err;
  EXPECT_NE(jobs.err.find("1 failed"), std::string::npos) << jobs.err;
  const std::vector<json> a = ReadJsonLines(dir + "/serial/records.jsonl");
  const std::vector<json> b = ReadJsonLines(dir + "/jobs/records.jsonl");
  ASSERT_EQ(a.size(), 9u);
  ASSERT_EQ(b.size(), a.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_TRUE(WithoutTimings(b[i]) == WithoutTimings(a[i]))
        << "record " << i
        << " differs in: " << DifferingFields(WithoutTimings(a[i]), WithoutTimings(b[i]));
    const double cpu = b[i]["cpu_seconds"].is_number() ? b[i]["cpu_seconds"].get<double>() : 0;
    const double wall = b[i]["wall_seconds"].is_number() ? b[i]["wall_seconds"].get<double>() : 0;
    EXPECT_LE(cpu, 1.2 * wall + 0.02) << "record " << i << " (" << b[i]["key"] << ")";
  }
  // The tables are made from the same records.
  const std::string csv = testing::ReadText(dir + "/jobs/records.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 10);  // header + 9 rows
}

std::vector<int> ChildrenOf(int pid) {
  std::vector<int> out;
  std::istringstream in(testing::ReadText(fmt::format("/proc/{}/task/{}/children", pid, pid)));
  for (int c; in >> c;) out.push_back(c);
  return out;
}

// A worker killed in the middle of a case costs that case only: it is recorded as an error
// (worker_died) and the run goes on. Killing the run itself takes its workers with it; --resume
// then finishes every case exactly once.
TEST(CliRun, JobsSurviveAKilledWorkerAndDieWithTheRun) {
  const std::string dir = testing::FreshDirectory("jobs-killed");
  const int cases = 6;
  testing::WriteText(dir + "/suite.json", TinySuite(cases, kKillTestN));
  const std::string records = dir + "/out/records.jsonl";
  auto wait_for_records = [&](size_t n) {
    for (int i = 0; i < 12000; ++i) {
      if (std::filesystem::exists(records) && CompleteRecords(records).size() >= n) return;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  };
  int pid =
      testing::StartOcpbenchProgram({"run", "suite.json", "--out", "out", "--jobs", "2"}, dir);
  wait_for_records(1);
  std::vector<int> workers = ChildrenOf(pid);
  ASSERT_EQ(workers.size(), 2u) << "the run ended before the kill";
  ::kill(workers[0], SIGKILL);
  wait_for_records(3);
  workers = ChildrenOf(pid);
  ::kill(pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the run ended before the kill";
  for (int w : workers) {  // the workers follow their run (PR_SET_PDEATHSIG)
    for (int i = 0; i < 2000 && std::filesystem::exists(fmt::format("/proc/{}/cmdline", w)) &&
                    testing::ReadText(fmt::format("/proc/{}/cmdline", w)).size() > 0;
         ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    EXPECT_TRUE(testing::ReadText(fmt::format("/proc/{}/cmdline", w)).empty())
        << "worker " << w << " outlived its run";
  }
  const size_t before = CompleteRecords(records).size();
  EXPECT_LT(before, static_cast<size_t>(cases)) << "the kill did not land mid-run";
  const ProgramRun resumed =
      RunOcpbenchProgram({"run", "suite.json", "--out", "out", "--resume", "--jobs", "2"}, dir);
  // The killed worker's case was recorded (as a failure) by the first run: not run again.
  EXPECT_EQ(resumed.exit_code, 0) << resumed.err;
  const std::vector<json> all = ReadJsonLines(records);
  std::map<std::string, int> count;
  int died = 0;
  for (const json& r : all) {
    count[r["key"]]++;
    if (r["solver_status"] == "worker_died") {
      ++died;
      EXPECT_EQ(r["status"], "error");
      EXPECT_NE(r["message"].get<std::string>().find("killed by signal 9"), std::string::npos)
          << r["message"];
    }
  }
  EXPECT_EQ(died, 1);
  EXPECT_EQ(count.size(), static_cast<size_t>(cases));
  for (const auto& [key, n] : count) EXPECT_EQ(n, 1) << key;
  std::vector<std::string> suite_order;
  for (const json& r : ReadJsonLines(dir + "/out/records.jsonl")) suite_order.push_back(r["key"]);
  std::vector<std::string> sorted_by_seed = suite_order;
  std::sort(sorted_by_seed.begin(), sorted_by_seed.end(), [](const auto& x, const auto& y) {
    auto seed = [](const std::string& k) { return std::stoi(k.substr(k.find("seed=") + 5)); };
    return seed(x) < seed(y);
  });
  EXPECT_EQ(suite_order, sorted_by_seed);  // put back in the suite's order at the end
}

}  // namespace
}  // namespace ocpb
