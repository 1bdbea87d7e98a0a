// End-to-end: what a record says beyond its status (warnings, the stopping tolerance), warm
// starts from a previous record's states and costates, and the penalty-to-hard continuation.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/cli/run_ocpbench.h"

namespace ocpb {
namespace {

using nlohmann::json;
using testing::ProgramRun;
using testing::RunOcpbenchProgram;

json SolveTo(const std::string& dir,
             const std::string& file,
             std::vector<std::string> args,
             int expected_exit = 0) {
  args.insert(args.begin(), "solve");
  args.insert(args.end(), {"--json", file});
  const ProgramRun run = RunOcpbenchProgram(args, dir);
  EXPECT_EQ(run.exit_code, expected_exit) << run.err << run.out;
  return json::parse(testing::ReadText(dir + "/" + file));
}

std::vector<std::string> WarningCodes(const json& record) {
  std::vector<std::string> codes;
  for (const json& w : record["warnings"]) codes.push_back(w["code"].get<std::string>());
  return codes;
}

// The indirect method converges on its discrete problem at N = 2, whose controls really cost
// 7x more (measured J fine 114.2 against its own 15.76): the record and the report say so.
TEST(JudgedRecords, ACoarseGridsConvergedAnswerCarriesADiscretizationWarning) {
  const std::string dir = testing::FreshDirectory("judged-coarse");
  const ProgramRun run = RunOcpbenchProgram({"solve",
                                             "--problem",
                                             "double-integrator",
                                             "--solver",
                                             "indirect-newton",
                                             "--N",
                                             "2",
                                             "--json",
                                             "coarse.json"},
                                            dir);
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("warning (discretization)"), std::string::npos) << run.out;
  const json r = json::parse(testing::ReadText(dir + "/coarse.json"));
  EXPECT_EQ(r["status"], "converged");
  EXPECT_EQ(WarningCodes(r), std::vector<std::string>{"discretization"});
  EXPECT_GT(r["discretization_gap"].get<double>(), 0.5);
  EXPECT_EQ(r["stopping_tolerance"]["option"], "tolerance");
  EXPECT_EQ(r["stopping_tolerance"]["value"], 1e-10);
  // On its default grid (N = 100) the same method is fine.
  const json fine =
      SolveTo(dir, "fine.json", {"--problem", "double-integrator", "--solver", "indirect-newton"});
  EXPECT_TRUE(fine["warnings"].empty()) << fine["warnings"].dump();
  EXPECT_LT(fine["discretization_gap"].get<double>(), 1e-2);
}

TEST(JudgedRecords, IpoptRecordsNameTolAsTheirAccuracyLimit) {
  const std::string dir = testing::FreshDirectory("judged-tol");
  const json r = SolveTo(dir,
                         "r.json",
                         {"--problem",
                          "hager",
                          "--solver",
                          "ipopt",
                          "--transcription",
                          "lgr",
                          "--option",
                          "tol=1e-10"});
  EXPECT_EQ(r["stopping_tolerance"]["option"], "tol");
  EXPECT_EQ(r["stopping_tolerance"]["value"], 1e-10);
  EXPECT_NE(r["stopping_tolerance"]["note"].get<std::string>().find("large N"), std::string::npos);
}

// The summary shows a row's warnings beside its status, and lists one message per row and code.
TEST(JudgedRecords, TheSummaryShowsWarningsBesideTheStatus) {
  const std::string dir = testing::FreshDirectory("judged-summary");
  testing::WriteText(dir + "/suite.json", R"({"name": "judged", "groups": [
      {"problem": "double-integrator", "N": [2, 100],
       "methods": [{"solver": "indirect-newton"}]}]})");
  const ProgramRun run = RunOcpbenchProgram({"run", "suite.json", "--out", "out"}, dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string md = testing::ReadText(dir + "/out/summary.md");
  EXPECT_NE(md.find("| indirect-newton, penalty, N=2 | 1 | 1 converged | 1 discretization |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| indirect-newton, penalty, N=100 | 1 | 1 converged | - |"), std::string::npos)
      << md;
  EXPECT_NE(md.find("- indirect-newton, penalty, N=2: discretization (1 of 1 cases)"),
            std::string::npos)
      << md;
}

// brachistochrone-free-time: indirect Newton from u = 0 fails (the Hamiltonian is singular in u
// there), and so it does from Ipopt's controls alone; from an Ipopt record's own states and
// costates (trajectory.own) it converges in 2 steps, starting at the record's T.
TEST(JudgedRecords, AWarmStartTakesTheRecordsStatesAndCostates) {
  const std::string dir = testing::FreshDirectory("judged-warm");
  const std::vector<std::string> problem = {
      "--problem", "brachistochrone-free-time", "--terminal", "hard", "--N", "100"};
  auto with = [&](std::vector<std::string> more) {
    std::vector<std::string> args = problem;
    args.insert(args.end(), more.begin(), more.end());
    return args;
  };
  const json ipopt =
      SolveTo(dir, "ipopt.json", with({"--solver", "ipopt", "--transcription", "trapezoid"}));
  ASSERT_EQ(ipopt["status"], "converged");
  ASSERT_TRUE(ipopt["trajectory"].contains("own"));
  EXPECT_EQ(ipopt["trajectory"]["own"]["x"].size(), 3u);  // nx rows
  EXPECT_EQ(ipopt["trajectory"]["own"]["p"].size(), 3u);
  const json warm = SolveTo(
      dir, "warm.json", with({"--solver", "indirect-newton", "--initial-guess", "ipopt.json"}));
  EXPECT_EQ(warm["status"], "converged") << warm["message"];
  EXPECT_LE(warm["iterations"].get<int>(), 3);
  EXPECT_NEAR(warm["final_time"].get<double>(), ipopt["final_time"].get<double>(), 1e-5);
  // The same record without its costates: the start is the controls' (and fails, as from u = 0).
  json controls_only = ipopt;
  controls_only["trajectory"].erase("own");
  testing::WriteText(dir + "/controls.json", controls_only.dump());
  const json cold =
      SolveTo(dir,
              "cold.json",
              with({"--solver", "indirect-newton", "--initial-guess", "controls.json"}),
              /*expected_exit=*/1);
  EXPECT_EQ(cold["status"], "numerical_failure") << cold["message"];
}

TEST(JudgedRecords, AContinuationRecordsBothStages) {
  const std::string dir = testing::FreshDirectory("judged-continuation");
  const json r = SolveTo(dir,
                         "r.json",
                         {"--problem",
                          "zermelo",
                          "--solver",
                          "ipopt",
                          "--transcription",
                          "trapezoid",
                          "--N",
                          "50",
                          "--terminal",
                          "hard",
                          "--continuation",
                          "penalty"});
  EXPECT_EQ(r["status"], "converged") << r["message"];
  ASSERT_TRUE(r.contains("continuation"));
  const json& c = r["continuation"];
  EXPECT_EQ(c["from"], "penalty");
  EXPECT_EQ(c["status"], "converged");
  EXPECT_GT(c["iterations"].get<int>(), 0);
  EXPECT_GT(r["cpu_seconds"].get<double>(), c["cpu_seconds"].get<double>());  // both stages
  EXPECT_NE(r["key"].get<std::string>().find("continuation=penalty"), std::string::npos);
  EXPECT_NE(r["message"].get<std::string>().find("mu_init=0.0001"), std::string::npos)
      << r["message"];  // Ipopt's warm-start option for the hard stage, said
  // The answer is the hard form's: the same optimum as the hard form solved from the default
  // start (its fine terminal miss, 1.7e-3 at N = 50, is the trapezoid's, not the continuation's).
  const json direct = SolveTo(dir,
                              "direct.json",
                              {"--problem",
                               "zermelo",
                               "--solver",
                               "ipopt",
                               "--transcription",
                               "trapezoid",
                               "--N",
                               "50",
                               "--terminal",
                               "hard"});
  ASSERT_EQ(direct["status"], "converged") << direct["message"];
  EXPECT_NEAR(r["J_fine"].get<double>(),
              direct["J_fine"].get<double>(),
              1e-6 * std::abs(direct["J_fine"].get<double>()));
  EXPECT_NEAR(r["terminal_violation_fine"].get<double>(),
              direct["terminal_violation_fine"].get<double>(),
              1e-6);
}

}  // namespace
}  // namespace ocpb
