// BvpRiccatiSolver: its solutions of the Newton system against a general sparse LU, on every
// layout PmpResidual has (both schemes, both terminal forms, a free final time, clipped
// controls).
#include <cmath>
#include <memory>
#include <string>

#include <gtest/gtest.h>
#include <Eigen/SparseLU>

#include "problems/registry.h"
#include "solvers/bvp_riccati_solver.h"
#include "solvers/indirect_newton.h"
#include "solvers/pmp_residual.h"
#include "tests/solvers/indirect_test_support.h"

namespace ocpb {
namespace {

// A point of smooth states and costates (and nu, T) for `pmp`.
Vec RiccatiTestPoint(const Ocp& ocp, const PmpResidual& pmp, double T) {
  const int N = pmp.intervals(), nx = ocp.nx();
  Mat X(nx, N + 1), P(nx, N + 1);
  for (int k = 0; k <= N; ++k) {
    for (int i = 0; i < nx; ++i) {
      X(i, k) = 0.7 * std::sin(0.09 * k + 1.3 * i) + 0.1 * i;
      P(i, k) = 0.6 * std::cos(0.07 * k + 0.4 * i) - 0.2;
    }
  }
  return pmp.Pack(X, P, Vec::Constant(pmp.num_multipliers(), 0.3), T);
}

// Solves J d = b by the sweep and by Eigen's SparseLU; expects the same d to 1e-9 relative.
void ExpectSweepMatchesSparseLu(PmpResidual* pmp, const Vec& z) {
  Vec F(pmp->size());
  double J = 0.0;
  ASSERT_TRUE(pmp->Evaluate(z, F, &J, true)) << pmp->FailureMessage();
  Vec b(pmp->size());
  for (int i = 0; i < b.size(); ++i) b[i] = std::sin(1.7 * i) + 0.5;
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(pmp->jacobian());
  ASSERT_EQ(lu.info(), Eigen::Success);
  const Vec expected = lu.solve(b);
  BvpRiccatiSolver sweep(*pmp);
  ASSERT_TRUE(sweep.Factorize());
  Vec d;
  ASSERT_TRUE(sweep.Solve(b, &d));
  EXPECT_LE((d - expected).lpNorm<Eigen::Infinity>(),
            1e-9 * std::max(1.0, expected.lpNorm<Eigen::Infinity>()));
  // A second right-hand side with the same factorization.
  const Vec b2 = -2.0 * b + Vec::Ones(b.size());
  ASSERT_TRUE(sweep.Solve(b2, &d));
  const Vec expected2 = lu.solve(b2);
  EXPECT_LE((d - expected2).lpNorm<Eigen::Infinity>(),
            1e-9 * std::max(1.0, expected2.lpNorm<Eigen::Infinity>()));
}

TEST(BvpRiccatiSolver, MatchesSparseLuOnEveryLayout) {
  for (const char* name :
       {"vanderpol", "lqr", "double-integrator", "double-integrator-free-time"}) {
    const auto ocp = MakeProblem(name, {}, 0);
    for (auto scheme : {PmpResidual::Scheme::kEuler, PmpResidual::Scheme::kTrapezoid}) {
      for (TerminalMode mode : {TerminalMode::kPenalty, TerminalMode::kHard}) {
        if (mode == TerminalMode::kHard && ocp->num_terminal() == 0) continue;
        SCOPED_TRACE(std::string(name) + " " + ToString(mode) +
                     (scheme == PmpResidual::Scheme::kEuler ? " euler" : " trapezoid"));
        const double T = ocp->free_final_time() ? 1.3 : ocp->tf();
        PmpResidual pmp(*ocp, TimeGrid::Uniform(ocp->t0(), T, 30), mode, scheme);
        ExpectSweepMatchesSparseLu(&pmp, RiccatiTestPoint(*ocp, pmp, T));
      }
    }
  }
}

// comm-path2d (nx = 5, five terminal multipliers), with the acceleration on its ball
// at some nodes and the rate clipped at others: the generalized Jacobian's blocks.
TEST(BvpRiccatiSolver, MatchesSparseLuOnCommWithClippedControls) {
  const auto ocp = MakeProblem("comm-path2d", {"channel=0", "tf=4"}, 1);
  const int N = 40;
  for (auto scheme : {PmpResidual::Scheme::kEuler, PmpResidual::Scheme::kTrapezoid}) {
    for (TerminalMode mode : {TerminalMode::kPenalty, TerminalMode::kHard}) {
      SCOPED_TRACE(std::string(ToString(mode)) +
                   (scheme == PmpResidual::Scheme::kEuler ? " euler" : " trapezoid"));
      PmpResidual pmp(*ocp, TimeGrid::Uniform(0.0, 4.0, N), mode, scheme);
      Mat X(5, N + 1), P(5, N + 1);
      for (int k = 0; k <= N; ++k) {
        X.col(k) << 20.0 - 0.1 * k, 40.0 - 0.3 * k, -0.5, -0.7 + 0.01 * k, 0.5 * k;
        const double s = k % 3 == 0 ? 0.6 : 0.05;
        // p3 over nine decades: the rate clipped at 0 at some nodes, at Rmax or free at others.
        P.col(k) << 0.3, -0.2, s * std::cos(k), s * std::sin(k), -std::pow(10.0, k % 9 - 4.0);
      }
      ExpectSweepMatchesSparseLu(&pmp, pmp.Pack(X, P, Vec::Constant(pmp.num_multipliers(), 0.5)));
    }
  }
}

// Newton with the sweep takes the steps it takes with KLU (the same iterates to roundoff) and
// never needs KLU on these problems (both schemes' Newton matrices, hard form, free time).
TEST(BvpRiccatiSolver, NewtonTakesKlusStepsWithoutFallingBack) {
  for (const char* name : {"vanderpol", "double-integrator", "double-integrator-free-time"}) {
    SCOPED_TRACE(name);
    const auto ocp = MakeProblem(name, {}, 0);
    const SolveResult klu = IndirectNewton().Solve(
        *ocp, Request(*ocp, 60, TerminalMode::kHard, {{"linear_solver", "klu"}}));
    const SolveResult sweep = IndirectNewton().Solve(
        *ocp, Request(*ocp, 60, TerminalMode::kHard, {{"linear_solver", "riccati"}}));
    ExpectConverged(klu);
    ExpectConverged(sweep);
    EXPECT_EQ(sweep.iterations, klu.iterations);
    EXPECT_NEAR(sweep.objective, klu.objective, 1e-10 * std::max(1.0, std::abs(klu.objective)));
    EXPECT_LE((sweep.states - klu.states).lpNorm<Eigen::Infinity>(), 1e-8);
    EXPECT_EQ(sweep.solver_stats.at("riccati_fallbacks"), 0.0);
  }
}

}  // namespace
}  // namespace ocpb
