// `ocpbench online` and suite entries of kind "online", end to end.
#include <algorithm>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/cli/run_ocpbench.h"

namespace ocpb {
namespace {

using nlohmann::json;
using testing::ProgramRun;
using testing::RunOcpbenchProgram;

// The small scenario of online_replanning_test.cc, as flags.
std::vector<std::string> OnlineArgs(const std::string& solver) {
  // clang-format off
  return {"online", "--problem", "comm-path2d", "--solver", solver, "--seed", "4",
          "--workspace", "25", "--truth-resolution", "0.25",
          "--set", "S=20,20", "--set", "c=75", "--set", "tf=20", "--N", "100",
          "--period", "5", "--initial-measurements", "60", "--per-update", "30"};
  // clang-format on
}

std::vector<std::string> With(std::vector<std::string> args, const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

// OnlineArgs(solver) with the value of `flag` replaced.
std::vector<std::string> Changed(const std::string& flag, const std::string& value) {
  std::vector<std::string> args = OnlineArgs("hamiltonian");
  const auto it = std::find(args.begin(), args.end(), flag);
  if (it == args.end()) return With(args, {flag, value});
  *(it + 1) = value;
  return args;
}

int LineCount(const std::string& s) {
  return static_cast<int>(std::count(s.begin(), s.end(), '\n'));
}

TEST(OnlineCli, JsonRecordHasTheContractFields) {
  const std::string dir = testing::FreshDirectory("online_json");
  for (const std::string solver : {"hamiltonian", "ipopt"}) {
    const std::string path = dir + "/" + solver + ".json";
    const ProgramRun run = RunOcpbenchProgram(With(
        OnlineArgs(solver),
        {"--option", solver == "ipopt" ? "max_iter=200" : "max_iterations=100", "--json", path}));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.out.find("online / offline true energy"), std::string::npos) << run.out;
    const json r = json::parse(testing::ReadText(path));
    EXPECT_EQ(r["kind"], "online");
    EXPECT_EQ(r["seed"], 4);
    EXPECT_EQ(r["solver"], solver);
    // The scenario's settings, with the estimator and placement that were used.
    EXPECT_EQ(r["online"]["estimator"], "binned");
    EXPECT_EQ(r["online"]["placement"], "random");
    if (solver == "ipopt") {
      EXPECT_EQ(r["transcription"], "euler");
    }
    ASSERT_TRUE(r["cycles"].is_array());
    ASSERT_EQ(r["cycles"].size(), 4u);
    double t0 = -1.0;
    for (const json& c : r["cycles"]) {
      for (const char* k : {"t0", "predict_seconds", "solve_seconds", "iterations"}) {
        ASSERT_TRUE(c.contains(k) && c[k].is_number()) << k;
      }
      EXPECT_GT(c["t0"].get<double>(), t0);
      t0 = c["t0"].get<double>();
      EXPECT_EQ(c["plan"]["x"].size(), 2u);
    }
    EXPECT_NEAR(r["cycles"][3]["t0"].get<double>(), 15.0, 1e-12);
    for (const char* k : {"energy_true",
                          "energy_predicted",
                          "offline_energy_true",
                          "terminal_violation",
                          "offline_terminal_violation",
                          "energy_ratio"}) {
      ASSERT_TRUE(r.contains(k) && r[k].is_number()) << k;
    }
    EXPECT_LT(r["terminal_violation"].get<double>(), 1.0);
    EXPECT_EQ(r["executed"]["x"].size(), 5u);
    EXPECT_EQ(r["executed"]["x"][0].size(), 101u);
    EXPECT_EQ(r["measurements"]["x"].size(), 150u);
    EXPECT_EQ(r["s_map"]["log10_s"].size(), r["s_map"]["y"].size());
  }
}

TEST(OnlineCli, BadInputsExitTwoWithOneLine) {
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {Changed("--period", "-10"), "update_period"},
      {Changed("--period", "0.3"), "multiple of the step"},
      {Changed("--per-update", "0"), "measurements_per_update"},
      {Changed("--initial-measurements", "2"), "initial_measurements"},
      {With(OnlineArgs("hamiltonian"), {"--placement", "everywhere"}), "placement"},
      {With(OnlineArgs("hamiltonian"), {"--estimator", "median"}),
       "online option 'estimator': must be one of: binned, ml, reml (got 'median')"},
      {With(OnlineArgs("hamiltonian"), {"--set", "samples=50"}), "samples"},
      {With(OnlineArgs("hamiltonian"), {"--set", "base=45,45"}),
       "base: (45, 45) lies outside the workspace [0, 25]^2"},
      {With(OnlineArgs("hamiltonian"), {"--replan-option", "bogus=1"}), "bogus"},
      {Changed("--per-update", "5000"), "measurements in all"},
      {{"online", "--problem", "double-integrator", "--solver", "hamiltonian"}, "comm-path2d"},
  };
  for (const auto& [args, expected] : cases) {
    const ProgramRun run = RunOcpbenchProgram(args);
    EXPECT_EQ(run.exit_code, 2) << expected << ": " << run.err;
    EXPECT_EQ(LineCount(run.err), 1) << run.err;
    EXPECT_EQ(run.err.rfind("ocpbench: error: ", 0), 0u) << run.err;
    EXPECT_NE(run.err.find(expected), std::string::npos) << run.err;
  }
}

TEST(OnlineCli, SuiteEntriesOfKindOnline) {
  const std::string dir = testing::FreshDirectory("online_suite");
  const std::string suite = R"({"name": "online-small", "groups": [{
      "kind": "online", "problem": "comm-path2d", "seeds": [1, 2], "N": 100,
      "set": {"S": [20, 20], "c": 75, "tf": 20},
      "online": {"update_period": 5, "initial_measurements": 60, "measurements_per_update": 30,
                 "workspace": 25, "truth_resolution": 0.25},
      "keep_trajectory": false,
      "methods": [{"solver": "hamiltonian", "options": {"max_iterations": 60},
                   "replan_options": {"max_iterations": 10}}]}]})";
  testing::WriteText(dir + "/suite.json", suite);
  const ProgramRun run = RunOcpbenchProgram({"run", dir + "/suite.json", "--out", dir + "/out"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::istringstream lines(testing::ReadText(dir + "/out/records.jsonl"));
  std::string line;
  int n = 0;
  while (std::getline(lines, line)) {
    const json r = json::parse(line);
    EXPECT_EQ(r["kind"], "online");
    EXPECT_EQ(r["seed"], n + 1);
    EXPECT_EQ(r["replan_options"]["max_iterations"], "10");
    EXPECT_EQ(r["cycles"].size(), 4u);
    EXPECT_FALSE(r.contains("executed"));
    ++n;
  }
  EXPECT_EQ(n, 2);

  // A bad online setting fails the whole suite before anything runs.
  std::string bad = suite;
  bad.replace(bad.find("\"update_period\": 5"), 18, "\"update_period\": 0");
  testing::WriteText(dir + "/bad.json", bad);
  const ProgramRun bad_run = RunOcpbenchProgram({"run", dir + "/bad.json", "--out", dir + "/bad"});
  EXPECT_EQ(bad_run.exit_code, 2) << bad_run.err;
  EXPECT_NE(bad_run.err.find("update_period"), std::string::npos) << bad_run.err;
}

}  // namespace
}  // namespace ocpb
