// End-to-end: solve records of the comm problems carry their controls' energy on the true
// channel and the executed path's geometry (optional fields), and read back through Record.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "bench/cli/record.h"
#include "tests/cli/run_ocpbench.h"

namespace ocpb {
namespace {

using nlohmann::json;
using testing::ProgramRun;
using testing::RunOcpbenchProgram;

json SolveTruthRecord(const std::string& dir,
                      const std::string& file,
                      std::vector<std::string> args) {
  args.insert(args.begin(), "solve");
  args.insert(args.end(), {"--json", file});
  const ProgramRun run = RunOcpbenchProgram(args, dir);
  EXPECT_EQ(run.exit_code, 0) << run.err << run.out;
  return json::parse(testing::ReadText(dir + "/" + file));
}

// A small channel (25 m at 0.25 m, 100 samples) keeps it quick under the sanitizers.
const std::vector<std::string> kSmallComm = {"--set",
                                             "workspace=25",
                                             "--set",
                                             "grid_step=0.25",
                                             "--set",
                                             "samples=100",
                                             "--set",
                                             "S=20,20",
                                             "--set",
                                             "tf=20",
                                             "--set",
                                             "c=75",
                                             "--N",
                                             "100",
                                             "--seed",
                                             "2"};

TEST(TruthRecords, TheBaselineOnTheTrueChannelRoundTrips) {
  const std::string dir = testing::FreshDirectory("truth-baseline");
  std::vector<std::string> args = {"solve", "--problem", "comm-path2d", "--solver", "baseline"};
  args.insert(args.end(), kSmallComm.begin(), kSmallComm.end());
  args.insert(args.end(), {"--json", "b.json"});
  const ProgramRun run = RunOcpbenchProgram(args, dir);
  ASSERT_EQ(run.exit_code, 0) << run.err << run.out;
  EXPECT_NE(run.out.find("on the true channel seed=2"), std::string::npos) << run.out;
  const json r = json::parse(testing::ReadText(dir + "/b.json"));
  EXPECT_EQ(r["status"], "converged");
  EXPECT_EQ(r["solver_status"], "baseline_plan");
  EXPECT_EQ(r["iterations"], 0);
  EXPECT_LT(r["terminal_violation"].get<double>(), 1e-9);
  EXPECT_NEAR(r["final_state"][4].get<double>(), 75.0, 1e-9);
  EXPECT_EQ(r["truth_model"], "true channel seed=2 cells=0.25m");
  const double energy = r["energy_true"].get<double>();
  const double transmit = r["transmit_energy_true"].get<double>();
  EXPECT_GT(transmit, 0.0);
  EXPECT_LT(transmit, energy);
  // At the destination at rest with every bit sent: the penalty is roundoff.
  EXPECT_NEAR(r["J_true"].get<double>(), energy, 1e-9 * energy);
  // The baseline drives the segment S-D; the base (5, 5) is closest at the foot of its
  // perpendicular onto the segment from (20, 20) to (10, 5).
  EXPECT_LT(r["max_distance_from_segment"].get<double>(), 1e-9);
  const Eigen::Vector2d a(20.0, 20.0), b(10.0, 5.0), base(5.0, 5.0);
  const double along = std::clamp((base - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
  const double expected = (base - (a + along * (b - a))).norm();
  EXPECT_NEAR(r["min_distance_to_base"].get<double>(), expected, 0.05);  // 0.2 s steps
  // The fields read back through the record type and are written again unchanged.
  const json again = Record::FromJson(r).ToJson();
  for (const char* key : {"truth_model",
                          "energy_true",
                          "transmit_energy_true",
                          "J_true",
                          "max_distance_from_segment",
                          "min_distance_to_base"}) {
    EXPECT_EQ(again[key], r[key]) << key;
  }
}

TEST(TruthRecords, AnOptimizedPlanAndAFixedPathCarryThemToo) {
  const std::string dir = testing::FreshDirectory("truth-optimized");
  std::vector<std::string> path2d = {
      "--problem", "comm-path2d", "--solver", "ipopt", "--transcription", "euler"};
  path2d.insert(path2d.end(), kSmallComm.begin(), kSmallComm.end());
  const json opt = SolveTruthRecord(dir, "opt.json", path2d);
  // The straight segment S-D as a fixed path (its waypoint on the segment, no fillet).
  std::vector<std::string> fixed = {"--problem",
                                    "comm-fixed-path",
                                    "--solver",
                                    "ipopt",
                                    "--transcription",
                                    "euler",
                                    "--set",
                                    "W=15,12.5",
                                    "--set",
                                    "fillet=0"};
  fixed.insert(fixed.end(), kSmallComm.begin(), kSmallComm.end());
  const json seg = SolveTruthRecord(dir, "seg.json", fixed);
  for (const json* r : {&opt, &seg}) {
    EXPECT_EQ((*r)["status"], "converged") << (*r)["message"];
    EXPECT_GT((*r)["energy_true"].get<double>(), (*r)["transmit_energy_true"].get<double>());
    EXPECT_GE((*r)["J_true"].get<double>(), (*r)["energy_true"].get<double>());
  }
  // A path on the segment stays on it (to roundoff); the co-optimized one leaves it (measured:
  // 5.3e-3 m on this small channel), so the field measures the path, not the segment.
  EXPECT_LT(seg["max_distance_from_segment"].get<double>(), 1e-9);
  EXPECT_GT(opt["max_distance_from_segment"].get<double>(), 1e-4);
  // Problems without a truth have none of the fields.
  const json lqr = SolveTruthRecord(
      dir, "lqr.json", {"--problem", "lqr", "--solver", "ipopt", "--transcription", "euler"});
  EXPECT_FALSE(lqr.contains("energy_true"));
  EXPECT_FALSE(lqr.contains("truth_model"));
}

}  // namespace
}  // namespace ocpb
