// The double integrators (problems/double_integrator.h; J* = 6 and 6.0450277563) as reference
// problems: costates of the Hamiltonian method and of Ipopt against p* = (-12, 12t - 6), and the
// bounded variant's reference value.
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

// p*(t) = (-12, 12t - 6) for H = p^T f + L (u* = -p2 = 6 - 12t).
Eigen::Vector2d Costate(double t) { return Eigen::Vector2d(-12.0, 12.0 * t - 6.0); }

// The Hamiltonian method (penalty form, C = 1e4, forward Euler N = 100) converges on this
// quadratic to Ipopt's optimum of the same discrete problem (the Euler transcription in penalty
// form), with the same costates (its exact discrete adjoint equals the multiplier-based estimate
// at a KKT point). Against p*: measured max errors 0.008 (p1) and 0.064 (p2), from the Euler
// grid (O(h)) and the penalty (p(1) = 2 C psi(x(1)) instead of the hard form's multiplier).
TEST(DoubleIntegrator, HamiltonianCostatesMatchTheNlpAndTheAnalyticOnes) {
  const auto ocp = MakeProblem("double-integrator", {"C=1e4"}, 0);
  const int N = 100;
  const SolveResult h =
      SolveWithHamiltonian(*ocp, N, {{"max_iterations", "2000"}, {"theta_tolerance", "1e-9"}});
  ASSERT_EQ(h.status, SolveStatus::kConverged) << h.solver_status << " " << h.message;
  const SolveResult ipopt = SolveWithIpopt(*ocp, "euler", N, TerminalMode::kPenalty);
  ASSERT_EQ(ipopt.status, SolveStatus::kConverged);
  EXPECT_NEAR(h.objective, ipopt.objective, 1e-9 * ipopt.objective);
  ASSERT_EQ(h.costates.cols(), N + 1);
  ASSERT_EQ(ipopt.costates.cols(), N + 1);
  EXPECT_LT((h.costates - ipopt.costates).cwiseAbs().maxCoeff(), 1e-4);
  double e1 = 0.0, e2 = 0.0;
  for (int k = 0; k <= N; ++k) {
    const Eigen::Vector2d p = Costate(h.state_grid.t(k));
    e1 = std::max(e1, std::abs(h.costates(0, k) - p[0]));
    e2 = std::max(e2, std::abs(h.costates(1, k) - p[1]));
  }
  EXPECT_LT(e1, 0.02);
  EXPECT_LT(e2, 0.1);
  EXPECT_LT(RelativeError(FineEvaluation(*ocp, h, N).Jbar, 6.0), 3e-3);  // measured 1.4e-3
}

// Ipopt, hard form, Hermite-Simpson N = 20: the multiplier-based costates at nodes and
// midpoints, and the cost. p* is linear and u* too, so the scheme is exact up to Ipopt's
// tolerance.
TEST(DoubleIntegrator, IpoptCostatesMatchTheAnalyticOnes) {
  const auto ocp = MakeProblem("double-integrator", {}, 0);
  const SolveResult r = SolveWithIpopt(*ocp, "hermite-simpson", 20);
  ASSERT_EQ(r.status, SolveStatus::kConverged);
  ASSERT_EQ(r.costates.cols(), r.state_grid.size());
  for (int j = 0; j < r.state_grid.size(); ++j) {
    const double t = r.state_grid.t(j);
    EXPECT_LT((r.costates.col(j) - Costate(t)).cwiseAbs().maxCoeff(), 1e-6) << "t = " << t;
  }
  EXPECT_LT(RelativeError(FineEvaluation(*ocp, r, 20).Jbar, 6.0), 1e-8);
}

// NLopt on single shooting (hard form: |u| <= 5 as bounds, psi = 0 as two dense rows), N = 100:
// SLSQP and AUGLAG(L-BFGS) reach the optimum of the Euler discretization, which Ipopt finds on
// the Euler transcription (6.0455684); its O(h) error is what separates it from J* (measured
// 8.94e-5 for both).
TEST(DoubleIntegratorBounded, NloptReachesTheReference) {
  const double reference = 6.0450277563;
  const auto ocp = MakeProblem("double-integrator-bounded", {}, 0);
  const SolveResult ipopt = SolveWithIpopt(*ocp, "euler", 100);
  ASSERT_EQ(ipopt.status, SolveStatus::kConverged);
  for (const char* algorithm : {"LD_SLSQP", "AUGLAG"}) {
    SolveRequest request = Request(*ocp, 100, TerminalMode::kHard, "single-shooting");
    request.options.Set("algorithm", algorithm);
    const SolveResult r = SolveWith("nlopt", *ocp, request);
    ASSERT_EQ(r.status, SolveStatus::kConverged) << algorithm << ": " << r.message;
    EXPECT_NEAR(r.objective, ipopt.objective, 1e-8 * ipopt.objective) << algorithm;
    const Evaluation fine = FineEvaluation(*ocp, r, 100);
    EXPECT_LT(RelativeError(fine.Jbar, reference), 1e-4) << algorithm << ": " << fine.Jbar;
    EXPECT_GT(fine.Jbar, reference) << algorithm;  // a feasible control cannot beat J*
    EXPECT_LT(fine.terminal_violation, 1e-6) << algorithm;
    EXPECT_EQ(fine.control_violation, 0.0) << algorithm;
  }
}

// The Hamiltonian method converges slowly here: where u* saturates the descent direction
// u*(p) - u is clipped, and the penalty C = 1e4 (needed for the penalty optimum to come within
// 0.2% of J*) makes the Armijo steps short. Measured at N = 50: after 10000 iterations (0.4 s)
// Jbar_fine = 6.0638, 0.31% above J*, still at the iteration limit (5000: 2.7%; C = 1000
// converges in 22000 iterations but to a penalty optimum 1.7% below J*). The penalty optimum
// itself (Ipopt on the Euler transcription, same C and grid) is 0.13% below J*. The stated
// tolerance, 0.5%, is thus the descent's unfinished convergence plus the penalty's offset.
TEST(DoubleIntegratorBounded, HamiltonianApproachesTheReference) {
  const double reference = 6.0450277563;
  const auto ocp = MakeProblem("double-integrator-bounded", {"C=1e4"}, 0);
  const int N = 50;
  const SolveResult h = SolveWithHamiltonian(*ocp, N, {{"max_iterations", "10000"}});
  EXPECT_EQ(h.status, SolveStatus::kMaxIterations) << h.solver_status << " " << h.message;
  const SolveResult ipopt = SolveWithIpopt(*ocp, "euler", N, TerminalMode::kPenalty);
  ASSERT_EQ(ipopt.status, SolveStatus::kConverged);
  // The same discrete problem: the descent stays above its optimum and approaches it.
  EXPECT_GE(h.objective, ipopt.objective * (1.0 - 1e-9));
  EXPECT_LT(RelativeError(h.objective, ipopt.objective), 6e-3);  // measured 0.45%
  const double penalty_optimum = FineEvaluation(*ocp, ipopt, N).Jbar;
  EXPECT_LT(RelativeError(penalty_optimum, reference), 2e-3) << penalty_optimum;
  const Evaluation fine = FineEvaluation(*ocp, h, N);
  EXPECT_LT(RelativeError(fine.Jbar, reference), 5e-3) << "Jbar_fine = " << fine.Jbar;
  EXPECT_EQ(fine.control_violation, 0.0);
}

}  // namespace
}  // namespace ocpb
