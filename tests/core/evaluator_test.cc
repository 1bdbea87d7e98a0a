#include "core/evaluator.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "core/autodiff_ocp.h"
#include "core/discrete_ocp.h"
#include "problems/registry.h"
#include "tests/core/test_problems.h"

namespace ocpb {
namespace {

ControlTrajectory AnalyticDoubleIntegratorControl(const TimeGrid& grid) {
  Mat U(1, grid.size());
  for (int k = 0; k < grid.size(); ++k) U(0, k) = 6.0 - 12.0 * grid.t(k);
  return ControlTrajectory::PiecewiseLinear(grid, U);
}

TEST(Evaluator, ReproducesTheDoubleIntegratorOptimumOnAFineRk4Grid) {
  const auto ocp = MakeProblem("double-integrator", {}, 0);
  const TimeGrid grid = TimeGrid::Uniform(0.0, 1.0, 1000);
  const Evaluation ev =
      Evaluate(*ocp, AnalyticDoubleIntegratorControl(grid), grid, Integrator::kRk4);
  ASSERT_TRUE(ev.finite);
  EXPECT_NEAR(ev.Jbar, 6.0, 6.0 * 1e-8);
  EXPECT_LT(ev.terminal_violation, 1e-10);
  EXPECT_NEAR(ev.J, ev.Jbar, 1e-12);  // no terminal penalty left at the optimum
  EXPECT_EQ(ev.control_violation, 0.0);
  EXPECT_EQ(ev.path_violation, 0.0);
}

TEST(Evaluator, ControlOnAnotherGridIsSampledWithOneSidedLimits) {
  // The analytic control on a coarse grid, evaluated on a finer one, is still exact.
  const auto ocp = MakeProblem("double-integrator", {}, 0);
  const TimeGrid coarse = TimeGrid::Uniform(0.0, 1.0, 7);
  const TimeGrid fine = TimeGrid::Uniform(0.0, 1.0, 350);
  const Evaluation ev =
      Evaluate(*ocp, AnalyticDoubleIntegratorControl(coarse), fine, Integrator::kRk4);
  EXPECT_NEAR(ev.Jbar, 6.0, 6.0 * 1e-8);
}

TEST(Evaluator, EulerWithPiecewiseConstantControlsIsTheDiscreteProblem) {
  const testing::NonlinearTestOcp ocp;
  const TimeGrid grid = TimeGrid::FromPoints({0.0, 0.2, 0.3, 0.7, 1.0});
  Mat U(2, 4);
  U << 0.1, -0.5, 0.9, 0.3, 1.2, 0.4, -0.2, 0.0;
  for (Integrator integrator : {Integrator::kEuler, Integrator::kRk4}) {
    const DiscreteOcp docp(ocp, grid, integrator, TerminalMode::kPenalty);
    Mat X;
    const double J = docp.Simulate(U, &X);
    const Evaluation ev =
        Evaluate(ocp, ControlTrajectory::PiecewiseConstant(grid, U), grid, integrator);
    EXPECT_NEAR(ev.J, J, 1e-12 * std::abs(J)) << ToString(integrator);
    EXPECT_TRUE(ev.X.isApprox(X, 1e-14));
  }
}

TEST(Evaluator, ReportsControlSetAndPathViolations) {
  const auto ocp = MakeProblem("double-integrator-bounded", {}, 0);  // |u| <= 5
  const TimeGrid grid = TimeGrid::Uniform(0.0, 1.0, 10);
  Mat U = Mat::Constant(1, 10, 1.0);
  U(0, 3) = 7.5;
  const Evaluation ev =
      Evaluate(*ocp, ControlTrajectory::PiecewiseConstant(grid, U), grid, Integrator::kEuler);
  EXPECT_NEAR(ev.control_violation, 2.5, 1e-15);

  const testing::NonlinearTestOcp nl;  // c = x1 + u1^2 - 3 <= 0
  Mat V = Mat::Zero(2, 10);
  V(0, 0) = 2.0;  // c(t0) = 0.3 + 4 - 3 = 1.3
  const Evaluation ev2 =
      Evaluate(nl, ControlTrajectory::PiecewiseConstant(grid, V), grid, Integrator::kEuler);
  EXPECT_NEAR(ev2.path_violation, 1.3, 1e-12);
}

// x' = u on [0, 1], x(0) = 0, path constraint c = t - x <= 0 (stay ahead of the clock).
class AheadOfTheClockOcp final : public AutoDiffOcp<AheadOfTheClockOcp, 1, 1, 0, 1> {
 public:
  AheadOfTheClockOcp() {
    SetDimensions(1, 1, 0, 1);
    SetHorizon(0.0, 1.0);
    SetInitialState(Vec::Zero(1));
  }
  std::string name() const override { return "ahead-of-the-clock"; }
  template <class T>
  void EvalDynamics(double, const VecT<T, 1>&, const VecT<T, 1>& u, VecT<T, 1>* f) const {
    (*f)[0] = u[0];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 1>&, const VecT<T, 1>& u) const {
    return u[0] * u[0];
  }
  template <class T>
  void EvalPathConstraints(double t, const VecT<T, 1>& x, const VecT<T, 1>&, VecT<T, 1>* c) const {
    (*c)[0] = t - x[0];
  }
};

TEST(Evaluator, PathConstraintsAreJudgedAtTheGridNodes) {
  // u = 1 gives x(t) = t exactly: c = 0 at every node, for both integrators. Judging c at an RK4
  // step's midpoint time with the step's initial state would report a false violation of h/2.
  const AheadOfTheClockOcp ocp;
  const TimeGrid grid = TimeGrid::Uniform(0.0, 1.0, 10);
  const ControlTrajectory u = ControlTrajectory::Constant(grid, Vec::Ones(1));
  for (Integrator integrator : {Integrator::kEuler, Integrator::kRk4}) {
    const Evaluation ev = Evaluate(ocp, u, grid, integrator);
    EXPECT_NEAR(ev.X(0, 10), 1.0, 1e-14) << ToString(integrator);
    EXPECT_LT(ev.path_violation, 1e-14) << ToString(integrator);
  }
  // A real violation at a node is still seen: falling behind from t = 0.5 on.
  Mat slow = Mat::Ones(1, 10);
  slow(0, 5) = 0.5;
  const Evaluation ev =
      Evaluate(ocp, ControlTrajectory::PiecewiseConstant(grid, slow), grid, Integrator::kRk4);
  EXPECT_NEAR(ev.path_violation, 0.05, 1e-14);  // x(0.6) = 0.55
}

TEST(Evaluator, RejectsControlsThatDoNotFitTheProblem) {
  const auto ocp = MakeProblem("double-integrator", {}, 0);  // nu = 1 on [0, 1]
  const TimeGrid grid = TimeGrid::Uniform(0.0, 1.0, 10);
  auto error = [&](const ControlTrajectory& u, const TimeGrid& g) -> std::string {
    try {
      Evaluate(*ocp, u, g, Integrator::kRk4);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "(no error)";
  };
  EXPECT_EQ(error(ControlTrajectory::Constant(grid, Vec::Zero(2)), grid),
            "Evaluate: the controls have 2 components, the problem double-integrator has nu = 1");
  EXPECT_EQ(error(ControlTrajectory(), grid),
            "Evaluate: the controls have 0 components, the problem double-integrator has nu = 1");
  const TimeGrid longer = TimeGrid::Uniform(0.0, 2.0, 10);
  EXPECT_EQ(error(ControlTrajectory::Constant(longer, Vec::Zero(1)), longer),
            "Evaluate: the grid [0, 2] does not span the horizon [0, 1] of problem "
            "'double-integrator'");
  const TimeGrid half = TimeGrid::Uniform(0.0, 0.5, 5);
  EXPECT_EQ(error(ControlTrajectory::Constant(half, Vec::Zero(1)), grid),
            "Evaluate: the controls are defined on [0, 0.5], which does not cover the grid [0, 1]");
}

TEST(Evaluator, EulerConvergesAtFirstOrderAndRk4AtFourth) {
  // A smooth control on a nonlinear problem: the error of Jbar against a fine RK4 value
  // shrinks by 2^order when the grid is halved.
  const testing::NonlinearTestOcp ocp;
  const TimeGrid any = TimeGrid::Uniform(0.0, 1.0, 1);
  const ControlTrajectory smooth = ControlTrajectory::Custom(
      2,
      any,
      [](double t, ControlTrajectory::Side, VecRef u) {
        u[0] = 0.5 * std::sin(3.0 * t);
        u[1] = std::cos(2.0 * t) - 0.5;
      },
      "smooth test control");
  auto jbar = [&](Integrator integ, int N) {
    return Evaluate(ocp, smooth, TimeGrid::Uniform(0.0, 1.0, N), integ).Jbar;
  };
  const double reference = jbar(Integrator::kRk4, 4096);
  const double euler_order = std::log2(std::abs(jbar(Integrator::kEuler, 200) - reference) /
                                       std::abs(jbar(Integrator::kEuler, 400) - reference));
  const double rk4_order = std::log2(std::abs(jbar(Integrator::kRk4, 16) - reference) /
                                     std::abs(jbar(Integrator::kRk4, 32) - reference));
  EXPECT_NEAR(euler_order, 1.0, 0.1);
  EXPECT_NEAR(rk4_order, 4.0, 0.2);
}

}  // namespace
}  // namespace ocpb
