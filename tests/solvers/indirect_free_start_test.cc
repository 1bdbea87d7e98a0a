// The indirect method with a free initial state and static parameters: the transversality rows
// p(t0) = -grad phi0 (clipped by x(t0)'s bounds) of PmpResidual, on free-start (analytic optimum,
// bound active or not) and double-integrator-time-parameter (T a static parameter, against the
// same problem posed with a free final time).
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "problems/reference/free_start.h"
#include "problems/registry.h"
#include "solvers/indirect_newton.h"
#include "solvers/judge.h"
#include "solvers/pmp_residual.h"
#include "solvers/registry.h"
#include "tests/solvers/indirect_test_support.h"

namespace ocpb {
namespace {

const PmpResidual::Scheme kSchemes[] = {PmpResidual::Scheme::kTrapezoid,
                                        PmpResidual::Scheme::kEuler};

// free-start with x1(0) in [lo, hi] (the default hi = 0.5 cuts the free optimum 8/9).
std::unique_ptr<Ocp> FreeStartWith(double hi) {
  return MakeProblem("free-start", {"hi=" + std::to_string(hi)}, 0);
}

SolveResult SolveIndirect(const Ocp& ocp,
                          const SolveRequest& request,
                          PmpResidual::Scheme scheme = PmpResidual::Scheme::kTrapezoid) {
  IndirectNewtonOptions o;
  o.scheme = scheme == PmpResidual::Scheme::kEuler ? IndirectNewtonOptions::Scheme::kEuler
                                                   : IndirectNewtonOptions::Scheme::kTrapezoid;
  return IndirectNewton(o).Solve(ocp, request);
}

// ---- the residual ------------------------------------------------------------------------------

// A point of free-start on 5 intervals with p2 > 0 (u* = -p1/p2 defined) where
// x1(0) - (p1(0) + w x1(0)) = 0.3 - (-1 + 0.3) = 1: inside [lo, hi] = [-1, 10], beyond hi = 0.5.
Vec FreeStartPoint(const PmpResidual& pmp) {
  Mat X(2, 6), P(2, 6);
  for (int k = 0; k < 6; ++k) {
    X.col(k) << 0.3 + 0.1 * k, 0.2 * k;
    P.col(k) << -1.0 + 0.1 * k, 1.0 + 0.05 * k;
  }
  return pmp.Pack(X, P, Vec());
}

TEST(PmpResidualFreeStart, TransversalityRowsMatchFiniteDifferences) {
  for (const auto scheme : kSchemes) {
    for (const double hi : {10.0, 0.5}) {  // the clip inactive, then active
      SCOPED_TRACE("scheme " + std::to_string(static_cast<int>(scheme)) + ", hi " +
                   std::to_string(hi));
      const auto ocp = FreeStartWith(hi);
      PmpResidual pmp(*ocp, TimeGrid::Uniform(0.0, 1.0, 5), TerminalMode::kHard, scheme);
      ASSERT_TRUE(pmp.free_initial_state());
      const Vec z = FreeStartPoint(pmp);
      Vec F(pmp.size());
      double J = 0.0;
      ASSERT_TRUE(pmp.Evaluate(z, F, &J, false)) << pmp.FailureMessage();
      // Row 0: p1(0) + w (x1(0) - a) = -1 + 0.3 inside; x1(0) - hi where the clip is active.
      EXPECT_NEAR(F[0], hi == 10.0 ? -0.7 : 0.3 - 0.5, 1e-15);
      EXPECT_EQ(F[1], 0.0);  // x2(0) = 0 fixed, and it is
      ExpectJacobianMatchesFiniteDifferences(*ocp, TerminalMode::kHard, z, scheme);
    }
  }
  // The discrete cost counts phi0(x(t0)): the same z with a = 0.3 (phi0 = 0) costs w/2 0.3^2
  // less.
  const auto shifted = MakeProblem("free-start", {"a=0.3"}, 0);
  const auto base = FreeStartWith(0.5);
  PmpResidual a(*base, TimeGrid::Uniform(0.0, 1.0, 5), TerminalMode::kHard);
  PmpResidual b(*shifted, TimeGrid::Uniform(0.0, 1.0, 5), TerminalMode::kHard);
  Vec F(a.size());
  double Ja = 0.0, Jb = 0.0;
  ASSERT_TRUE(a.Evaluate(FreeStartPoint(a), F, &Ja, false));
  ASSERT_TRUE(b.Evaluate(FreeStartPoint(b), F, &Jb, false));
  EXPECT_NEAR(Ja - Jb, 0.5 * 0.3 * 0.3, 1e-14);
}

TEST(PmpResidualFreeStart, StaticParameterRowMatchesFiniteDifferences) {
  const auto ocp = MakeProblem("double-integrator-time-parameter", {}, 0);
  for (const auto scheme : kSchemes) {
    for (const TerminalMode mode : {TerminalMode::kPenalty, TerminalMode::kHard}) {
      SCOPED_TRACE(ToString(mode));
      PmpResidual pmp(*ocp, TimeGrid::Uniform(0.0, 1.0, 5), mode, scheme);
      Mat X(3, 6), P(3, 6);
      for (int k = 0; k < 6; ++k) {
        X.col(k) << -1.0 + 0.2 * k, 0.3, 2.0 + 0.01 * k;
        P.col(k) << 0.5, -0.3 + 0.1 * k, 0.2 - 0.05 * k;
      }
      const Vec z = pmp.Pack(X, P, Vec::Constant(pmp.num_multipliers(), 0.4));
      Vec F(pmp.size());
      ASSERT_TRUE(pmp.Evaluate(z, F, nullptr, false)) << pmp.FailureMessage();
      EXPECT_DOUBLE_EQ(F[2], 0.2);  // p_T(0) (no initial cost; T = 2 inside [0.1, 100])
      EXPECT_DOUBLE_EQ(F[0], 0.0);  // x(0) = (-1, 0) fixed
      ExpectJacobianMatchesFiniteDifferences(*ocp, mode, z, scheme);
    }
  }
}

// ---- Newton on the analytic optima
// ---------------------------------------------------------------

TEST(IndirectNewtonFreeStart, ReachesTheAnalyticOptimumWithTheBoundActiveOrNot) {
  for (const auto scheme : kSchemes) {
    for (const double hi : {0.5, 2.0}) {
      SCOPED_TRACE("scheme " + std::to_string(static_cast<int>(scheme)) + ", hi " +
                   std::to_string(hi));
      const auto ocp = FreeStartWith(hi);
      const auto& problem = dynamic_cast<const FreeStart&>(*ocp);
      const FreeStart::Optimum best = problem.AnalyticOptimum();
      ASSERT_EQ(best.x1_start == 0.5, hi == 0.5);  // active with the default hi only
      const SolveRequest request = Request(*ocp, 20, TerminalMode::kHard);
      const SolveResult r = SolveIndirect(*ocp, request, scheme);
      ExpectConverged(r);
      ASSERT_EQ(r.initial_state.size(), 2);
      // u is constant at the optimum, which both schemes integrate exactly.
      EXPECT_NEAR(r.initial_state[0], best.x1_start, 1e-12);
      EXPECT_EQ(r.initial_state[1], 0.0);
      EXPECT_NEAR(r.objective, best.J, 1e-12);
      EXPECT_NEAR(r.costates(0, 0), problem.OptimalCostate()[0], 1e-10);
      const Judgement j = JudgeResult(*ocp, request, r);
      EXPECT_NEAR(j.fine.Jbar, best.J, 1e-10);
      EXPECT_TRUE(j.warnings.empty());
    }
  }
}

// The Riccati sweep starts from a fixed x_0: with transversality rows it declines every step
// and the sparse LU solves it, counted, to the same point.
TEST(IndirectNewtonFreeStart, RiccatiLinearSolverHandsEveryStepToTheSparseLu) {
  const auto ocp = FreeStartWith(2.0);
  const SolveResult klu = SolveIndirect(*ocp, Request(*ocp, 20, TerminalMode::kHard));
  const SolveResult riccati =
      SolveIndirect(*ocp, Request(*ocp, 20, TerminalMode::kHard, {{"linear_solver", "riccati"}}));
  ExpectConverged(riccati);
  EXPECT_EQ(riccati.solver_stats.at("riccati_fallbacks"), riccati.iterations);
  EXPECT_EQ(riccati.iterations, klu.iterations);
  EXPECT_NEAR(riccati.initial_state[0], klu.initial_state[0], 1e-14);
}

// warm_start=hamiltonian would run a descent that refuses a free initial state: refused up
// front, with the reason; warm_start=ipopt starts from Ipopt's trapezoid solution and converges.
TEST(IndirectNewtonFreeStart, HamiltonianWarmStartIsRefusedIpoptsWorks) {
  const auto ocp = FreeStartWith(2.0);
  const SolveResult refused =
      SolveIndirect(*ocp, Request(*ocp, 20, TerminalMode::kHard, {{"warm_start", "hamiltonian"}}));
  EXPECT_EQ(refused.status, SolveStatus::kNotApplicable);
  EXPECT_NE(refused.message.find("warm_start=hamiltonian"), std::string::npos) << refused.message;
  const SolveResult warm =
      SolveIndirect(*ocp, Request(*ocp, 20, TerminalMode::kHard, {{"warm_start", "ipopt"}}));
  ExpectConverged(warm);
  EXPECT_NEAR(warm.initial_state[0],
              dynamic_cast<const FreeStart&>(*ocp).AnalyticOptimum().x1_start,
              1e-10);
}

// T as a static parameter (its adjoint: p_T(0) = 0) is the free-final-time problem with t = T s:
// the same trapezoidal discretization, so the same discrete optimum as H(T) = 0 gives, second
// order in h towards T* = 18^(1/4).
TEST(IndirectNewtonStaticParameter, FinalTimeAsAParameterMatchesTheFreeFinalTimeForm) {
  const auto param = MakeProblem("double-integrator-time-parameter", {}, 0);
  const auto free_time = MakeProblem("double-integrator-free-time", {}, 0);
  const double T_star = std::pow(18.0, 0.25);
  double last_error = 0.0;
  for (const int N : {25, 50}) {
    SCOPED_TRACE(N);
    const SolveResult p = SolveIndirect(*param, Request(*param, N, TerminalMode::kHard));
    ExpectConverged(p);
    const SolveResult f = SolveIndirect(*free_time, Request(*free_time, N, TerminalMode::kHard));
    ExpectConverged(f);
    ASSERT_EQ(p.initial_state.size(), 3);
    EXPECT_NEAR(p.initial_state[2], f.state_grid.tf(), 1e-9);
    EXPECT_NEAR(p.objective, f.objective, 1e-9);
    // T stays constant along the solution (its dynamics are 0).
    EXPECT_LT((p.states.row(2).array() - p.initial_state[2]).abs().maxCoeff(), 1e-12);
    const double error = std::abs(p.initial_state[2] - T_star);
    EXPECT_LT(error, 2e-3);
    if (last_error > 0.0) {
      EXPECT_GT(last_error / error, 3.5);  // second order: about 4
    }
    last_error = error;
  }
}

}  // namespace
}  // namespace ocpb
