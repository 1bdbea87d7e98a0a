// One mechanism prices plans on the true channel: the offline records' judge
// (ProblemInfo::judge_on_truth of the comm problems) and the online driver agree exactly.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/evaluator.h"
#include "drivers/online/online_replanning.h"
#include "problems/comm_path2d.h"
#include "problems/comm_true_energy.h"
#include "problems/registry.h"
#include "tests/online/small_online_problem.h"

namespace ocpb {
namespace {

// The small scenario of online_replanning_test.cc (25 m at 0.25 m, tf = 20 s, N = 100) and the
// comm-path2d parameters that describe the same problem and channel realization.
const std::vector<std::string> kSmallSet = {
    "S=20,20", "D=10,5", "c=75", "tf=20", "workspace=25", "grid_step=0.25", "samples=100"};

TEST(TrueChannelJudge, TheCommProblemsTruthIsTheOnlineDriversRealization) {
  // The truth needs the parameters only (no prediction: 100 samples do not always estimate).
  Parameters params(FindProblem("comm-path2d").parameters);
  for (const std::string& a : kSmallSet) params.SetFromString(a);
  const auto truth = MakeCommTrueChannel(params, 4);
  OnlineChannelOptions c;
  c.simulation.grid = GridSpec::Workspace(25.0, 25.0, 0.25);
  const OnlineChannel online(4, c);
  for (const Eigen::Vector2d& q : {Eigen::Vector2d(20.0, 20.0),
                                   Eigen::Vector2d(5.3, 7.9),
                                   Eigen::Vector2d(0.01, 24.99),
                                   Eigen::Vector2d(12.5, 12.5)}) {
    double s = 0.0;
    Eigen::Vector2d g(1.0, 1.0);
    truth->Evaluate(q, &s, &g, nullptr);
    EXPECT_EQ(s, online.TrueQuality(q)) << q.transpose();
    EXPECT_EQ(g.squaredNorm(), 0.0);  // piecewise constant: a judge, not a planner's model
  }
  // Another seed is another realization.
  double s4 = 0.0, s5 = 0.0;
  truth->Evaluate(Eigen::Vector2d(12.5, 12.5), &s4, nullptr, nullptr);
  MakeCommTrueChannel(params, 5)->Evaluate(Eigen::Vector2d(12.5, 12.5), &s5, nullptr, nullptr);
  EXPECT_NE(s4, s5);
}

TEST(TrueChannelJudge, AnOfflinePlansTrueEnergyIsTheOnlineDriversOfflineEnergy) {
  const std::uint64_t seed = 3;
  OnlineChannelOptions c;
  c.simulation.grid = GridSpec::Workspace(25.0, 25.0, 0.25);
  OnlineChannel channel(seed, c);
  OnlineReplanningOptions r;
  r.update_period = 5.0;
  r.initial_measurements = 60;
  r.measurements_per_update = 30;
  r.intervals = 100;
  r.solver = "hamiltonian";
  r.offline_options = {{"max_iterations", "100"}};
  r.replan_options = {{"max_iterations", "10"}};
  const OnlineResult online = RunOnlineReplanning(testing::SmallOnlineProblem(), &channel, seed, r);

  // The offline plan judged as an offline record's controls are: by the problem's registry
  // entry, on the problem built for that seed (its own prediction differs; the truth does not).
  Parameters params;
  const auto ocp = MakeProblem("comm-path2d", kSmallSet, seed, &params);
  const ProblemInfo& info = FindProblem("comm-path2d");
  ASSERT_TRUE(info.judge_on_truth);
  const auto judged = info.judge_on_truth(params, seed, *ocp, online.grid, online.offline_U);
  ASSERT_TRUE(judged.has_value());
  EXPECT_EQ(judged->energy_true, online.offline_energy_true);
  EXPECT_EQ(judged->transmit_energy_true, online.offline_transmit_energy_true);
  EXPECT_EQ(judged->J_true, online.offline_J_true);
  EXPECT_EQ(judged->terminal_violation, online.offline_terminal_violation);
  EXPECT_NE(judged->truth.find("true channel seed=3"), std::string::npos) << judged->truth;
  // And the executed online trajectory's controls, judged the same way, cost its energy_true
  // (the driver prices it step by step, plan by plan).
  const auto executed = info.judge_on_truth(params, seed, *ocp, online.grid, online.U);
  EXPECT_NEAR(executed->energy_true, online.energy_true, 1e-12 * online.energy_true);
  EXPECT_NEAR(executed->J_true, online.J_true, 1e-10 * online.J_true);
  // Geometry of the offline path from its executed states.
  const PathGeometry g = MeasurePath(online.offline_X.topRows(2),
                                     Eigen::Vector2d(20.0, 20.0),
                                     Eigen::Vector2d(10.0, 5.0),
                                     Eigen::Vector2d(5.0, 5.0));
  EXPECT_EQ(judged->max_distance_from_segment, g.max_distance_from_segment);
  EXPECT_EQ(judged->min_distance_to_base, g.min_distance_to_base);
}

TEST(TrueChannelJudge, PathGeometryAgainstTheSegmentAndTheBase) {
  Mat path(2, 4);
  path << 0.0, 1.0, 2.0, 3.0,  //
      0.0, 1.0, 0.0, -2.0;
  const PathGeometry g =
      MeasurePath(path, Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(2.0, 0.0), {1.0, 3.0});
  // (3, -2) lies beyond the segment's end (2, 0): sqrt(1 + 4) from it.
  EXPECT_NEAR(g.max_distance_from_segment, std::sqrt(5.0), 1e-15);
  EXPECT_NEAR(g.min_distance_to_base, 2.0, 1e-15);
}

TEST(TrueChannelJudge, WithAPathLossChannelTheTruthIsTheModel) {
  // channel = 0 is deterministic: the true energy of any controls is the evaluator's Jbar.
  Parameters params;
  const auto ocp = MakeProblem("comm-path2d", {"channel=0"}, 1, &params);
  const TimeGrid grid = TimeGrid::Uniform(0.0, 40.0, 400);
  std::string why;
  const Mat U = ocp->BaselinePlan(grid, &why)->SampleIntervals(grid);
  const auto t = FindProblem("comm-path2d").judge_on_truth(params, 1, *ocp, grid, U);
  const Evaluation ev =
      Evaluate(*ocp, ControlTrajectory::PiecewiseConstant(grid, U), grid, Integrator::kEuler);
  EXPECT_NEAR(t->energy_true, ev.Jbar, 1e-12 * ev.Jbar);
  EXPECT_NEAR(t->J_true, ev.J, 1e-12 * ev.J);
  EXPECT_LT(t->max_distance_from_segment, 1e-12);  // the baseline drives the segment
}

}  // namespace
}  // namespace ocpb
