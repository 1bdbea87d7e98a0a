// Issue 41's leftovers, each as a class tried with many values: Ipopt's options
// are accepted by the check exactly when the linked Ipopt accepts them (the
// check asks Ipopt, no list of its rules), no output of any command names a run
// folder's files, `online` checks its horizon as `solve` does, and a thread the
// system refuses does not end the channel prediction.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bench/cli/output_place.h"
#include "solvers/ipopt_adapter.h"
#include "tests/cli/run_ocpbench.h"

namespace ocpb {
// Named, not anonymous: the unity build puts this file beside the other
// reliability tests.
namespace round4 {

namespace fs = std::filesystem;
using nlohmann::json;
using testing::ProgramRun;
using testing::RunOcpbenchProgram;

// ---- no output names a run folder's files
// --------------------------------------------------

bool OneErrorLine(const ProgramRun &run) {
  return run.err.rfind("ocpbench: error: ", 0) == 0 &&
         std::count(run.err.begin(), run.err.end(), '\n') == 1;
}

std::map<std::string, std::string> Snapshot(const std::string &dir) {
  std::map<std::string, std::string> out;
  for (const auto &e : fs::recursive_directory_iterator(dir)) {
    if (e.is_symlink() || !e.is_regular_file())
      continue;
    if (e.path().filename() == ".ocpbench.lock")
      continue;
    out[fs::relative(e.path(), dir).string()] =
        testing::ReadText(e.path().string());
  }
  return out;
}

std::string QuickSuite(int seeds) {
  std::string list;
  for (int i = 1; i <= seeds; ++i)
    list += (i > 1 ? "," : "") + std::to_string(i);
  return R"({"name": "r4", "groups": [{"problem": "double-integrator", "N": 10, "seeds": [)" +
         list +
         R"(], "methods": [{"solver": "hamiltonian", "options": {"max_iterations": 3}}]}]})";
}

// The shared checker (FilePlan) against run folders, by every spelling of their
// files: those that exist, those a shard has yet to write, through links to the
// file and to the folder.
TEST(OutputNeverNamesARunFolder, EverySpellingOfEveryRunFolderFile) {
  const std::string dir = testing::FreshDirectory("r4-run-folder-plan");
  testing::WriteText(dir + "/suite.json", QuickSuite(3));
  ASSERT_EQ(
      RunOcpbenchProgram({"run", "suite.json", "--out", "runs"}, dir).exit_code,
      0);
  ASSERT_EQ(RunOcpbenchProgram(
                {"run", "suite.json", "--out", "sweep", "--shard", "2/3"}, dir)
                .exit_code,
            0);
  fs::create_directories(dir + "/other");
  fs::create_symlink("runs", dir + "/runs-link");
  fs::create_symlink("runs/records.jsonl", dir + "/records-link");
  fs::create_symlink("../sweep", dir + "/other/sweep-link");
  const std::string abs = fs::canonical(dir).string();
  std::vector<std::string> refused;
  for (const std::string &folder : std::vector<std::string>{
           "runs", "./runs", "other/../runs", abs + "/runs", "runs-link"}) {
    for (const std::string &name :
         {"records.jsonl", "records.jsonl.prev", "records.jsonl.3.prev",
          "summary.md", "records.csv", "derived.jsonl", "suite.json",
          ".ocpbench.lock"}) {
      refused.push_back(folder + "/" + name);
    }
  }
  for (const std::string &folder : std::vector<std::string>{
           "sweep", "./sweep/", "other/sweep-link", abs + "/sweep"}) {
    for (const std::string &name :
         {"records.shard-1-of-3.jsonl", // not written yet
          "records.shard-2-of-3.jsonl", "records.shard-3-of-3.jsonl.prev",
          "records.jsonl", "shards.json"}) {
      refused.push_back(folder + (folder.back() == '/' ? "" : "/") + name);
    }
  }
  refused.push_back("records-link");
  const std::vector<std::string> accepted = {
      "runs/ipopt.log",      "runs/records.txt", "sweep/notes.md",
      "records.jsonl", // no run folder here
      "other/records.jsonl", "other/summary.md"};
  const fs::path cwd = fs::current_path();
  fs::current_path(dir);
  for (const std::string &path : refused) {
    for (const char *what : {"--json", "--option output_file"}) {
      FilePlan plan;
      plan.Output(path, what);
      try {
        plan.Check();
        ADD_FAILURE() << path << " accepted";
      } catch (const std::invalid_argument &e) {
        const std::string message = e.what();
        EXPECT_EQ(message.rfind(std::string(what) + " " + path + ": is ", 0),
                  0u)
            << message;
        EXPECT_NE(message.find("of the run folder"), std::string::npos)
            << message;
      }
    }
  }
  for (const std::string &path : accepted) {
    FilePlan plan;
    plan.Output(path, "--json");
    EXPECT_NO_THROW(plan.Check()) << path;
  }
  // A run's own plan: a case's file may not name a file of its folder that is
  // yet to come.
  for (const std::string &name :
       {"records.shard-1-of-3.jsonl", "records.shard-3-of-3.jsonl.prev"}) {
    FilePlan plan;
    plan.Output("fresh/" + name, "option output_file of case 1", "solver log");
    EXPECT_THROW(
        PlanRunFolder("fresh", "fresh/records.shard-2-of-3.jsonl", 3, &plan),
        std::invalid_argument)
        << name;
  }
  fs::current_path(cwd);
  EXPECT_GE(refused.size(), 60u);
}

// The same through the commands: solve's --json and Ipopt's output file,
// online's, compare's, a suite case's output file naming another shard's
// records yet to be written.
TEST(OutputNeverNamesARunFolder, CommandsRefuseBeforeAnyWork) {
  const std::string dir = testing::FreshDirectory("r4-run-folder-cli");
  testing::WriteText(dir + "/suite.json", QuickSuite(3));
  ASSERT_EQ(
      RunOcpbenchProgram({"run", "suite.json", "--out", "runs"}, dir).exit_code,
      0);
  ASSERT_EQ(RunOcpbenchProgram(
                {"run", "suite.json", "--out", "sweep", "--shard", "2/3"}, dir)
                .exit_code,
            0);
  fs::create_symlink("runs", dir + "/runs-link");
  const std::vector<std::string> solve = {
      "solve",    "--problem", "double-integrator",
      "--solver", "ipopt",     "--transcription",
      "euler",    "--N",       "10"};
  std::vector<std::vector<std::string>> commands;
  for (const std::string &target :
       {"runs/records.jsonl", "./runs/../runs/records.jsonl.prev",
        "runs-link/summary.md", "sweep/records.shard-1-of-3.jsonl"}) {
    std::vector<std::string> a = solve;
    a.insert(a.end(), {"--json", target});
    commands.push_back(a);
    std::vector<std::string> b = solve;
    b.insert(b.end(), {"--option", "output_file=" + target});
    commands.push_back(b);
  }
  commands.push_back({"online", "--problem", "comm-path2d", "--solver", "ipopt",
                      "--option", "output_file=runs/records.jsonl"});
  commands.push_back({"compare", "runs/records.jsonl",
                      "sweep/records.shard-2-of-3.jsonl", "--json",
                      "runs-link/records.csv"});
  commands.push_back(
      {"channel", "simulate", "--no-files", "--json", "sweep/shards.json"});
  // A case's output file naming the records of a shard yet to run.
  testing::WriteText(
      dir + "/logs.json",
      R"({"name": "r4", "groups": [{"problem": "double-integrator", "N": 10, "seeds": [1, 2, 3],)"
      R"( "methods": [{"solver": "ipopt", "transcription": "euler", "options": )"
      R"({"output_file": "sweep/records.shard-3-of-3.jsonl"}}]}]})");
  const auto before = Snapshot(dir);
  for (const auto &args : commands) {
    const ProgramRun run = RunOcpbenchProgram(args, dir);
    std::string line;
    for (const std::string &a : args)
      line += a + " ";
    EXPECT_EQ(run.exit_code, 2) << line << ": " << run.err;
    EXPECT_TRUE(OneErrorLine(run)) << line << ": " << run.err;
    EXPECT_NE(run.err.find("of the run folder"), std::string::npos)
        << line << ": " << run.err;
  }
  for (const bool check : {false, true}) {
    std::vector<std::string> args = {"run",   "logs.json", "--out",
                                     "sweep", "--shard",   "1/3"};
    if (check)
      args.push_back("--check");
    const ProgramRun run = RunOcpbenchProgram(args, dir);
    EXPECT_EQ(run.exit_code, 2) << run.err;
    EXPECT_TRUE(OneErrorLine(run)) << run.err;
    EXPECT_NE(run.err.find("option output_file of case 1"), std::string::npos)
        << run.err;
  }
  EXPECT_EQ(Snapshot(dir), before);
  EXPECT_FALSE(fs::exists(dir + "/sweep/records.shard-3-of-3.jsonl"));
}

// ---- online: the horizon check every solving command makes
// -----------------------------------

TEST(OnlineHorizon, AHorizonItsGridCannotSpanIsRefusedNamingTf) {
  const std::string dir = testing::FreshDirectory("r4-online-horizon");
  int tried = 0;
  for (const char *tf : {"4.9e-324", "1e-310", "2.2e-308"}) {
    for (const char *solver : {"hamiltonian", "ipopt"}) {
      const ProgramRun run = RunOcpbenchProgram(
          {"online", "--problem", "comm-path2d", "--solver", solver, "--set",
           std::string("tf=") + tf, "--json", "o.json"},
          dir);
      EXPECT_EQ(run.exit_code, 2) << tf << ": " << run.err;
      EXPECT_TRUE(OneErrorLine(run)) << run.err;
      EXPECT_NE(run.err.find("tf: the horizon"), std::string::npos)
          << tf << ": " << run.err;
      ++tried;
    }
  }
  EXPECT_FALSE(fs::exists(dir + "/o.json"));
  EXPECT_GE(tried, 6);
}

} // namespace round4
} // namespace ocpb
