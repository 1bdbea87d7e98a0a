// Online re-planning with channel updates: bookkeeping, controls, determinism, the new
// comm-path2d initial conditions.
#include "drivers/online/online_replanning.h"

#include <cmath>
#include <numeric>

#include <gtest/gtest.h>

#include "core/evaluator.h"
#include "problems/comm_path2d.h"
#include "problems/registry.h"
#include "tests/online/small_online_problem.h"

namespace ocpb {
namespace {

// A small scenario (fast under ASan): a 25 m workspace simulated at 0.25 m, tf = 20 s, N = 100
// (h = 0.2 s), updates every 5 s (4 cycles), 60 + 3 x 30 measurements (the paper's density of
// 100 per 2500 m^2 would leave the estimator too few lag pairs here).
OnlineChannelOptions SmallChannel() {
  OnlineChannelOptions c;
  c.simulation.grid = GridSpec::Workspace(25.0, 25.0, 0.25);
  c.map_resolution = 0.5;
  return c;
}

OnlineReplanningOptions SmallScenario(const std::string& solver) {
  OnlineReplanningOptions r;
  r.update_period = 5.0;
  r.initial_measurements = 60;
  r.measurements_per_update = 30;
  r.intervals = 100;
  r.solver = solver;
  if (solver == "ipopt") r.transcription = "euler";
  r.offline_options = solver == "hamiltonian"
                          ? std::map<std::string, std::string>{{"max_iterations", "150"}}
                          : std::map<std::string, std::string>{};
  r.replan_options = solver == "hamiltonian"
                         ? std::map<std::string, std::string>{{"max_iterations", "20"}}
                         : std::map<std::string, std::string>{};
  return r;
}

OnlineResult RunSmall(const OnlineReplanningOptions& r,
                      std::uint64_t seed = 3,
                      const OnlineChannelOptions& c = SmallChannel(),
                      OnlineChannel** keep = nullptr) {
  static thread_local std::unique_ptr<OnlineChannel> channel;
  channel = std::make_unique<OnlineChannel>(seed, c);
  if (keep) *keep = channel.get();
  return RunOnlineReplanning(testing::SmallOnlineProblem(), channel.get(), seed, r);
}

TEST(OnlineReplanning, EnergyBookkeepingAndExecution) {
  OnlineChannel* channel = nullptr;
  const OnlineResult r = RunSmall(SmallScenario("hamiltonian"), 3, SmallChannel(), &channel);
  ASSERT_EQ(r.cycles.size(), 4u);
  ASSERT_EQ(r.step_energy_true.size(), 100u);
  // The total is the sum of the steps and the sum of the cycles' segments.
  const double steps = std::accumulate(r.step_energy_true.begin(), r.step_energy_true.end(), 0.0);
  double segments = 0.0, segments_predicted = 0.0;
  for (const OnlineCycle& c : r.cycles) {
    segments += c.segment_energy_true;
    segments_predicted += c.segment_energy_predicted;
  }
  EXPECT_NEAR(r.energy_true, steps, 1e-10 * steps);
  EXPECT_NEAR(r.energy_true, segments, 1e-10 * steps);
  EXPECT_NEAR(r.energy_predicted, segments_predicted, 1e-10 * steps);
  // An independent recomputation from the executed states and controls on the true channel.
  const CommPowerModel power;
  double energy = 0.0;
  for (int k = 0; k < 100; ++k) {
    const Vec x = r.X.col(k), u = r.U.col(k);
    const double s = channel->TrueQuality(x.head<2>());
    energy += 0.2 * ((std::exp2(u[2]) - 1.0) / power.K() * s +
                     power.Motion(u.head<2>().squaredNorm(), x.segment<2>(2).squaredNorm()));
  }
  EXPECT_NEAR(r.energy_true, energy, 1e-9 * energy);
  // Each cycle starts where the robot is and the robot follows the plan it executes.
  for (const OnlineCycle& c : r.cycles) {
    EXPECT_EQ(c.first_step, static_cast<int>(std::lround(c.t0 / 0.2)));
    for (int j = 0; j <= c.steps_executed; ++j) {
      EXPECT_LT((c.plan_states.col(j) - r.X.col(c.first_step + j)).cwiseAbs().maxCoeff(), 1e-9);
    }
    EXPECT_GE(c.solve_seconds, 0.0);
    EXPECT_GE(c.predict.total(), 0.0);
    EXPECT_LE(c.iterations, c.t0 == 0.0 ? 150 : 20);
  }
  EXPECT_EQ(r.cycles.back().measurements, 60 + 3 * 30);
  EXPECT_EQ(channel->num_measurements(), 150);
  // Terminal state: close to the destination, at rest, bits sent.
  EXPECT_LT(r.terminal_violation, 1.0);
  EXPECT_NEAR(r.terminal_violation, r.terminal_residual.cwiseAbs().maxCoeff(), 0.0);
  EXPECT_GT(r.energy_true, 0.0);
  EXPECT_GT(r.offline_energy_true, 0.0);
  // The offline plan executed to tf follows the plan of cycle 0 exactly.
  EXPECT_LT((r.offline_X - r.cycles[0].plan_states).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_NEAR(r.offline_energy_predicted, r.cycles[0].planned_energy, 1e-9 * r.offline_energy_true);
}

TEST(OnlineReplanning, WithoutNewInformationOrIterationsOnlineIsOffline) {
  // The prediction is never refreshed and re-plans take no iteration: the robot executes the
  // offline plan, piece by piece, exactly.
  OnlineReplanningOptions r = SmallScenario("hamiltonian");
  r.replan_options = {{"max_iterations", "0"}};
  OnlineChannelOptions c = SmallChannel();
  c.refresh = false;
  const OnlineResult o = RunSmall(r, 5, c);
  EXPECT_LT((o.X - o.offline_X).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_NEAR(o.energy_true, o.offline_energy_true, 1e-12 * o.offline_energy_true);
  EXPECT_NEAR(o.energy_predicted, o.offline_energy_predicted, 1e-12 * o.offline_energy_true);
  EXPECT_NEAR(o.terminal_violation, o.offline_terminal_violation, 1e-12);
}

TEST(OnlineReplanning, UnchangedChannelIpoptReplansReproduceTheOfflineOptimum) {
  // Bellman: the tail of an optimal plan is optimal for the cost-to-go problem. Ipopt solves the
  // Euler transcription to tol 1e-8, so a warm-started re-plan on the same channel returns the
  // tail again, to solver tolerance.
  // (With Ipopt's default tol = 1e-8 the paths differ by up to 8 mm on this flat objective; with
  // 1e-11 by 2e-6 m and the energies by 1e-12 relative.)
  OnlineReplanningOptions r = SmallScenario("ipopt");
  r.offline_options = r.replan_options = {{"tol", "1e-11"}};
  OnlineChannelOptions c = SmallChannel();
  c.refresh = false;
  const OnlineResult o = RunSmall(r, 5, c);
  for (const OnlineCycle& cy : o.cycles) EXPECT_TRUE(IsSuccess(cy.status)) << cy.solver_status;
  EXPECT_LT((o.X - o.offline_X).cwiseAbs().maxCoeff(), 1e-4);
  EXPECT_NEAR(o.energy_true, o.offline_energy_true, 1e-9 * o.offline_energy_true);
  EXPECT_NEAR(o.terminal_violation, o.offline_terminal_violation, 1e-6);
}

TEST(OnlineReplanning, NewMeasurementsChangeThePlanAndRunsAreDeterministic) {
  const OnlineReplanningOptions r = SmallScenario("hamiltonian");
  const OnlineResult a = RunSmall(r, 7);
  const OnlineResult b = RunSmall(r, 7);
  EXPECT_EQ(a.energy_true, b.energy_true);
  EXPECT_EQ(a.X, b.X);
  // Re-estimated parameters and new plans: the executed path leaves the offline one.
  EXPECT_GT((a.X - a.offline_X).cwiseAbs().maxCoeff(), 1e-3);
  EXPECT_NE(a.cycles[1].estimated.xi, a.cycles[0].estimated.xi);
  EXPECT_EQ(a.cycles[1].measurement_stream, OnlineMeasurementStream(1));
}

TEST(OnlineReplanning, MeasurementsAlongThePathLieOnTheDrivenPath) {
  OnlineReplanningOptions r = SmallScenario("hamiltonian");
  r.placement = MeasurementPlacement::kAlongPath;
  OnlineChannel* channel = nullptr;
  const OnlineResult o = RunSmall(r, 2, SmallChannel(), &channel);
  const MeasurementSet& m = channel->measurements();
  int k = o.cycles[0].new_measurements;
  EXPECT_EQ(k, 60);
  for (size_t ci = 1; ci < o.cycles.size(); ++ci) {
    const OnlineCycle& c = o.cycles[ci];
    EXPECT_GT(c.new_measurements, 0);
    EXPECT_LE(c.new_measurements, 30);
    const int from = o.cycles[ci - 1].first_step;
    for (int j = 0; j < c.new_measurements; ++j, ++k) {
      double best = 1e9;
      for (int s = from; s <= c.first_step; ++s) {
        best = std::min(best, (m.positions[k] - o.X.col(s).head<2>()).norm());
      }
      EXPECT_LE(best, 0.25 * std::sqrt(0.5) + 1e-9);  // within the cell containing a path point
    }
  }
}

TEST(OnlineChannel, RegionOfInterestMapAgreesWithTheWholeWorkspaceMap) {
  OnlineChannelOptions o = SmallChannel();
  OnlineChannel whole(9, o), region(9, o);
  const MeasurementSet first = whole.DrawRandom(80, 9, 100);
  whole.Update(first);
  region.Update(first);
  const std::vector<Eigen::Vector2d> focus = {Eigen::Vector2d(10.0, 5.0),
                                              Eigen::Vector2d(14.0, 9.0)};
  const MeasurementSet more = whole.DrawRandom(40, 9, 101);
  whole.Update(more);
  region.Update(more, &focus);
  const GridSpec& g = region.map_grid();
  // The box [10, 14] x [5, 9] grown by 10 m, clipped to [0, 25]^2, in whole 0.5 m cells.
  EXPECT_DOUBLE_EQ(g.x_min, 0.0);
  EXPECT_DOUBLE_EQ(g.y_min, 0.0);
  EXPECT_DOUBLE_EQ(g.x_max(), 24.0);
  EXPECT_DOUBLE_EQ(g.y_max(), 19.0);
  EXPECT_EQ(whole.map_grid().nx, 50);
  // Inside the region, away from its edges, both maps give the same s (local-kriging variance
  // and spline ends differ slightly).
  double worst = 0.0;
  for (double x = 2.0; x <= 22.0; x += 0.37) {
    for (double y = 2.0; y <= 17.0; y += 0.41) {
      double a = 0.0, b = 0.0;
      whole.map()->Evaluate(Eigen::Vector2d(x, y), &a, nullptr, nullptr);
      region.map()->Evaluate(Eigen::Vector2d(x, y), &b, nullptr, nullptr);
      worst = std::max(worst, std::abs(b / a - 1.0));
    }
  }
  EXPECT_LT(worst, 1e-3);
}

TEST(OnlineOptions, DefaultsAreValidAndThePapers) {
  std::string error;
  const OnlineReplanningOptions r;
  EXPECT_TRUE(r.IsValid(&error)) << error;
  EXPECT_EQ(r.update_period, 10.0);
  EXPECT_EQ(r.initial_measurements, 100);
  EXPECT_EQ(r.measurements_per_update, 100);
  EXPECT_EQ(r.intervals, 400);
  const OnlineChannelOptions c;
  EXPECT_TRUE(c.IsValid(&error)) << error;
  EXPECT_EQ(c.simulation.grid.nx, 500);
  EXPECT_EQ(c.grid_prediction.num_threads, 1);
  OnlineChannelOptions bad;
  bad.region_margin = -1.0;
  EXPECT_FALSE(bad.IsValid(&error));
  EXPECT_NE(error.find("region_margin"), std::string::npos);
  EXPECT_EQ(MeasurementPlacementFromString("path"), MeasurementPlacement::kAlongPath);
  EXPECT_EQ(MeasurementPlacementFromString("plan"), MeasurementPlacement::kAlongPlan);
  for (MeasurementPlacement p : {MeasurementPlacement::kRandom,
                                 MeasurementPlacement::kAlongPath,
                                 MeasurementPlacement::kAlongPlan}) {
    EXPECT_EQ(MeasurementPlacementFromString(ToString(p)), p);
  }
  EXPECT_THROW(MeasurementPlacementFromString("nowhere"), std::invalid_argument);
}

TEST(OnlineReplanning, MeasurementsAlongThePlanLieOnTheRestOfThePlan) {
  OnlineReplanningOptions r = SmallScenario("hamiltonian");
  r.placement = MeasurementPlacement::kAlongPlan;
  OnlineChannel* channel = nullptr;
  const OnlineResult o = RunSmall(r, 2, SmallChannel(), &channel);
  const MeasurementSet& m = channel->measurements();
  const double cell = 0.25 * std::sqrt(0.5) + 1e-9;  // half the diagonal of a 0.25 m cell
  int k = o.cycles[0].new_measurements;
  EXPECT_EQ(k, 60);
  for (size_t ci = 1; ci < o.cycles.size(); ++ci) {
    const OnlineCycle& c = o.cycles[ci];
    const OnlineCycle& last = o.cycles[ci - 1];
    // The rest of the plan the robot was following: from its state now to tf.
    const Mat rest = last.plan_states.rightCols(last.plan_states.cols() - last.steps_executed);
    ASSERT_LT((rest.col(0) - o.X.col(c.first_step)).cwiseAbs().maxCoeff(), 1e-9);
    // The first plan update measures mostly new cells; later ones fewer, since the previous
    // update sampled the same plan (its cells are measured once).
    EXPECT_GT(c.new_measurements, ci == 1 ? 20 : 0) << ci;
    EXPECT_LE(c.new_measurements, 30);
    double final = 1e9, ahead = 0.0;
    for (int j = 0; j < c.new_measurements; ++j, ++k) {
      double best = 1e9, driven = 1e9;
      for (int s = 0; s < rest.cols(); ++s) {
        best = std::min(best, (m.positions[k] - rest.col(s).head<2>()).norm());
      }
      EXPECT_LE(best, cell);  // within the cell containing a point of the plan
      for (int s = 0; s <= c.first_step; ++s) {
        driven = std::min(driven, (m.positions[k] - o.X.col(s).head<2>()).norm());
      }
      ahead = std::max(ahead, driven);
      final = std::min(final, (m.positions[k] - rest.col(rest.cols() - 1).head<2>()).norm());
    }
    // Evenly spaced in time from now to tf: the last sample is the plan's end point (at the
    // first plan update its cell is new; later plans may end in the same cell), and some
    // measurements lie ahead of the driven path.
    if (ci == 1) {
      EXPECT_LE(final, cell);
    }
    EXPECT_GT(ahead, 1.0) << ci;
  }
}

TEST(OnlineReplanning, RejectsBadOptions) {
  OnlineReplanningOptions r = SmallScenario("hamiltonian");
  r.update_period = -1.0;
  EXPECT_THROW(RunSmall(r), std::invalid_argument);
  r = SmallScenario("hamiltonian");
  r.measurements_per_update = 0;
  EXPECT_THROW(RunSmall(r), std::invalid_argument);
  r = SmallScenario("hamiltonian");
  r.update_period = 0.3;  // not a multiple of h = 0.2
  EXPECT_THROW(RunSmall(r), std::invalid_argument);
  r = SmallScenario("hamiltonian");
  r.replan_options = {{"no_such_option", "1"}};
  EXPECT_THROW(RunSmall(r), std::invalid_argument);
  r = SmallScenario("ipopt");
  r.transcription.clear();
  EXPECT_THROW(RunSmall(r), std::invalid_argument);
}

TEST(CommPath2dInitialConditions, DefaultsAreTheOfflineProblemAndNewFieldsAreUsed) {
  const auto channel = std::make_shared<PathLossChannel>();
  CommPath2d::Options o;
  const CommPath2d from_rest(o, channel);
  EXPECT_EQ(from_rest.t0(), 0.0);
  EXPECT_EQ(from_rest.tf(), 40.0);
  Vec x0(5);
  x0 << 20.0, 40.0, 0.0, 0.0, 0.0;
  EXPECT_EQ(from_rest.x0(), x0);
  o.t0 = 10.0;
  o.v0 = Eigen::Vector2d(0.3, -0.2);
  o.bits_sent = 40.0;
  const CommPath2d later(o, channel);
  EXPECT_EQ(later.t0(), 10.0);
  x0 << 20.0, 40.0, 0.3, -0.2, 40.0;
  EXPECT_EQ(later.x0(), x0);
  // The cost-to-go of u = 0, R = 0 from there: 30 s of gamma k4, the drift, and the penalties.
  const TimeGrid grid = TimeGrid::Uniform(10.0, 40.0, 300);
  const Evaluation ev =
      Evaluate(later, ControlTrajectory::Constant(grid, Vec::Zero(3)), grid, Integrator::kEuler);
  EXPECT_NEAR(ev.terminal_residual[4], 40.0 - 150.0, 1e-12);
  EXPECT_NEAR(ev.terminal_residual[2], 0.3, 1e-12);
  EXPECT_NEAR(ev.X(0, 300), 20.0 + 0.3 * 30.0, 1e-9);
  for (const auto& [field, mutate] :
       std::vector<std::pair<const char*, std::function<void(CommPath2d::Options*)>>>{
           {"t0", [](CommPath2d::Options* p) { p->t0 = 40.0; }},
           {"t0", [](CommPath2d::Options* p) { p->t0 = -1.0; }},
           {"v0", [](CommPath2d::Options* p) { p->v0[1] = NAN; }},
           {"x3_0", [](CommPath2d::Options* p) { p->bits_sent = -1.0; }}}) {
    CommPath2d::Options bad;
    mutate(&bad);
    std::string error;
    EXPECT_FALSE(bad.IsValid(&error)) << field;
    EXPECT_NE(error.find(field), std::string::npos) << error;
    EXPECT_THROW(CommPath2d(bad, channel), std::invalid_argument);
  }
}

TEST(CommPath2dInitialConditions, RegistryParameters) {
  Parameters params;
  const std::unique_ptr<Ocp> ocp =
      MakeProblem("comm-path2d", {"channel=0", "t0=5", "v0=0.1,0.2", "x3_0=3"}, 1, &params);
  EXPECT_EQ(ocp->t0(), 5.0);
  EXPECT_EQ(ocp->x0()[2], 0.1);
  EXPECT_EQ(ocp->x0()[3], 0.2);
  EXPECT_EQ(ocp->x0()[4], 3.0);
  EXPECT_THROW(MakeProblem("comm-path2d", {"channel=0", "t0=40"}, 1, &params),
               std::invalid_argument);
}

}  // namespace
}  // namespace ocpb
