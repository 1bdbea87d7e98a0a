// The polish on the stage controls (solvers/stage_newton.h): Newton reaches the scheme's discrete
// optimum, where the descent stops at its Armijo floor; box bounds end in a KKT point; in the
// family (hamiltonian-polish, scheme=rk4) the hard form reaches the continuous optimum and the
// multipliers.
#include "solvers/stage_newton.h"

#include <cmath>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "core/costate_error.h"
#include "core/rk_tableau.h"
#include "core/stage_rk_ocp.h"
#include "problems/registry.h"
#include "solvers/hamiltonian_family.h"

namespace ocpb {
namespace {

// hager (LQ, closed form): from U = 0 Newton reaches the RK4 discrete optimum in a few steps;
// its J and node costates are then at RK4's order (the descent's costates stop at 2e-9 .. 2e-8:
// results/notes/2026-12-06-family-rk.md), and the residual falls at least linearly fast.
TEST(StageNewton, ReachesTheDiscreteOptimumOfRk4) {
  const std::unique_ptr<Ocp> ocp = MakeProblem("hager", {}, 1);
  const ProblemInfo& info = FindProblem("hager");
  const double J_star = (std::exp(3.0) - 1.0) / (2.0 + std::exp(3.0));
  double previous_error = NAN;
  for (int N : {50, 100}) {
    SCOPED_TRACE(N);
    const TimeGrid grid = TimeGrid::Uniform(ocp->t0(), ocp->tf(), N);
    const StageRkOcp srk(*ocp, grid, RkTableau::Classical4(), TerminalMode::kPenalty);
    Mat U = Mat::Zero(ocp->nu(), srk.controls());
    const StageNewtonOutcome out = StageNewton(srk, ocp->control_set(), {}, {}, &U);
    ASSERT_TRUE(out.converged) << out.why;
    EXPECT_EQ(out.code, "converged");
    EXPECT_LE(out.iterations, 6);
    EXPECT_LE(out.residual, 1e-10);
    EXPECT_LE(StageProjectedResidual(srk, ocp->control_set(), U), 1e-10);
    Mat X, Lambda, Y, P, G;
    const double J = srk.Simulate(U, &X);
    EXPECT_DOUBLE_EQ(J, out.J);
    const double error = std::abs(J - J_star);
    EXPECT_LT(error, 1e-9);
    srk.Adjoint(U, X, &Lambda, &Y, &P, &G);
    EXPECT_LT(RelativeCostateError(Lambda, grid, info.reference_costate), N == 50 ? 5e-9 : 3e-10);
    if (!std::isnan(previous_error)) EXPECT_GT(previous_error / error, 13.0);  // order 4
    previous_error = error;
  }
}

// A box that binds: the double integrator with |u| <= 5 in the penalty form. At Newton's end,
// every stage control strictly inside the box has H_u = 0, and at a bound H_u points outwards
// (the KKT conditions of the discrete problem, from an independent adjoint sweep).
TEST(StageNewton, EndsAtAKktPointOfTheBoxBounds) {
  const std::unique_ptr<Ocp> ocp = MakeProblem("double-integrator-bounded", {}, 1);
  const TimeGrid grid = TimeGrid::Uniform(ocp->t0(), ocp->tf(), 40);
  for (const RkTableau& tableau : {RkTableau::Heun(), RkTableau::Classical4()}) {
    const StageRkOcp srk(*ocp, grid, tableau, TerminalMode::kPenalty);
    Mat U = Mat::Zero(ocp->nu(), srk.controls());
    const StageNewtonOutcome out = StageNewton(srk, ocp->control_set(), {}, {}, &U);
    ASSERT_TRUE(out.converged) << out.why;
    Vec lower, upper;
    ocp->control_set().BoundingBox(&lower, &upper);
    Mat X, Lambda, Y, P, G;
    srk.Simulate(U, &X);
    srk.Adjoint(U, X, &Lambda, &Y, &P, &G);
    int at_bound = 0;
    for (int k = 0; k < srk.intervals(); ++k) {
      for (int i = 0; i < srk.stages(); ++i) {
        const int c = k * srk.stages() + i;
        const double Hu = G(0, c) / srk.StageWeight(k, i), u = U(0, c);
        ASSERT_GE(u, lower[0]);
        ASSERT_LE(u, upper[0]);
        if (u == lower[0]) {
          ++at_bound;
          EXPECT_GE(Hu, -1e-9) << c;
        } else if (u == upper[0]) {
          ++at_bound;
          EXPECT_LE(Hu, 1e-9) << c;
        } else {
          EXPECT_LE(std::abs(Hu), 1e-9) << c;
        }
      }
    }
    EXPECT_GT(at_bound, 0);  // the bound is active somewhere
  }
}

// The family's polish on RK4 in the hard terminal form (a multiplier loop of Newton solves): the
// double integrator's x(1) = 0 to 1e-8, J* = 6 and nu = p*(1) = (-12, 6) to RK4's accuracy at
// N = 20; the bounded one's continuous optimum within 1e-6 at N = 100 (Euler's polish is 9e-5
// off there: results/library/summary.md).
TEST(StageNewton, FamilyPolishOnRk4InTheHardForm) {
  const std::unique_ptr<Ocp> di = MakeProblem("double-integrator", {}, 1);
  SolveRequest r;
  r.grid = TimeGrid::Uniform(di->t0(), di->tf(), 20);
  r.terminal = TerminalMode::kHard;
  r.options = {{"scheme", "rk4"}};
  SolveResult s = HamiltonianFamily(HamiltonianFamily::Preset::kPolish).Solve(*di, r);
  ASSERT_EQ(s.status, SolveStatus::kConverged) << s.message;
  EXPECT_EQ(s.solver_status, "stage_newton_converged");
  EXPECT_LE(s.solver_stats.at("terminal_residual"), 1e-8);
  EXPECT_NEAR(s.objective, 6.0, 1e-6);
  EXPECT_NEAR(s.solver_stats.at("nu_0"), -12.0, 1e-4);
  EXPECT_NEAR(s.solver_stats.at("nu_1"), 6.0, 1e-4);
  EXPECT_NE(s.message.find("Newton (projected, truncated, on the rk4 stage controls"),
            std::string::npos)
      << s.message;

  const std::unique_ptr<Ocp> bounded = MakeProblem("double-integrator-bounded", {}, 1);
  r.grid = TimeGrid::Uniform(bounded->t0(), bounded->tf(), 100);
  s = HamiltonianFamily(HamiltonianFamily::Preset::kPolish).Solve(*bounded, r);
  ASSERT_EQ(s.status, SolveStatus::kConverged) << s.message;
  EXPECT_LE(s.solver_stats.at("terminal_residual"), 1e-8);
  const double reference = *FindProblem("double-integrator-bounded").reference_value;
  EXPECT_LT(std::abs(s.objective - reference) / reference, 1e-6) << s.objective;
}

}  // namespace
}  // namespace ocpb
