// The third round of hostile inputs (issue 41), one class per test, each tried with many
// values: no output of any command names an input or another output (by any spelling: "..",
// "./", symbolic and hard links), no earlier version of a records file is lost, a path or a
// size at fault is exit 2 before any work (never 3), and what the check accepts the solve
// accepts.
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/cli/run_ocpbench.h"

namespace ocpb {
// Named, not anonymous: the unity build puts this file beside reliability_test.cc.
namespace round3 {

namespace fs = std::filesystem;
using nlohmann::json;
using testing::ProgramRun;
using testing::RunOcpbenchProgram;

using testing::OneErrorLine;

const std::vector<std::string> kQuickSolve = {"solve",
                                              "--problem",
                                              "double-integrator",
                                              "--solver",
                                              "hamiltonian",
                                              "--N",
                                              "10",
                                              "--option",
                                              "max_iterations=3"};
const std::vector<std::string>& kQuickIpopt = testing::QuickIpoptSolve();
using testing::Plus;

// A suite of `seeds` quick cases; `options` is the text of the method's options object.
std::string QuickSuite(int seeds, const std::string& solver, const std::string& options) {
  std::string list;
  for (int i = 1; i <= seeds; ++i) list += (i > 1 ? "," : "") + std::to_string(i);
  const std::string transcription =
      solver == "ipopt" ? R"(, "transcription": "euler")" : std::string();
  return R"({"name": "r3", "groups": [{"problem": "double-integrator", "N": 10, "seeds": [)" +
         list + R"(], "methods": [{"solver": ")" + solver + "\"" + transcription +
         R"(, "options": )" + options + "}]}]}";
}

// ---- A. an output over an input, a record lost ------------------------------------------

// Every spelling of one file: as given, "./", "sub/../", a symbolic link, a hard link.
std::vector<std::string> Spellings(const std::string& dir, const std::string& name) {
  fs::create_directories(dir + "/sub");
  const std::string link = dir + "/link-to-" + name;
  const std::string hard = dir + "/hard-" + name;
  fs::remove(link);
  fs::remove(hard);
  fs::create_symlink(name, link);
  fs::create_hard_link(dir + "/" + name, hard);
  fs::create_directories(dir + "/linked-folder-target");
  return {name,
          "./" + name,
          "sub/../" + name,
          dir + "/" + name,
          "link-to-" + name,
          "hard-" + name,
          "sub/./../sub/../" + name};
}

TEST(OutputNeverReplacesInput, SolveAndOnlineOutputsAgainstTheirInputs) {
  const std::string dir = testing::FreshDirectory("r3-solve-outputs");
  // A record to start from (an --initial-guess file).
  ProgramRun made = RunOcpbenchProgram(Plus(kQuickSolve, {"--json", "guess.json"}), dir);
  ASSERT_EQ(made.exit_code, 0) << made.err;
  int tried = 0;
  for (const std::string& spelling : Spellings(dir, "guess.json")) {
    const auto before = testing::SnapshotFiles(dir);
    // Ipopt's own output file naming the --initial-guess file.
    ProgramRun run = RunOcpbenchProgram(
        Plus(kQuickIpopt, {"--initial-guess", "guess.json", "--option", "output_file=" + spelling}),
        dir);
    EXPECT_EQ(run.exit_code, 2) << spelling << ": " << run.err;
    EXPECT_TRUE(OneErrorLine(run)) << run.err;
    EXPECT_NE(run.err.find("is also --initial-guess"), std::string::npos) << run.err;
    // --json naming the --initial-guess file.
    run = RunOcpbenchProgram(
        Plus(kQuickSolve, {"--initial-guess", "guess.json", "--json", spelling}), dir);
    EXPECT_EQ(run.exit_code, 2) << spelling << ": " << run.err;
    EXPECT_NE(run.err.find("an output never replaces an input"), std::string::npos) << run.err;
    // --json and Ipopt's output file naming one file.
    run = RunOcpbenchProgram(
        Plus(kQuickIpopt, {"--json", "guess.json", "--option", "output_file=" + spelling}), dir);
    EXPECT_EQ(run.exit_code, 2) << spelling << ": " << run.err;
    EXPECT_NE(run.err.find("two outputs in one file"), std::string::npos) << run.err;
    // online: --json and the solver's output file (of every solve, or of the re-plans).
    for (const char* flag : {"--option", "--replan-option"}) {
      run = RunOcpbenchProgram({"online",
                                "--problem",
                                "comm-path2d",
                                "--solver",
                                "ipopt",
                                "--json",
                                "guess.json",
                                flag,
                                "output_file=" + spelling},
                               dir);
      EXPECT_EQ(run.exit_code, 2) << flag << " " << spelling << ": " << run.err;
      EXPECT_NE(run.err.find("two outputs in one file"), std::string::npos) << run.err;
      ++tried;
    }
    EXPECT_EQ(testing::SnapshotFiles(dir), before) << spelling;
    tried += 3;
  }
  EXPECT_GE(tried, 30);
  // Distinct files stay accepted: the output file is written, the guess is read.
  const ProgramRun ok = RunOcpbenchProgram(Plus(kQuickIpopt,
                                                {"--initial-guess",
                                                 "guess.json",
                                                 "--option",
                                                 "output_file=ipopt.log",
                                                 "--json",
                                                 "new.json"}),
                                           dir);
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_TRUE(fs::exists(dir + "/ipopt.log"));
}

TEST(OutputNeverReplacesInput, RunAndMergeNeverWriteOverTheSuiteFile) {
  const std::string dir = testing::FreshDirectory("r3-run-suite");
  const std::string suite = QuickSuite(2, "hamiltonian", R"({"max_iterations": 3})");
  testing::WriteText(dir + "/suite.json", suite);
  int tried = 0;
  for (const std::string& spelling : Spellings(dir, "suite.json")) {
    const auto before = testing::SnapshotFiles(dir);
    // run SUITE --out DIR with the suite in DIR (run writes DIR/suite.json).
    for (const std::vector<std::string>& extra :
         std::vector<std::vector<std::string>>{{}, {"--check"}, {"--overwrite"}}) {
      const ProgramRun run = RunOcpbenchProgram(Plus({"run", spelling, "--out", "."}, extra), dir);
      EXPECT_EQ(run.exit_code, 2) << spelling << ": " << run.err;
      EXPECT_TRUE(OneErrorLine(run)) << run.err;
      EXPECT_NE(run.err.find("is also the suite file"), std::string::npos) << run.err;
      ++tried;
    }
    EXPECT_EQ(testing::SnapshotFiles(dir), before) << spelling;
  }
  // merge DIR --suite DIR/suite.json: the shards ran from a copy of the suite.
  testing::WriteText(dir + "/elsewhere.json", suite);
  for (const char* shard : {"1/2", "2/2"}) {
    const ProgramRun run =
        RunOcpbenchProgram({"run", "elsewhere.json", "--out", "sweep", "--shard", shard}, dir);
    ASSERT_EQ(run.exit_code, 0) << run.err;
  }
  fs::copy_file(dir + "/suite.json", dir + "/sweep/suite.json");
  for (const std::string& spelling : Spellings(dir + "/sweep", "suite.json")) {
    const auto before = testing::SnapshotFiles(dir);
    const std::string given = spelling[0] == '/' ? spelling : "sweep/" + spelling;
    const ProgramRun run = RunOcpbenchProgram({"merge", "sweep", "--suite", given}, dir);
    EXPECT_EQ(run.exit_code, 2) << spelling << ": " << run.err;
    EXPECT_TRUE(OneErrorLine(run)) << run.err;
    EXPECT_NE(run.err.find("is also --suite"), std::string::npos) << run.err;
    EXPECT_EQ(testing::SnapshotFiles(dir), before) << spelling;
    ++tried;
  }
  EXPECT_GE(tried, 25);
}

TEST(OutputNeverReplacesInput, SolverLogsOfASuiteNeverNameTheRunsFiles) {
  const std::string dir = testing::FreshDirectory("r3-run-logs");
  // A sharded folder with another shard's records already there, and an unsharded one with
  // an earlier run's files.
  testing::WriteText(dir + "/shards.suite.json",
                     QuickSuite(2, "ipopt", R"({"output_file": "ok.log"})"));
  ProgramRun shard = RunOcpbenchProgram(
      {"run", "shards.suite.json", "--out", "out-sharded", "--shard", "2/2"}, dir);
  ASSERT_EQ(shard.exit_code, 0) << shard.err;
  fs::create_directories(dir + "/out-sharded/sub");
  fs::create_directories(dir + "/out");
  const std::vector<std::pair<std::string, std::string>> kTargets = {
      // the output file, the run's --out folder (and its --shard)
      {"out/records.jsonl", "out"},
      {"out/./records.jsonl", "out"},
      {"out/summary.md", "out"},
      {"out/records.csv", "out"},
      {"out/derived.jsonl", "out"},
      {"out/suite.json", "out"},
      {"out/records.jsonl.prev", "out"},
      {"suite.json", "out"},
      {"./suite.json", "out"},
      {"out/../suite.json", "out"},
      {"out-sharded/records.shard-1-of-2.jsonl", "out-sharded"},
      {"out-sharded/records.shard-2-of-2.jsonl", "out-sharded"},
      {"out-sharded/shards.json", "out-sharded"},
      {"out-sharded/sub/../records.shard-2-of-2.jsonl", "out-sharded"},
      {"out-sharded/records.shard-1-of-2.jsonl.prev", "out-sharded"},
      {"suite.json", "out-sharded"},
  };
  int tried = 0;
  for (const auto& [target, out] : kTargets) {
    for (const bool check : {false, true}) {
      testing::WriteText(dir + "/suite.json",
                         QuickSuite(2, "ipopt", R"({"output_file": ")" + target + "\"}"));
      const auto before = testing::SnapshotFiles(dir);
      std::vector<std::string> args = {"run", "suite.json", "--out", out};
      if (out == "out-sharded") args.insert(args.end(), {"--shard", "1/2"});
      if (check) args.push_back("--check");
      const ProgramRun run = RunOcpbenchProgram(args, dir);
      EXPECT_EQ(run.exit_code, 2) << target << ": " << run.err;
      EXPECT_TRUE(OneErrorLine(run)) << run.err;
      EXPECT_NE(run.err.find("option output_file of case 1"), std::string::npos) << run.err;
      EXPECT_EQ(testing::SnapshotFiles(dir), before) << target;
      ++tried;
    }
  }
  EXPECT_GE(tried, 32);
}

TEST(OutputNeverReplacesInput, ChannelOutputsNeverNameOneFile) {
  const std::string dir = testing::FreshDirectory("r3-channel");
  const std::vector<std::string> kWays = {
      "maps/predict.json", "./maps/predict.json", "maps/../maps/predict.json"};
  for (const std::string& json_path : kWays) {
    const ProgramRun run =
        RunOcpbenchProgram({"channel", "predict", "--out", "maps", "--json", json_path}, dir);
    EXPECT_EQ(run.exit_code, 2) << json_path << ": " << run.err;
    EXPECT_NE(run.err.find("two outputs in one file"), std::string::npos) << run.err;
  }
  const ProgramRun run = RunOcpbenchProgram(
      {"channel", "simulate", "--out", "maps", "--json", "maps/simulate.json"}, dir);
  EXPECT_EQ(run.exit_code, 2) << run.err;
}

// Each merge keeps the records file it replaces (records.jsonl.prev the latest,
// records.jsonl.1.prev, ... the older ones), and a merge that changes nothing keeps no copy; `run
// --overwrite` the same.
TEST(NoRecordLost, EveryMergeAndOverwriteKeepsEachEarlierVersion) {
  const std::string dir = testing::FreshDirectory("r3-versions");
  testing::WriteText(dir + "/suite.json", QuickSuite(3, "hamiltonian", R"({"max_iterations": 3})"));
  for (const char* shard : {"1/2", "2/2"}) {
    ASSERT_EQ(
        RunOcpbenchProgram({"run", "suite.json", "--out", "d", "--shard", shard}, dir).exit_code,
        0);
  }
  ASSERT_EQ(RunOcpbenchProgram({"merge", "d"}, dir).exit_code, 0);
  const std::string merged = testing::ReadText(dir + "/d/records.jsonl");
  std::vector<std::string> versions;
  for (int i = 0; i < 6; ++i) {
    // Records written into records.jsonl between merges (a resumed unsharded run, a user).
    std::string changed = merged;
    changed.insert(0, std::string(static_cast<size_t>(i + 1), '\n'));
    testing::WriteText(dir + "/d/records.jsonl", changed);
    versions.push_back(changed);
    const ProgramRun run = RunOcpbenchProgram({"merge", "d"}, dir);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_EQ(testing::ReadText(dir + "/d/records.jsonl"), merged);
  }
  // The latest earlier version is .prev, the older ones .1.prev, .2.prev, ... oldest first.
  EXPECT_EQ(testing::ReadText(dir + "/d/records.jsonl.prev"), versions.back());
  for (size_t k = 1; k < versions.size(); ++k) {
    const std::string older = dir + "/d/records.jsonl." + std::to_string(k) + ".prev";
    ASSERT_TRUE(fs::exists(older)) << older;
    EXPECT_EQ(testing::ReadText(older), versions[k - 1]) << k;
  }
  // A merge that changes nothing keeps no copy.
  const auto before = testing::SnapshotFiles(dir + "/d");
  ASSERT_EQ(RunOcpbenchProgram({"merge", "d"}, dir).exit_code, 0);
  EXPECT_EQ(testing::SnapshotFiles(dir + "/d").size(), before.size());

  // run --overwrite, repeated: every earlier records file stays.
  for (int i = 0; i < 4; ++i) {
    const ProgramRun run =
        RunOcpbenchProgram({"run", "suite.json", "--out", "o", "--overwrite"}, dir);
    ASSERT_EQ(run.exit_code, 0) << run.err;
  }
  EXPECT_TRUE(fs::exists(dir + "/o/records.jsonl.prev"));
  EXPECT_TRUE(fs::exists(dir + "/o/records.jsonl.1.prev"));
  EXPECT_TRUE(fs::exists(dir + "/o/records.jsonl.2.prev"));
  EXPECT_FALSE(fs::exists(dir + "/o/records.jsonl.3.prev"));
}

// ---- B. exit 3 where input is at fault -----------------------------------------------------

TEST(InputAtFaultIsExitTwo, SymbolicLinkLoopsAnywhere) {
  const std::string dir = testing::FreshDirectory("r3-loops");
  fs::create_symlink("loop-b", dir + "/loop-a");
  fs::create_symlink("loop-a", dir + "/loop-b");
  fs::create_symlink("self", dir + "/self");
  testing::WriteText(dir + "/suite.json", QuickSuite(1, "hamiltonian", R"({"max_iterations": 3})"));
  ProgramRun made = RunOcpbenchProgram(Plus(kQuickSolve, {"--json", "rec.json"}), dir);
  ASSERT_EQ(made.exit_code, 0) << made.err;
  testing::WriteText(dir + "/rec.jsonl",
                     json::parse(testing::ReadText(dir + "/rec.json")).dump() + "\n");
  int tried = 0;
  for (const std::string& loop :
       std::vector<std::string>{"loop-a", "self", "loop-b/x", "self/records.jsonl"}) {
    const std::vector<std::vector<std::string>> kCommands = {
        Plus(kQuickSolve, {"--json", loop}),
        Plus(kQuickSolve, {"--initial-guess", loop}),
        Plus(kQuickIpopt, {"--option", "output_file=" + loop}),
        {"run", loop},
        {"run", "suite.json", "--out", loop},
        {"run", "suite.json", "--out", loop, "--check"},
        {"run", "suite.json", "--out", loop, "--shard", "1/2"},
        {"merge", loop},
        {"merge", loop, "--suite", "suite.json"},
        {"status", loop},
        {"status", loop, "--suite", "suite.json"},
        {"compare", loop, "rec.jsonl"},
        {"compare", "rec.jsonl", loop},
        {"compare", "rec.jsonl", "rec.jsonl", "--json", loop},
        {"compare", "rec.jsonl", "rec.jsonl", "--markdown", loop},
        {"channel", "simulate", "--out", loop},
        {"channel", "simulate", "--no-files", "--json", loop},
        {"online", "--problem", "comm-path2d", "--solver", "hamiltonian", "--json", loop},
    };
    for (const auto& args : kCommands) {
      const ProgramRun run = RunOcpbenchProgram(args, dir);
      std::string line;
      for (const std::string& a : args) line += a + " ";
      EXPECT_EQ(run.exit_code, 2) << line << ": " << run.err;
      EXPECT_TRUE(OneErrorLine(run)) << line << ": " << run.err;
      ++tried;
    }
  }
  EXPECT_GE(tried, 70);
}

TEST(InputAtFaultIsExitTwo, ShardCountsBeyondTheLimit) {
  const std::string dir = testing::FreshDirectory("r3-shards");
  testing::WriteText(dir + "/suite.json", QuickSuite(1, "hamiltonian", R"({"max_iterations": 3})"));
  int tried = 0;
  for (const std::string& n :
       std::vector<std::string>{"100001", "999999999", "2147483647", "1000000"}) {
    ProgramRun run = RunOcpbenchProgram({"run", "suite.json", "--shard", "1/" + n}, dir);
    EXPECT_EQ(run.exit_code, 2) << n << ": " << run.err;
    // More than 9 digits is no shard count at all.
    EXPECT_NE(run.err.find(n.size() > 9 ? "--shard '1/" : "at most 100000 shards"),
              std::string::npos)
        << run.err;
    // A records file whose name says so, in a folder given to status and merge.
    const std::string sweep = dir + "/sweep-" + n;
    fs::create_directories(sweep);
    testing::WriteText(sweep + "/records.shard-1-of-" + n + ".jsonl", "");
    for (const char* command : {"status", "merge"}) {
      run = RunOcpbenchProgram({command, sweep, "--suite", "suite.json"}, dir);
      EXPECT_EQ(run.exit_code, 2) << command << " " << n << ": " << run.err;
      EXPECT_TRUE(OneErrorLine(run)) << run.err;
      ++tried;
    }
    // A shards.json that says so.
    const std::string manifest = dir + "/manifest-" + n;
    fs::create_directories(manifest);
    testing::WriteText(
        manifest + "/shards.json",
        R"({"shards": )" + n +
            R"(, "cases": 1, "suite_name": "r3", "suite_source": "x", "suite": {}})");
    testing::WriteText(manifest + "/records.shard-1-of-2.jsonl", "");
    run = RunOcpbenchProgram({"status", manifest}, dir);
    EXPECT_EQ(run.exit_code, 2) << n << ": " << run.err;
    tried += 2;
  }
  EXPECT_GE(tried, 16);
}

TEST(InputAtFaultIsExitTwo, SizesMeetAMemoryEstimateBeforeAnyWork) {
  const std::string dir = testing::FreshDirectory("r3-sizes");
  struct Case {
    std::vector<std::string> args;
    std::string field;
  };
  const std::vector<std::string> hs = {"solve",
                                       "--problem",
                                       "double-integrator",
                                       "--solver",
                                       "ipopt",
                                       "--transcription",
                                       "hermite-simpson",
                                       "--N",
                                       "10",
                                       "--option",
                                       "mesh_tolerance=1e-8"};
  std::vector<Case> cases;
  for (const char* points : {"100000000", "2147483647", "1000000000", "2001"}) {
    cases.push_back({Plus(hs, {"--option", std::string("mesh_max_new_points=") + points}),
                     "mesh_max_new_points"});
  }
  // Within the rule mesh_max_new_points <= mesh_max_nodes, the refined mesh's own estimate.
  for (const char* nodes : {"50000", "100000"}) {
    cases.push_back({Plus(hs,
                          {"--option",
                           std::string("mesh_max_nodes=") + nodes,
                           "--option",
                           std::string("mesh_max_new_points=") + nodes}),
                     "mesh_max_new_points"});
  }
  cases.push_back({Plus(hs, {"--option", "mesh_max_nodes=2147483647"}), "mesh_max_nodes"});
  cases.push_back({Plus(hs, {"--option", "mesh_max_nodes=100000000"}), "mesh_max_nodes"});
  for (const char* n : {"100000000", "2147483647", "500000000"}) {
    cases.push_back({{"online", "--problem", "comm-path2d", "--solver", "ipopt", "--N", n}, "N"});
    cases.push_back(
        {{"online", "--problem", "comm-path2d", "--solver", "hamiltonian", "--N", n}, "N"});
  }
  // An iteration limit the Hamiltonian descent reserves its history for.
  for (const char* limit : {"2147483647", "1000000000", "300000000"}) {
    cases.push_back({{"solve",
                      "--problem",
                      "double-integrator",
                      "--solver",
                      "hamiltonian",
                      "--N",
                      "10",
                      "--option",
                      std::string("max_iterations=") + limit},
                     "max_iterations"});
    cases.push_back({{"online",
                      "--problem",
                      "comm-path2d",
                      "--solver",
                      "hamiltonian",
                      "--option",
                      std::string("max_iterations=") + limit},
                     "max_iterations"});
    cases.push_back({{"online",
                      "--problem",
                      "comm-path2d",
                      "--solver",
                      "hamiltonian",
                      "--replan-option",
                      std::string("max_iterations=") + limit},
                     "max_iterations"});
  }
  for (const char* tf : {"4.9e-324", "1e-310", "2.2e-308", "1e-320"}) {
    cases.push_back({Plus(kQuickSolve, {"--set", std::string("tf=") + tf}), "tf"});
    cases.push_back({Plus(kQuickIpopt, {"--set", std::string("tf=") + tf}), "tf"});
  }
  for (const Case& c : cases) {
    const ProgramRun run = RunOcpbenchProgram(c.args, dir);
    std::string line;
    for (const std::string& a : c.args) line += a + " ";
    EXPECT_EQ(run.exit_code, 2) << line << ": " << run.err;
    EXPECT_TRUE(OneErrorLine(run)) << line << ": " << run.err;
    EXPECT_NE(run.err.find(c.field + ":"), std::string::npos) << line << ": " << run.err;
    EXPECT_EQ(run.err.find("time grid"), std::string::npos) << run.err;
  }
  EXPECT_GE(cases.size(), 18u);
}

// The suite's memory estimate counts what `run` holds of a record (its fields and history),
// not 4 MB a record: thousands of small cases are accepted.
TEST(InputAtFaultIsExitTwo, ThousandsOfSmallCasesFitTheSuiteEstimate) {
  const std::string dir = testing::FreshDirectory("r3-many");
  testing::WriteText(dir + "/suite.json",
                     QuickSuite(4000, "hamiltonian", R"({"max_iterations": 3})"));
  const ProgramRun run = RunOcpbenchProgram({"run", "suite.json", "--check"}, dir);
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("4000 cases"), std::string::npos) << run.err;
}

// ---- C. what the check accepts, the solve accepts; one rule everywhere ------------------------

TEST(ConsistentAcceptance, IpoptJointRulesRefusedUpFront) {
  const std::string dir = testing::FreshDirectory("r3-ipopt-joint");
  const std::vector<std::vector<std::string>> kBad = {
      {"mumps_pivtol=0.5", "mumps_pivtolmax=0.1"},
      {"mumps_pivtolmax=1e-7"},  // below the default mumps_pivtol 1e-6
      {"mumps_pivtol=1e-3", "mumps_pivtolmax=1e-4"},
      {"min_refinement_steps=5", "max_refinement_steps=2"},
      {"min_refinement_steps=11"},  // above the default max_refinement_steps 10
      {"max_refinement_steps=0"},   // below the default min_refinement_steps 1
      {"min_refinement_steps=100", "max_refinement_steps=99"},
      // mehrotra_algorithm=yes needs mu_strategy=adaptive (OCPBench's default is monotone), and
      // refuses other settings of two options Ipopt would otherwise set itself.
      {"mehrotra_algorithm=yes"},
      {"mehrotra_algorithm=yes", "mu_strategy=monotone"},
      {"mehrotra_algorithm=yes", "mu_strategy=adaptive", "corrector_type=affine"},
      {"mehrotra_algorithm=yes", "mu_strategy=adaptive", "adaptive_mu_globalization=kkt-error"},
  };
  int tried = 0;
  for (const auto& options : kBad) {
    std::vector<std::string> args = kQuickIpopt;
    std::string options_json = "{";
    for (const std::string& o : options) {
      args.insert(args.end(), {"--option", o});
      const auto eq = o.find('=');
      const std::string value = o.substr(eq + 1);
      const bool text = value.find_first_not_of("0123456789.e-+") != std::string::npos;
      options_json += (options_json.size() > 1 ? ", \"" : "\"") + o.substr(0, eq) +
                      "\": " + (text ? "\"" + value + "\"" : value);
    }
    options_json += "}";
    ProgramRun run = RunOcpbenchProgram(args, dir);
    EXPECT_EQ(run.exit_code, 2) << options[0] << ": " << run.err;
    EXPECT_NE(run.err.find("Ipopt's rule"), std::string::npos) << run.err;
    testing::WriteText(dir + "/suite.json", QuickSuite(1, "ipopt", options_json));
    run = RunOcpbenchProgram({"run", "suite.json", "--check"}, dir);
    EXPECT_EQ(run.exit_code, 2) << options_json << ": " << run.err;
    EXPECT_NE(run.err.find("Ipopt's rule"), std::string::npos) << run.err;
    tried += 2;
  }
  // Within the rules, the solve runs. mumps_pivtol above the default mumps_pivtolmax with
  // mumps_pivtolmax unset is within them: Ipopt then raises mumps_pivtolmax to mumps_pivtol.
  const ProgramRun ok = RunOcpbenchProgram(Plus(kQuickIpopt,
                                                {"--option",
                                                 "mumps_pivtol=1e-4",
                                                 "--option",
                                                 "mumps_pivtolmax=1e-2",
                                                 "--option",
                                                 "min_refinement_steps=2",
                                                 "--option",
                                                 "max_refinement_steps=2"}),
                                           dir);
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  const ProgramRun raised =
      RunOcpbenchProgram(Plus(kQuickIpopt, {"--option", "mumps_pivtol=0.2"}), dir);
  EXPECT_EQ(raised.exit_code, 0) << raised.err;
  const ProgramRun mehrotra = RunOcpbenchProgram(Plus(kQuickIpopt,
                                                      {"--option",
                                                       "mehrotra_algorithm=yes",
                                                       "--option",
                                                       "mu_strategy=adaptive",
                                                       "--json",
                                                       "m.json"}),
                                                 dir);
  EXPECT_NE(mehrotra.exit_code, 2) << mehrotra.err;
  EXPECT_NE(json::parse(testing::ReadText(dir + "/m.json")).at("solver_status"), "Invalid_Option");
  // An output file whose name the file system cannot hold is refused up front too.
  const std::string long_name(300, 'x');
  for (const std::string& path :
       {long_name, "sub/" + long_name + "/log", "no-such-folder/" + long_name}) {
    const ProgramRun run =
        RunOcpbenchProgram(Plus(kQuickIpopt, {"--option", "output_file=" + path}), dir);
    EXPECT_EQ(run.exit_code, 2) << run.err;
    EXPECT_NE(run.err.find("output_file"), std::string::npos) << run.err;
    ++tried;
  }
  EXPECT_GE(tried, 25);
}

TEST(ConsistentAcceptance, DegreeIsAnOptionOfLgr) {
  const std::string dir = testing::FreshDirectory("r3-degree");
  const std::vector<std::string> lgr = {"solve",
                                        "--problem",
                                        "double-integrator",
                                        "--solver",
                                        "ipopt",
                                        "--transcription",
                                        "lgr",
                                        "--N",
                                        "4"};
  for (const char* degree : {"2", "4", "5"}) {
    const ProgramRun run = RunOcpbenchProgram(
        Plus(lgr, {"--option", std::string("degree=") + degree, "--json", "r.json"}), dir);
    ASSERT_EQ(run.exit_code, 0) << degree << ": " << run.err;
    EXPECT_EQ(json::parse(testing::ReadText(dir + "/r.json")).at("degree").get<int>(),
              std::stoi(degree));
    // The same degree twice agrees; two different degrees are refused.
    EXPECT_EQ(RunOcpbenchProgram(
                  Plus(lgr, {"--degree", degree, "--option", std::string("degree=") + degree}), dir)
                  .exit_code,
              0);
    const ProgramRun both = RunOcpbenchProgram(
        Plus(lgr, {"--degree", "3", "--option", std::string("degree=") + degree}), dir);
    EXPECT_EQ(both.exit_code, degree == std::string("3") ? 0 : 2) << both.err;
  }
}

TEST(ConsistentAcceptance, OneClearLineForEachFlagAndValue) {
  const std::string dir = testing::FreshDirectory("r3-flags");
  testing::WriteText(dir + "/suite.json", QuickSuite(2, "hamiltonian", R"({"max_iterations": 3})"));
  ProgramRun made = RunOcpbenchProgram(Plus(kQuickSolve, {"--json", "rec.json"}), dir);
  ASSERT_EQ(made.exit_code, 0) << made.err;
  struct Case {
    std::vector<std::string> args;
    std::string expected;
  };
  std::vector<Case> cases;
  for (const char* jobs : {"abc", "", "1.5", "0", "257", "1e3", " 2", "0x10", "99999999999"}) {
    cases.push_back({{"run", "suite.json", "--jobs", jobs}, "must be an integer from 1 to 256"});
  }
  for (const char* shard : {"", " ", "/", "1/", "/2", "1/100001"}) {
    cases.push_back({{"run", "suite.json", "--shard", shard}, "--shard '"});
  }
  for (const char* extra : {"extra", "x", "comm-path2d"}) {
    cases.push_back({{"describe", "online", extra}, "takes no name"});
    cases.push_back({{"describe", "compare", extra}, "takes no name"});
  }
  const std::string rec = json::parse(testing::ReadText(dir + "/rec.json")).dump();
  testing::WriteText(dir + "/rec.jsonl", rec + "\n");
  cases.push_back({{"compare", "", "rec.jsonl"}, "BASE '': an empty path"});
  cases.push_back({{"compare", "rec.jsonl", ""}, "NEW '': an empty path"});
  const std::vector<std::string> solve = {
      "solve", "--problem", "double-integrator", "--solver", "hamiltonian"};
  for (const char* n : {"abc", "1.5", "ten"}) {
    cases.push_back({Plus(solve, {"--N", n}), "--N '"});
    cases.push_back({Plus(solve, {"--repeats", n}), "--repeats '"});
    cases.push_back({Plus(solve, {"--degree", n}), "--degree '"});
  }
  for (const char* threads : {"100000", "257", "-1", "2147483647"}) {
    cases.push_back({{"channel", "predict", "--threads", threads}, "--threads"});
  }
  // compare: statuses outside the schema's list.
  for (const char* status : {"ok", "Converged", "success", "", "converged "}) {
    json j = json::parse(rec);
    j["status"] = status;
    const std::string name = std::string("status-") + std::to_string(cases.size()) + ".jsonl";
    testing::WriteText(dir + "/" + name, j.dump() + "\n");
    cases.push_back({{"compare", "rec.jsonl", name}, "status: must be one of converged"});
  }
  for (const Case& c : cases) {
    const ProgramRun run = RunOcpbenchProgram(c.args, dir);
    std::string line;
    for (const std::string& a : c.args) line += "'" + a + "' ";
    EXPECT_EQ(run.exit_code, 2) << line << ": " << run.err;
    EXPECT_TRUE(OneErrorLine(run)) << line << ": " << run.err;
    EXPECT_NE(run.err.find(c.expected), std::string::npos) << line << ": " << run.err;
    EXPECT_EQ(run.err.find("Could not convert"), std::string::npos) << run.err;
  }
  EXPECT_GE(cases.size(), 40u);
  EXPECT_FALSE(fs::exists(dir + "/results"));
}

}  // namespace round3
}  // namespace ocpb
