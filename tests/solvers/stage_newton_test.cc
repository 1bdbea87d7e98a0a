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
#include "core/timer.h"
#include "problems/registry.h"
#include "solvers/augmented_lagrangian_ocp.h"
#include "solvers/descent_loop.h"
#include "solvers/hamiltonian_family.h"
#include "solvers/solver.h"
#include "solvers/stage_descent_passes.h"

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
    if (!std::isnan(previous_error)) {
      EXPECT_GT(previous_error / error, 13.0);  // order 4
    }
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
  // The costates of the hard form: lambda_N = psi_x^T nu = nu (psi = x(1)), at the multipliers.
  ASSERT_EQ(s.costates.cols(), 21);
  EXPECT_NEAR(s.costates(0, 20), s.solver_stats.at("nu_0"), 1e-8);
  EXPECT_NEAR(s.costates(1, 20), s.solver_stats.at("nu_1"), 1e-8);

  const std::unique_ptr<Ocp> bounded = MakeProblem("double-integrator-bounded", {}, 1);
  r.grid = TimeGrid::Uniform(bounded->t0(), bounded->tf(), 100);
  s = HamiltonianFamily(HamiltonianFamily::Preset::kPolish).Solve(*bounded, r);
  ASSERT_EQ(s.status, SolveStatus::kConverged) << s.message;
  EXPECT_LE(s.solver_stats.at("terminal_residual"), 1e-8);
  const double reference = *FindProblem("double-integrator-bounded").reference_value;
  EXPECT_LT(std::abs(s.objective - reference) / reference, 1e-6) << s.objective;
}

// A ball and a box in one control set: the paper's problem without its channel map (acceleration
// in a disc, spectral efficiency >= 0), RK4 at N = 20, penalty form, from 250 descent steps.
// At Newton's end every stage control is a KKT point of its set: inside the disc H_u = 0 on
// the acceleration, on its circle H_u = -mu n with mu >= 0 (no tangential part); the spectral
// efficiency's H_u is 0 where it is positive and >= 0 at its bound. (Here the disc is not
// active; with umax small enough to make it active, 0.12 and 0.2, Newton stops at its
// iteration limit: results/notes/2026-12-07-family-rk4-polish.md.)
TEST(StageNewton, EndsAtAKktPointOfABoxWithABallInTheSet) {
  const std::unique_ptr<Ocp> ocp = MakeProblem("comm-path2d", {"channel=0"}, 1);
  const TimeGrid grid = TimeGrid::Uniform(ocp->t0(), ocp->tf(), 20);
  const StageRkOcp srk(*ocp, grid, RkTableau::Classical4(), TerminalMode::kPenalty);
  StageDescentPasses passes(srk, nullptr);
  const Mat U0 = DefaultInitialGuess(*ocp, grid).values();
  Mat U(ocp->nu(), srk.controls());
  for (int c = 0; c < U.cols(); ++c) {
    U.col(c) = U0.col(c / srk.stages());
    ocp->control_set().Project(U.col(c));
  }
  passes.Start(U);
  DescentLoopOptions loop;
  loop.max_iterations = 250;
  std::vector<IterationRecord> history;
  const Stopwatch clock;
  RunDescentLoop(loop, clock, &passes, &history);
  U = passes.U();
  const StageNewtonOutcome out = StageNewton(srk, ocp->control_set(), {}, {}, &U);
  ASSERT_TRUE(out.converged) << out.why;
  EXPECT_LE(out.J, passes.J());
  Mat X, Lambda, Y, P, G;
  srk.Simulate(U, &X);
  srk.Adjoint(U, X, &Lambda, &Y, &P, &G);
  int on_circle = 0, at_bound = 0;
  for (int k = 0; k < srk.intervals(); ++k) {
    for (int i = 0; i < srk.stages(); ++i) {
      const int c = k * srk.stages() + i;
      const Vec Hu = G.col(c) / srk.StageWeight(k, i);
      for (const ControlSet::Block& b : ocp->control_set().blocks()) {
        const Vec u = U.col(c).segment(b.offset, b.size);
        const Vec h = Hu.segment(b.offset, b.size);
        if (b.kind == ControlSet::Kind::kBall) {
          const Vec n = (u - b.center) / (u - b.center).norm();
          if ((u - b.center).norm() < b.radius - 1e-9) {
            EXPECT_LE(h.lpNorm<Eigen::Infinity>(), 1e-8) << c;
          } else {
            ++on_circle;
            EXPECT_LE(h.dot(n), 1e-8) << c;                                      // mu >= 0
            EXPECT_LE((h - h.dot(n) * n).lpNorm<Eigen::Infinity>(), 1e-8) << c;  // no tangent
          }
          continue;
        }
        for (int j = 0; j < b.size; ++j) {
          if (u[j] <= b.lower[j]) {
            ++at_bound;
            EXPECT_GE(h[j], -1e-8) << c;
          } else if (u[j] >= b.upper[j]) {
            ++at_bound;
            EXPECT_LE(h[j], 1e-8) << c;
          } else {
            EXPECT_LE(std::abs(h[j]), 1e-8) << c;
          }
        }
      }
    }
  }
  EXPECT_GT(at_bound, 0);  // the spectral efficiency's bound is active (the disc is not here)
}

// Each way StageNewton stops, and the multiplier loop's limit.
TEST(StageNewton, StopsForEachReasonAndSaysWhich) {
  const std::unique_ptr<Ocp> ocp = MakeProblem("vanderpol", {}, 1);
  const TimeGrid grid = TimeGrid::Uniform(ocp->t0(), ocp->tf(), 20);
  const StageRkOcp srk(*ocp, grid, RkTableau::Classical4(), TerminalMode::kPenalty);
  const Mat U0 = Mat::Zero(ocp->nu(), srk.controls());
  Mat U = U0;
  StageNewtonOptions options;
  options.max_iterations = 0;
  StageNewtonOutcome out = StageNewton(srk, ocp->control_set(), options, {}, &U);
  EXPECT_EQ(out.code, "max_iterations");
  EXPECT_FALSE(out.converged);
  EXPECT_NE(out.why.find("projected residual"), std::string::npos) << out.why;
  const Stopwatch clock;
  U = U0;
  out = StageNewton(srk, ocp->control_set(), {}, CpuLimit{&clock, 0.0}, &U);
  EXPECT_EQ(out.code, "max_cpu_seconds");
  U = U0;
  U(0, 3) = NAN;
  out = StageNewton(srk, ocp->control_set(), {}, {}, &U);
  EXPECT_EQ(out.code, "not_finite");
  EXPECT_TRUE(std::isnan(StageProjectedResidual(srk, ocp->control_set(), U)));

  // The hard form's loop with one outer iteration: rho = 1 leaves psi far from 0.
  const std::unique_ptr<Ocp> di = MakeProblem("double-integrator", {}, 1);
  const TimeGrid di_grid = TimeGrid::Uniform(di->t0(), di->tf(), 20);
  AugmentedLagrangianOcp al(*di, di_grid);
  const StageRkOcp hard(al, di_grid, RkTableau::Classical4(), TerminalMode::kHard);
  U = Mat::Zero(di->nu(), hard.controls());
  const StageAugmentedLagrangianOutcome a = StageNewtonAugmentedLagrangian(
      hard, &al, di->control_set(), {}, 1.0, 10.0, 1e10, 1e-10, 1, {}, &U);
  EXPECT_EQ(a.code, "max_outer_iterations");
  EXPECT_FALSE(a.converged);
  EXPECT_TRUE(a.last.converged);
  EXPECT_GT(a.terminal_residual, 1e-3);
  EXPECT_EQ(a.multipliers.size(), 2);

  // In the family: Newton's limit is the result's status, with its code.
  SolveRequest r;
  r.grid = TimeGrid::Uniform(di->t0(), di->tf(), 20);
  r.terminal = TerminalMode::kHard;
  r.options = {{"scheme", "rk4"}, {"newton_max_iterations", "1"}};
  const SolveResult s = HamiltonianFamily(HamiltonianFamily::Preset::kPolish).Solve(*di, r);
  EXPECT_EQ(s.status, SolveStatus::kMaxIterations) << s.message;
  EXPECT_EQ(s.solver_status, "stage_newton_max_iterations");
}

}  // namespace
}  // namespace ocpb
