// The free-final-time COPS problems with box-bounded controls (goddard, robot-arm), posed by
// time scaling: registry entries, derivatives, COPS' values at COPS' own scheme and grid, the
// structure of the optima, agreement across transcriptions, and the Hamiltonian method's "not
// applicable".
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/derivative_check.h"
#include "problems/reference/goddard.h"
#include "problems/reference/robot_arm.h"
#include "problems/registry.h"
#include "tests/problems/reference_test_support.h"

namespace ocpb {
namespace {

using reference_testing::Request;
using reference_testing::SolveWith;

const std::vector<std::string> kNames = {"goddard", "robot-arm"};

SolveResult SolveHard(const std::string& name, const std::string& transcription, int N) {
  const auto ocp = MakeProblem(name, {}, 0);
  return SolveWith(
      "ipopt", *ocp, Request(*ocp, N, TerminalMode::kHard, transcription, {{"tol", "1e-12"}}));
}

TEST(FreeTimeProblems, AreRegisteredWithCopsValuesAndNoHamiltonianMethod) {
  EXPECT_EQ(*FindProblem("goddard").reference_value, -1.01283);
  EXPECT_EQ(*FindProblem("robot-arm").reference_value, 9.14138);
  EXPECT_EQ(FindProblem("goddard").default_intervals, 400);
  EXPECT_EQ(FindProblem("robot-arm").default_intervals, 200);
  for (const std::string& name : kNames) {
    SCOPED_TRACE(name);
    const ProblemInfo& info = FindProblem(name);
    EXPECT_FALSE(info.hamiltonian_applicable);
    EXPECT_NE(info.hamiltonian_note.find("not applicable"), std::string::npos);
    EXPECT_NE(info.reference_source.find("trapezoid"), std::string::npos);
    const auto ocp = MakeProblem(name, {}, 0);
    EXPECT_EQ(ocp->name(), name);
    EXPECT_FALSE(ocp->HasHamiltonianMinimizer());
    EXPECT_EQ(ocp->x0()[ocp->nx() - 1], 0.0);  // the clock starts at t = 0
    EXPECT_EQ(ocp->tf(), 1.0);                 // the scaled horizon s in [0, 1]
    // The Hamiltonian descent says so instead of returning a number.
    const SolveResult r = SolveWith("hamiltonian", *ocp, Request(*ocp, 20, TerminalMode::kPenalty));
    EXPECT_EQ(r.status, SolveStatus::kNotApplicable);
    EXPECT_EQ(r.iterations, 0);
  }
  EXPECT_THROW(MakeProblem("goddard", {"sigma_min=2", "sigma_max=1"}, 0), std::invalid_argument);
}

// J = Phi + eps (int sigma^2 - tau(1)^2): at a constant sigma it is Phi exactly.
TEST(FreeTimeProblems, CostIsThePhysicalCostPlusEpsTimesTheVarianceOfSigma) {
  const auto ocp = MakeProblem("robot-arm", {"eps=0.3"}, 0);
  Vec x = ocp->x0();
  x[6] = 9.0;  // tau(1)
  Vec u = Vec::Zero(4);
  u[3] = 9.0;
  EXPECT_NEAR(ocp->TerminalCost(x) + ocp->RunningCost(0.5, x, u), 9.0, 1e-12);
  // sigma = 8 on half of [0, 1] and 10 on the other half: Var = 1.
  Vec u8 = u, u10 = u;
  u8[3] = 8.0;
  u10[3] = 10.0;
  const double J = ocp->TerminalCost(x) + 0.5 * ocp->RunningCost(0.2, x, u8) +
                   0.5 * ocp->RunningCost(0.7, x, u10);
  EXPECT_NEAR(J, 9.0 + 0.3, 1e-12);
  // Goddard's physical cost is -h(T).
  const auto rocket = MakeProblem("goddard", {}, 0);
  Vec y = rocket->x0();
  y[0] = 1.01;
  y[3] = 0.2;
  Vec w(2);
  w << 1.0, 0.2;
  EXPECT_NEAR(rocket->TerminalCost(y) + rocket->RunningCost(0.0, y, w), -1.01, 1e-12);
}

// The scaled dynamics are sigma times the physical ones, with the clock running at sigma.
TEST(FreeTimeProblems, DynamicsAreTheTimeDilationTimesThePhysicalDynamics) {
  const auto rocket = MakeProblem("goddard", {}, 0);
  Vec x(4), u(2), f(4);
  x << 1.002, 0.1, 0.8, 0.05;
  u << 2.0, 0.25;
  rocket->Dynamics(0.3, x, u, f);
  const double drag = 310.0 * 0.1 * 0.1 * std::exp(-500.0 * 0.002);
  EXPECT_NEAR(f[0], 0.25 * 0.1, 1e-14);
  EXPECT_NEAR(f[1], 0.25 * ((2.0 - drag) / 0.8 - 1.0 / (1.002 * 1.002)), 1e-13);
  EXPECT_NEAR(f[2], 0.25 * (-2.0 / 0.5), 1e-14);
  EXPECT_NEAR(f[3], 0.25, 1e-14);

  const auto arm = MakeProblem("robot-arm", {}, 0);
  Vec y(7), v(4), g(7);
  y << 4.4, 0.5, 0.9, 0.1, 0.2, -0.3, 2.0;
  v << 0.5, -1.0, 0.25, 3.0;
  arm->Dynamics(0.3, y, v, g);
  const double inertia = (std::pow(0.6, 3) + std::pow(4.4, 3)) / 3.0;
  EXPECT_NEAR(g[0], 3.0 * 0.1, 1e-14);
  EXPECT_NEAR(g[1], 3.0 * 0.2, 1e-14);
  EXPECT_NEAR(g[2], 3.0 * -0.3, 1e-14);
  EXPECT_NEAR(g[3], 3.0 * 0.5 / 5.0, 1e-14);
  EXPECT_NEAR(g[4], 3.0 * -1.0 / (inertia * std::pow(std::sin(0.9), 2)), 1e-13);
  EXPECT_NEAR(g[5], 3.0 * 0.25 / inertia, 1e-13);
  EXPECT_NEAR(g[6], 3.0, 1e-14);
}

TEST(FreeTimeProblems, DerivativesMatchFiniteDifferences) {
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (const std::string& name : kNames) {
    const auto ocp = MakeProblem(name, {}, 0);
    Vec lo, hi;
    ocp->control_set().BoundingBox(&lo, &hi);
    for (int trial = 0; trial < 8; ++trial) {
      Vec x = ocp->x0();
      // Near the problem's own scale: Goddard's drag varies like exp(-500 (h - 1)).
      const double spread = name == "goddard" ? 0.01 : 0.5;
      for (int i = 0; i < ocp->nx(); ++i) x[i] += spread * std::abs(unit(rng));
      Vec u(ocp->nu());
      for (int i = 0; i < ocp->nu(); ++i) u[i] = lo[i] + (hi[i] - lo[i]) * 0.5 * (1.0 + unit(rng));
      Vec lambda(ocp->nx()), nu(ocp->num_terminal());
      for (int i = 0; i < ocp->nx(); ++i) lambda[i] = unit(rng);
      for (int i = 0; i < ocp->num_terminal(); ++i) nu[i] = unit(rng);
      const DerivativeCheck check = CheckOcpDerivatives(*ocp, 0.5, x, u, lambda, Vec(0), nu);
      // Goddard's drag exp(-500 (h - 1)) gives central differences (step 6e-6) a relative
      // truncation error of (500 * 6e-6)^2 / 6 = 1.5e-6 in the Hessian (measured 1.5e-6).
      EXPECT_LT(check.max_error, name == "goddard" ? 1e-5 : 1e-6) << name << "\n" << check.log;
    }
  }
}

// COPS 3.0 reports h(T) = 1.01283 (Goddard, nh = 400) and T = 9.14138 (robot arm, nh = 200) for
// the trapezoid scheme with a constant step, which is our trapezoid transcription with sigma
// constant (the default eps keeps it constant to 1e-6). Measured (Ipopt, tol 1e-12):
// h(T) = 1.01283661, T = 9.14139545. Goddard is 6.6e-6 above COPS' printed 1.01283 (which reads
// as truncated: rounded it would be 1.01284; a per-grid value 1.01283634 attributed to LINDO in
// the project notes is 2.7e-7 away). The robot arm's T is 1.5e-5 (1.7e-6 relative) above
// COPS' value, three times COPS' rounding: the same scheme gives 9.1426853 at nh = 100 and
// 9.1410259 at nh = 400, so the published value is not a neighbouring grid's, and sigma is
// constant. The tolerances state those measured gaps, not COPS' rounding.
TEST(FreeTimeProblems, TrapezoidMatchesCopsAtItsOwnGrid) {
  const SolveResult rocket = SolveHard("goddard", "trapezoid", Goddard::kCopsIntervals);
  ASSERT_EQ(rocket.status, SolveStatus::kConverged) << rocket.message;
  EXPECT_NEAR(-rocket.objective, -Goddard::kCopsReferenceCost, 1e-5);

  const SolveResult arm = SolveHard("robot-arm", "trapezoid", RobotArm::kCopsIntervals);
  ASSERT_EQ(arm.status, SolveStatus::kConverged) << arm.message;
  EXPECT_NEAR(arm.objective, RobotArm::kCopsReferenceTime, 2e-5);
}

// The optimum's structure: sigma constant (= T, the clock's final value), COPS' left-out state
// bounds satisfied, and the controls' known shapes (Goddard: full thrust first, none at the end;
// robot arm: bang-bang, |u_theta| = 1 at almost every node).
TEST(FreeTimeProblems, OptimaHaveConstantSigmaTheLeftOutBoundsAndTheKnownControlShapes) {
  {
    const int N = 400;
    const SolveResult r = SolveHard("goddard", "trapezoid", N);
    ASSERT_EQ(r.status, SolveStatus::kConverged);
    const double T = r.states(3, N);
    EXPECT_NEAR(T, 0.19885, 1e-4);  // measured 0.198850
    for (int k = 0; k <= N; ++k) {
      EXPECT_GE(r.states(0, k), 1.0 - 1e-12);  // h >= 1
      EXPECT_GE(r.states(1, k), -1e-12);       // v >= 0
      EXPECT_LE(r.states(2, k), 1.0 + 1e-12);  // m <= 1
      EXPECT_GE(r.states(2, k), Goddard::kFinalMass - 1e-9);
    }
    Vec u(2);
    double max_sigma_error = 0.0;
    for (int k = 0; k <= N; ++k) {
      const double s = static_cast<double>(k) / N;
      r.controls.Evaluate(
          s, k == N ? ControlTrajectory::Side::kLeft : ControlTrajectory::Side::kRight, u);
      max_sigma_error = std::max(max_sigma_error, std::abs(u[1] - T) / T);
    }
    EXPECT_LT(max_sigma_error, 1e-4);
    r.controls.Evaluate(0.0, ControlTrajectory::Side::kRight, u);
    EXPECT_NEAR(u[0], Goddard::kMaxThrust, 1e-6);
    r.controls.Evaluate(1.0, ControlTrajectory::Side::kLeft, u);
    EXPECT_NEAR(u[0], 0.0, 1e-6);
  }
  {
    const int N = 200;
    const SolveResult r = SolveHard("robot-arm", "trapezoid", N);
    ASSERT_EQ(r.status, SolveStatus::kConverged);
    const double T = r.states(6, N);
    int saturated = 0;
    double max_sigma_error = 0.0;
    Vec u(4);
    for (int k = 0; k <= N; ++k) {
      EXPECT_GE(r.states(0, k), 0.0);
      EXPECT_LE(r.states(0, k), RobotArm::kLength);
      EXPECT_LE(std::abs(r.states(1, k)), M_PI);
      EXPECT_GE(r.states(2, k), 0.0);
      EXPECT_LE(r.states(2, k), M_PI);
      r.controls.Evaluate(static_cast<double>(k) / N,
                          k == N ? ControlTrajectory::Side::kLeft : ControlTrajectory::Side::kRight,
                          u);
      saturated += std::abs(std::abs(u[1]) - 1.0) < 1e-6;
      max_sigma_error = std::max(max_sigma_error, std::abs(u[3] - T) / T);
    }
    EXPECT_LT(max_sigma_error, 1e-4);
    EXPECT_GE(saturated, N * 9 / 10);
  }
}

// Away from COPS' grid there is no published value; the schemes must agree with one another on
// the continuous optimum. Measured (tol 1e-12): Goddard h(T) = 1.01283662 (trapezoid 400),
// 1.01283686 (LGR degree 3, 50 intervals), 1.01283696 (Hermite-Simpson 400, Ipopt "acceptable");
// robot arm: trapezoid 9.1413955, 9.1410259, 9.1409409 at 200, 400, 800 (second order, ratios
// of successive differences 3.5 and 4.3), Richardson from 200 and 400: 9.1409028;
// Hermite-Simpson 9.1409971, 9.1409057, 9.1409161 at 100, 200, 400 (the bang-bang switches
// limit its order), LGR degree 3 at 100 intervals 9.1409321.
TEST(FreeTimeProblems, TranscriptionsAgreeOnTheContinuousOptimum) {
  const SolveResult trap = SolveHard("goddard", "trapezoid", 400);
  const SolveResult lgr = SolveHard("goddard", "lgr", 50);
  ASSERT_EQ(trap.status, SolveStatus::kConverged);
  ASSERT_EQ(lgr.status, SolveStatus::kConverged);
  EXPECT_NEAR(trap.objective, lgr.objective, 1e-6);

  const SolveResult arm200 = SolveHard("robot-arm", "trapezoid", 200);
  const SolveResult arm400 = SolveHard("robot-arm", "trapezoid", 400);
  const SolveResult hs = SolveHard("robot-arm", "hermite-simpson", 200);
  ASSERT_EQ(arm200.status, SolveStatus::kConverged);
  ASSERT_EQ(arm400.status, SolveStatus::kConverged);
  ASSERT_EQ(hs.status, SolveStatus::kConverged);
  // Richardson extrapolation of the second-order trapezoid values vs Hermite-Simpson.
  const double extrapolated = arm400.objective + (arm400.objective - arm200.objective) / 3.0;
  EXPECT_NEAR(extrapolated, hs.objective, 2e-5);  // measured 9.1409028 vs 9.1409057
  EXPECT_GT(arm200.objective, arm400.objective);
}

}  // namespace
}  // namespace ocpb
