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
  // Cases of about 0.1 s each (Release; several times that under the sanitizers), so that the
  // kill below lands with most of the suite still to run.
  const int cases = 8;
  testing::WriteText(dir + "/suite.json", TinySuite(cases, 4000));
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

TEST(CliRun, MergedShardsEqualTheUnshardedRun) {
  const std::string dir = testing::FreshDirectory("sharded-suite");
  testing::WriteText(dir + "/suite.json", TinySuite(5, 40));
  ASSERT_EQ(RunOcpbenchProgram({"run", "suite.json", "--out", "whole"}, dir).exit_code, 0);
  for (const char* shard : {"0/3", "1/3", "2/3"}) {
    const ProgramRun run =
        RunOcpbenchProgram({"run", "suite.json", "--out", "parts", "--shard", shard}, dir);
    ASSERT_EQ(run.exit_code, 0) << run.err;
  }
  const ProgramRun merge = RunOcpbenchProgram({"merge", "parts", "--name", "tiny"}, dir);
  ASSERT_EQ(merge.exit_code, 0) << merge.err;
  auto by_key = [](const std::vector<json>& rs) {
    std::map<std::string, json> m;
    for (const json& r : rs) m[r["key"]] = r;
    return m;
  };
  const auto whole = by_key(ReadJsonLines(dir + "/whole/records.jsonl"));
  const auto parts = by_key(ReadJsonLines(dir + "/parts/records.jsonl"));
  ASSERT_EQ(whole.size(), 5u);
  ASSERT_EQ(parts.size(), whole.size());
  for (const auto& [key, r] : whole) {
    ASSERT_TRUE(parts.count(key)) << key;
    // Deterministic results: the same J and iterations whichever process ran the case.
    EXPECT_EQ(parts.at(key)["J"], r["J"]);
    EXPECT_EQ(parts.at(key)["iterations"], r["iterations"]);
  }
  EXPECT_TRUE(std::filesystem::exists(dir + "/parts/summary.md"));
}

}  // namespace
}  // namespace ocpb
