// Bryson-Denham (J* = 4): the analytic solution, every method against it, costates, and what the
// penalty reformulation of the state bound costs the Hamiltonian method.
#include "problems/reference/bryson_denham.h"

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "problems/registry.h"
#include "tests/problems/reference_test_support.h"

namespace ocpb {
namespace {

using reference_testing::FineEvaluation;
using reference_testing::RelativeError;
using reference_testing::Request;
using reference_testing::SolveWith;
using reference_testing::SolveWithHamiltonian;
using reference_testing::SolveWithIpopt;

constexpr double kJ = 4.0;
constexpr double kL = 1.0 / 9.0;  // junctions at 3l = 1/3 and 1 - 3l = 2/3

TEST(BrysonDenham, AnalyticSolutionSatisfiesTheProblem) {
  const auto ocp = MakeProblem("bryson-denham", {}, 0);
  EXPECT_EQ(BrysonDenham::OptimalCost(), kJ);
  // u* is linear on each arc and continuous, and the junctions 1/3, 2/3 are nodes of this grid,
  // so the piecewise-linear samples are u* itself and RK4 integrates the cubic x* exactly.
  const TimeGrid grid = TimeGrid::Uniform(0.0, 1.0, 300);
  Mat U(1, grid.size());
  for (int k = 0; k < grid.size(); ++k) U(0, k) = BrysonDenham::OptimalControl(grid.t(k));
  const Evaluation ev =
      Evaluate(*ocp, ControlTrajectory::PiecewiseLinear(grid, U), grid, Integrator::kRk4);
  EXPECT_NEAR(ev.Jbar, kJ, 1e-12);
  EXPECT_LT(ev.terminal_violation, 1e-12);
  EXPECT_LT(ev.path_violation, 1e-12);
  for (int k = 0; k < grid.size(); ++k) {
    EXPECT_LT((ev.X.col(k) - BrysonDenham::OptimalState(grid.t(k))).cwiseAbs().maxCoeff(), 1e-12)
        << "t = " << grid.t(k);
  }
  // Costates: p2 = -u, and p1 = -p2' (from p' = -H_x, H_x2 = p1) on the unconstrained arcs.
  for (double t : {0.05, 0.2, 0.3, 0.7, 0.85, 0.97}) {
    const double d = 1e-6;
    const double dp2 =
        (BrysonDenham::OptimalCostate(t + d)[1] - BrysonDenham::OptimalCostate(t - d)[1]) /
        (2.0 * d);
    EXPECT_NEAR(BrysonDenham::OptimalCostate(t)[0], -dp2, 1e-6) << "t = " << t;
    EXPECT_EQ(BrysonDenham::OptimalCostate(t)[1], -BrysonDenham::OptimalControl(t));
  }
  EXPECT_EQ(BrysonDenham::OptimalCostate(0.5), Eigen::Vector2d(0.0, 0.0));
}

// The multiplier-based costates of Hermite-Simpson (N = 50) against the analytic p*: p2
// everywhere away from the junctions, p1 on the unconstrained arcs (p1 jumps at the junctions;
// a discrete multiplier smears each jump over about one interval).
TEST(BrysonDenham, IpoptCostatesMatchTheAnalyticOnes) {
  const auto ocp = MakeProblem("bryson-denham", {}, 0);
  const SolveResult r = SolveWithIpopt(*ocp, "hermite-simpson", 50);
  ASSERT_EQ(r.status, SolveStatus::kConverged);
  ASSERT_EQ(r.costates.rows(), 2);
  ASSERT_EQ(r.costates.cols(), r.state_grid.size());
  double e1 = 0.0, e2 = 0.0;
  int compared = 0;
  for (int j = 0; j < r.state_grid.size(); ++j) {
    const double t = r.state_grid.t(j);
    if (std::abs(t - 3 * kL) < 0.05 || std::abs(t - (1 - 3 * kL)) < 0.05) continue;
    const Eigen::Vector2d p = BrysonDenham::OptimalCostate(t);
    e2 = std::max(e2, std::abs(r.costates(1, j) - p[1]));
    if (t < 3 * kL || t > 1 - 3 * kL) e1 = std::max(e1, std::abs(r.costates(0, j) - p[0]));
    ++compared;
  }
  EXPECT_GT(compared, 60);
  EXPECT_LT(e1, 1e-3 * 18.0) << "p1 (|p1*| = 18 on the arcs)";
  EXPECT_LT(e2, 1e-3 * 6.0) << "p2 (|p2*| <= 6)";
}

// The penalty reformulation's optimum approaches J* from below as rho grows (measured with
// Ipopt, Hermite-Simpson N = 100, hard terminal form, judged on the original problem).
TEST(BrysonDenham, PenaltyReformulationGapShrinksWithRho) {
  const auto ocp = MakeProblem("bryson-denham", {}, 0);
  double previous = 0.0;
  for (double rho : {1e3, 1e4, 1e5}) {
    HamiltonianReformulationOptions o;
    o.path_penalty = rho;
    const auto re = ocp->HamiltonianReformulation(o);
    const SolveResult r = SolveWithIpopt(*re, "hermite-simpson", 100);
    ASSERT_EQ(r.status, SolveStatus::kConverged) << "rho = " << rho;
    const double jbar = FineEvaluation(*ocp, r, 100).Jbar;
    EXPECT_GT(jbar, previous) << "rho = " << rho;
    EXPECT_LT(jbar, kJ) << "rho = " << rho;  // the penalty relaxes the bound
    previous = jbar;
  }
  EXPECT_LT(RelativeError(previous, kJ), 1e-2);  // measured 0.7% at rho = 1e5
}

// The Hamiltonian method on the penalty reformulation (C = 1e4, rho = 1e5: the defaults), Euler
// N = 100:
//  - it solves the same discrete problem as Ipopt on the Euler transcription in penalty form,
//    and after 2000 Armijo steps is within 1% of that optimum's cost (measured 0.5%: a
//    first-order method on a problem that the penalties make stiff);
//  - judged on the original problem, its controls cost within 1.5% of J* (measured -0.6%): the
//    penalties let x(1) and x1 <= l be violated slightly (Ipopt's optimum of the same discrete
//    problem is 0.8% below J*), and Euler's states are first order.
TEST(BrysonDenham, HamiltonianOnThePenaltyReformulation) {
  const auto ocp = MakeProblem("bryson-denham", {}, 0);
  const int N = 100;
  const SolveResult h =
      SolveWithHamiltonian(*ocp, N, {{"max_iterations", "2000"}, {"theta_tolerance", "1e-10"}});
  ASSERT_TRUE(h.status == SolveStatus::kMaxIterations || h.status == SolveStatus::kConverged)
      << h.solver_status << " " << h.message;

  const auto re = ocp->HamiltonianReformulation({});
  const SolveResult ipopt = SolveWithIpopt(*re, "euler", N, TerminalMode::kPenalty);
  ASSERT_EQ(ipopt.status, SolveStatus::kConverged);
  EXPECT_GE(h.objective, ipopt.objective - 1e-9);  // convex: Ipopt's is the discrete optimum
  EXPECT_LT(RelativeError(h.objective, ipopt.objective), 1e-2);

  const Evaluation fine = FineEvaluation(*ocp, h, N);
  EXPECT_LT(RelativeError(fine.Jbar, kJ), 1.5e-2) << "Jbar_fine = " << fine.Jbar;
}

// Costates of the Hamiltonian method need a converged run: with the weaker penalties C = 1e3,
// rho = 1e4 2000 steps reach Ipopt's optimum of the same discrete problem to 1e-5 in cost. Its
// costates (the exact discrete adjoint) then approach Ipopt's multiplier-based ones for the Euler
// transcription (measured max difference 0.07, against |p1| = 18: the remaining control
// difference of about 0.01 is amplified by the penalty terms in p' = -H_x), and on the first arc
// [0, 0.25] they match p* = (18, 6 - 18t) to O(h) (the
// last arc is skewed by the soft terminal constraint: p(1) = 2 C psi(x(1)), and the boundary
// arc by the penalty, which smears the jumps of p1).
TEST(BrysonDenham, HamiltonianCostatesMatchTheNlpAndTheAnalyticOnes) {
  const auto ocp = MakeProblem("bryson-denham", {"C=1e3", "rho=1e4"}, 0);
  const int N = 100;
  const SolveResult h =
      SolveWithHamiltonian(*ocp, N, {{"max_iterations", "2000"}, {"theta_tolerance", "1e-10"}});
  const auto re = ocp->HamiltonianReformulation({});
  const SolveResult ipopt = SolveWithIpopt(*re, "euler", N, TerminalMode::kPenalty);
  ASSERT_EQ(ipopt.status, SolveStatus::kConverged);
  ASSERT_LT(RelativeError(h.objective, ipopt.objective), 1e-5) << h.solver_status;
  ASSERT_EQ(h.costates.cols(), N + 1);
  ASSERT_EQ(ipopt.costates.cols(), N + 1);
  EXPECT_LT((h.costates - ipopt.costates).cwiseAbs().maxCoeff(), 0.1);
  double e1 = 0.0, e2 = 0.0;
  for (int k = 0; h.state_grid.t(k) <= 0.25; ++k) {
    const Eigen::Vector2d p = BrysonDenham::OptimalCostate(h.state_grid.t(k));
    e1 = std::max(e1, std::abs(h.costates(0, k) - p[0]));
    e2 = std::max(e2, std::abs(h.costates(1, k) - p[1]));
  }
  EXPECT_LT(e1, 0.5) << "p1 = 18 on the first arc";  // measured 0.16
  EXPECT_LT(e2, 0.25) << "p2 = 6 - 18t";             // measured 0.13
}

}  // namespace
}  // namespace ocpb
