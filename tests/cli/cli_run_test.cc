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
  return R"({"name": "tiny", "groups": [{"problem": "double-integrator", "N": )" + std::to_string(N) +
         R"(, "seeds": [)" + SeedList(seeds) +
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
    for (const char* key : {"problem", "parameters", "seed", "solver", "N", "status", "J", "Jbar",
                            "terminal_violation", "control_violation", "resimulation_defect",
                            "iterations", "cpu_seconds", "wall_seconds", "history", "versions"}) {
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
  const ProgramRun resumed = RunOcpbenchProgram({"run", "suite.json", "--out", "out", "--resume"}, dir);
  EXPECT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_EQ(ReadJsonLines(dir + "/out/records.jsonl").size(), 2u);
}

TEST(CliRun, KilledRunResumesWithEveryCaseExactlyOnce) {
  const std::string dir = testing::FreshDirectory("killed-suite");
  const int cases = 40;
  testing::WriteText(dir + "/suite.json", TinySuite(cases, 4000));
  const int pid = testing::StartOcpbenchProgram({"run", "suite.json", "--out", "out"}, dir);
  const std::string records = dir + "/out/records.jsonl";
  // Kill it once a few records are on disk (or when it is done, whichever comes first).
  for (int i = 0; i < 6000; ++i) {
    if (std::filesystem::exists(records) && ReadJsonLines(records).size() >= 3) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ::kill(pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
  const size_t before = ReadJsonLines(records).size();
  EXPECT_GE(before, 1u);
  const ProgramRun resumed = RunOcpbenchProgram({"run", "suite.json", "--out", "out", "--resume"}, dir);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  std::map<std::string, int> count;
  for (const json& r : ReadJsonLines(records)) count[r["key"]]++;
  EXPECT_EQ(count.size(), static_cast<size_t>(cases));
  for (const auto& [key, n] : count) EXPECT_EQ(n, 1) << key;
}

TEST(CliRun, MergedShardsEqualTheUnshardedRun) {
  const std::string dir = testing::FreshDirectory("sharded-suite");
  testing::WriteText(dir + "/suite.json", TinySuite(5, 40));
  ASSERT_EQ(RunOcpbenchProgram({"run", "suite.json", "--out", "whole"}, dir).exit_code, 0);
  for (const char* shard : {"0/3", "1/3", "2/3"}) {
    const ProgramRun run = RunOcpbenchProgram({"run", "suite.json", "--out", "parts", "--shard", shard}, dir);
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
