#include <cmath>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>

#include "core/derivative_check.h"
#include "core/discrete_ocp.h"
#include "problems/registry.h"
#include "tests/core/test_problems.h"

namespace ocpb {
namespace {

// dJ/dU from one backward pass equals central differences of the discrete J, for both
// integrators, both terminal modes, on a nonlinear problem and on a non-uniform grid.
class DiscreteAdjoint : public ::testing::TestWithParam<std::tuple<Integrator, TerminalMode>> {};

TEST_P(DiscreteAdjoint, GradientMatchesFiniteDifferences) {
  const auto [integrator, mode] = GetParam();
  const testing::NonlinearTestOcp ocp;
  const TimeGrid grid = TimeGrid::FromPoints({0.0, 0.1, 0.25, 0.3, 0.5, 0.62, 0.8, 1.0});
  const DiscreteOcp docp(ocp, grid, integrator, mode);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> dist(-1.0, 1.0);
  Mat U(2, grid.intervals());
  for (int i = 0; i < U.size(); ++i) U(i) = dist(rng);

  Mat X, Lambda, G;
  docp.Simulate(U, &X);
  docp.Adjoint(U, X, &Lambda, &G);
  const Vec u_flat = Eigen::Map<const Vec>(U.data(), U.size());
  const Mat fd = CentralJacobian(
      [&](const Vec& v) {
        const Mat Uv = Eigen::Map<const Mat>(v.data(), U.rows(), U.cols());
        return Vec::Constant(1, docp.Simulate(Uv, nullptr));
      },
      u_flat,
      1e-6);
  const Vec g_flat = Eigen::Map<const Vec>(G.data(), G.size());
  const double rel = (g_flat - fd.row(0).transpose()).norm() / fd.norm();
  EXPECT_LT(rel, 1e-6) << "analytic " << g_flat.transpose() << "\nfd " << fd;

  // The costate at node 0 is dJ/dx0.
  double phi;
  Vec grad(3);
  ocp.TerminalObjectiveGradient(X.col(grid.intervals()), mode, &phi, grad);
  EXPECT_TRUE(Lambda.col(grid.intervals()).isApprox(grad, 1e-14));
}

INSTANTIATE_TEST_SUITE_P(BothIntegratorsBothModes,
                         DiscreteAdjoint,
                         ::testing::Combine(::testing::Values(Integrator::kEuler, Integrator::kRk4),
                                            ::testing::Values(TerminalMode::kPenalty,
                                                              TerminalMode::kHard)));

TEST(DiscreteOcp, EulerCostateIsGradientWithRespectToState) {
  // lambda_k = dJ/dx_k: perturb x_k by restarting the simulation from a perturbed state.
  const auto ocp = MakeProblem("double-integrator", {}, 0);
  const TimeGrid grid = TimeGrid::Uniform(0.0, 1.0, 20);
  const DiscreteOcp docp(*ocp, grid, Integrator::kEuler, TerminalMode::kPenalty);
  Mat U = Mat::Constant(1, 20, 0.3);
  Mat X, Lambda, G;
  docp.Simulate(U, &X);
  docp.Adjoint(U, X, &Lambda, &G);
  // J as a function of x_0 (node 0): simulate by hand with Euler.
  auto J_of_x0 = [&](const Vec& x0) {
    Vec x = x0;
    double J = 0.0;
    for (int k = 0; k < 20; ++k) {
      J += grid.h(k) * 0.5 * U(0, k) * U(0, k);
      x = x + grid.h(k) * Eigen::Vector2d(x[1], U(0, k));
    }
    return Vec::Constant(1, J + ocp->TerminalObjective(x, TerminalMode::kPenalty));
  };
  const Mat fd = CentralJacobian(J_of_x0, ocp->x0());
  EXPECT_NEAR(Lambda(0, 0), fd(0, 0), 1e-6 * std::abs(fd(0, 0)));
  EXPECT_NEAR(Lambda(1, 0), fd(0, 1), 1e-6 * std::abs(fd(0, 1)));
}

// SimulateStates gives Simulate's states bit for bit (the descent evaluates the cost on them and
// must see the same numbers), for both integrators on a non-uniform grid.
TEST(DiscreteOcp, SimulateStatesIsSimulatesStatesExactly) {
  const testing::NonlinearTestOcp ocp;
  const TimeGrid grid = TimeGrid::FromPoints({0.0, 0.1, 0.25, 0.3, 0.5, 0.62, 0.8, 1.0});
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> dist(-1.0, 1.0);
  Mat U(2, grid.intervals());
  for (int i = 0; i < U.size(); ++i) U(i) = dist(rng);
  for (Integrator integrator : {Integrator::kEuler, Integrator::kRk4}) {
    const DiscreteOcp docp(ocp, grid, integrator, TerminalMode::kPenalty);
    Mat X, X_states;
    docp.Simulate(U, &X);
    docp.SimulateStates(U, &X_states);
    EXPECT_EQ(X, X_states) << ToString(integrator);
  }
  const DiscreteOcp docp(ocp, grid, Integrator::kEuler, TerminalMode::kPenalty);
  Mat X;
  EXPECT_THROW(docp.SimulateStates(Mat::Zero(2, 3), &X), std::invalid_argument);
}

}  // namespace
}  // namespace ocpb
