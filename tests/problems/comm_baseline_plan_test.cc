// The comm problems' baseline plan (what a user runs without optimizing) and the "baseline"
// method that returns it.
#include "problems/comm_baseline_plan.h"

#include <cmath>
#include <numeric>
#include <string>

#include <gtest/gtest.h>

#include "core/evaluator.h"
#include "problems/registry.h"
#include "solvers/registry.h"

namespace ocpb {
namespace {

TEST(BaselineAccelerations, CoverTheLengthExactlyWithTheShortestSpeedUp) {
  const double h = 0.1, umax = 0.5;
  const int N = 400;
  for (double length : {36.4005, 1.0, 0.0, 96.0}) {
    std::string why;
    const auto u = BaselineAccelerations(length, h, N, umax, &why);
    ASSERT_TRUE(u.has_value()) << why;
    ASSERT_EQ(u->size(), 400u);
    // Euler from rest: v_{k+1} = v_k + h u_k, distance h sum v_k; at rest at the end.
    double v = 0.0, distance = 0.0;
    int speed_up = 0;
    for (double a : *u) {
      EXPECT_LE(std::abs(a), umax * (1.0 + 1e-15));
      distance += h * v;
      v += h * a;
      if (a > 0.0) ++speed_up;
    }
    EXPECT_NEAR(distance, length, 1e-12 * std::max(1.0, length));
    EXPECT_NEAR(v, 0.0, 1e-12);
    if (length == 0.0) continue;
    // The speed-up is as short as the bound allows: one step less would need a > umax.
    const int m = speed_up;
    EXPECT_GE(m, 1);
    if (m > 1) EXPECT_GT(length / (h * h * (m - 1) * (N - m + 1)), umax);
  }
  std::string why;
  EXPECT_FALSE(BaselineAccelerations(1000.0, h, N, umax, &why).has_value());
  EXPECT_NE(why.find("cannot be covered"), std::string::npos) << why;
}

// The baseline plan of both problems ends at D at rest having sent exactly c bits, with forward
// Euler on its grid and with RK4 on a finer one (piecewise-constant accelerations that sum to
// zero: the exact integral agrees).
TEST(BaselinePlan, EndsAtTheDestinationAtRestHavingSentCBits) {
  struct Case {
    const char* problem;
    std::vector<std::string> set;
  };
  for (const Case& c : {Case{"comm-path2d", {"channel=0"}},
                        Case{"comm-path2d", {"channel=0", "c=50", "S=40,30", "tf=30"}},
                        Case{"comm-fixed-path", {"channel=0"}},
                        Case{"comm-fixed-path", {"channel=0", "W=15,22.5", "fillet=0", "c=225"}}}) {
    SCOPED_TRACE(std::string(c.problem) + " " + c.set.back());
    Parameters params;
    const auto ocp = MakeProblem(c.problem, c.set, 1, &params);
    const TimeGrid grid = TimeGrid::Uniform(ocp->t0(), ocp->tf(), 400);
    std::string why;
    const auto plan = ocp->BaselinePlan(grid, &why);
    ASSERT_TRUE(plan.has_value()) << why;
    for (Integrator integrator : {Integrator::kEuler, Integrator::kRk4}) {
      const TimeGrid judged = integrator == Integrator::kEuler ? grid : grid.Refined(10);
      const Evaluation ev = Evaluate(*ocp, *plan, judged, integrator);
      ASSERT_TRUE(ev.finite);
      EXPECT_LT(ev.terminal_violation, 1e-9) << ev.terminal_residual.transpose();
      EXPECT_LT(ev.control_violation, 1e-12);
      const Vec last = ev.X.col(ev.X.cols() - 1);
      EXPECT_NEAR(last[last.size() - 1], params.Scalar("c"), 1e-9);
    }
    // The rate is constant, c / tf.
    const Mat U = plan->SampleIntervals(grid);
    EXPECT_NEAR(U.row(U.rows() - 1).minCoeff(), params.Scalar("c") / params.Scalar("tf"), 1e-12);
    EXPECT_NEAR(U.row(U.rows() - 1).maxCoeff(), params.Scalar("c") / params.Scalar("tf"), 1e-12);
  }
}

TEST(BaselinePlan, SaysWhyWhenThereIsNone) {
  const TimeGrid grid = TimeGrid::Uniform(0.0, 40.0, 400);
  std::string why;
  // Too many bits for Rmax = 6 over 40 s.
  EXPECT_FALSE(MakeProblem("comm-path2d", {"channel=0", "c=450"}, 1)->BaselinePlan(grid, &why));
  EXPECT_NE(why.find("outside [0, Rmax"), std::string::npos) << why;
  // Not from rest.
  EXPECT_FALSE(MakeProblem("comm-path2d", {"channel=0", "v0=1,0"}, 1)->BaselinePlan(grid, &why));
  EXPECT_NE(why.find("v0 = 0"), std::string::npos) << why;
  // Too far for umax in tf.
  EXPECT_FALSE(MakeProblem("comm-path2d", {"channel=0", "umax=0.01"}, 1)->BaselinePlan(grid, &why));
  EXPECT_NE(why.find("cannot be covered"), std::string::npos) << why;
  // A grid on another horizon.
  EXPECT_FALSE(MakeProblem("comm-path2d", {"channel=0"}, 1)
                   ->BaselinePlan(TimeGrid::Uniform(0.0, 20.0, 400), &why));
  EXPECT_NE(why.find("horizon"), std::string::npos) << why;
  // A problem without one.
  EXPECT_FALSE(MakeProblem("lqr", {}, 1)->BaselinePlan(TimeGrid::Uniform(0.0, 5.0, 50), &why));
  EXPECT_NE(why.find("defines no baseline plan"), std::string::npos) << why;
}

TEST(BaselineSolver, ReturnsThePlanUnoptimizedOrSaysNotApplicable) {
  const auto solver = FindSolver("baseline").make();
  const auto ocp = MakeProblem("comm-path2d", {"channel=0"}, 1);
  SolveRequest request;
  request.grid = TimeGrid::Uniform(0.0, 40.0, 400);
  const SolveResult r = solver->Solve(*ocp, request);
  EXPECT_EQ(r.status, SolveStatus::kConverged);
  EXPECT_EQ(r.solver_status, "baseline_plan");
  EXPECT_EQ(r.iterations, 0);
  const Evaluation ev = Evaluate(*ocp, r.controls, request.grid, Integrator::kEuler);
  EXPECT_DOUBLE_EQ(r.objective, ev.J);
  request.terminal = TerminalMode::kHard;
  EXPECT_DOUBLE_EQ(solver->Solve(*ocp, request).objective, ev.Jbar);
  const auto lqr = MakeProblem("lqr", {}, 1);
  request.grid = TimeGrid::Uniform(lqr->t0(), lqr->tf(), 50);
  const SolveResult na = solver->Solve(*lqr, request);
  EXPECT_EQ(na.status, SolveStatus::kNotApplicable);
  EXPECT_NE(na.message.find("no baseline plan"), std::string::npos) << na.message;
  request.options.Set("max_iterations", 3);
  EXPECT_THROW(solver->Solve(*ocp, request), std::invalid_argument);
}

}  // namespace
}  // namespace ocpb
