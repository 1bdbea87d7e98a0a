// The Euler maximum principle (PmpResidual::Scheme::kEuler) and its fitted costates: the
// Jacobian against finite differences, and its solutions against the Euler NLP's optimum.
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/discrete_ocp.h"
#include "core/evaluator.h"
#include "problems/registry.h"
#include "solvers/euler_costate_fit.h"
#include "solvers/hamiltonian_descent.h"
#include "solvers/indirect_newton.h"
#include "solvers/registry.h"
#include "tests/solvers/indirect_test_support.h"

namespace ocpb {
namespace {

constexpr auto kEuler = PmpResidual::Scheme::kEuler;

// A point z of the right size from smooth states and costates (and nu, T).
Vec PointFor(const Ocp& ocp, const PmpResidual& pmp, double T) {
  const int N = pmp.grid().intervals(), nx = ocp.nx();
  Mat X(nx, N + 1), P(nx, N + 1);
  for (int k = 0; k <= N; ++k) {
    for (int i = 0; i < nx; ++i) {
      X(i, k) = 0.7 * std::sin(0.9 * k + 1.3 * i) + 0.1 * i;
      P(i, k) = 0.6 * std::cos(0.7 * k + 0.4 * i) - 0.2;
    }
  }
  return pmp.Pack(X, P, Vec::Constant(pmp.num_multipliers(), 0.3), T);
}

TEST(PmpResidualEuler, JacobianMatchesFiniteDifferences) {
  for (const char* name : {"vanderpol", "lqr", "double-integrator"}) {
    const auto ocp = MakeProblem(name, {}, 0);
    for (TerminalMode mode : {TerminalMode::kPenalty, TerminalMode::kHard}) {
      if (mode == TerminalMode::kHard && ocp->num_terminal() == 0) continue;
      SCOPED_TRACE(std::string(name) + " " + ToString(mode));
      const PmpResidual pmp(*ocp, TimeGrid::Uniform(ocp->t0(), ocp->tf(), 5), mode, kEuler);
      ExpectJacobianMatchesFiniteDifferences(*ocp, mode, PointFor(*ocp, pmp, ocp->tf()), kEuler);
    }
  }
}

TEST(PmpResidualEuler, JacobianMatchesFiniteDifferencesOnCommWithClippedControls) {
  const auto ocp = MakeProblem("comm-path2d", {"channel=0", "tf=4"}, 1);
  for (TerminalMode mode : {TerminalMode::kPenalty, TerminalMode::kHard}) {
    SCOPED_TRACE(ToString(mode));
    const PmpResidual pmp(*ocp, TimeGrid::Uniform(0.0, 4.0, 5), mode, kEuler);
    Mat X(5, 6), P(5, 6);
    for (int k = 0; k < 6; ++k) {
      X.col(k) << 20.0 - k, 40.0 - 3.0 * k, -0.5, -0.7 + 0.1 * k, 5.0 * k;
      // |p2| large at even nodes (acceleration on the ball), small at odd ones; rate interior.
      const double s = k % 2 == 0 ? 0.6 : 0.05;
      P.col(k) << 0.3, -0.2, s * std::cos(k), s * std::sin(k), -40.0 - k;
    }
    const Vec nu = Vec::Constant(pmp.num_multipliers(), 0.5);
    ExpectJacobianMatchesFiniteDifferences(*ocp, mode, pmp.Pack(X, P, nu), kEuler);
  }
}

// The free final time's row sum_k ds_k H_k and the T column, on both free-time problems.
TEST(PmpResidualEuler, FreeTimeJacobianMatchesFiniteDifferences) {
  const auto ocp = MakeProblem("double-integrator-free-time", {}, 0);
  for (TerminalMode mode : {TerminalMode::kPenalty, TerminalMode::kHard}) {
    SCOPED_TRACE(ToString(mode));
    const PmpResidual pmp(*ocp, TimeGrid::Uniform(0.0, 1.0, 5), mode, kEuler);
    ASSERT_TRUE(pmp.free_final_time());
    ExpectJacobianMatchesFiniteDifferences(*ocp, mode, PointFor(*ocp, pmp, 1.3), kEuler);
  }
}

// Newton evaluates its Jacobian where it evaluated last (the accepted trial), and PmpResidual
// then reuses that evaluation's node values (u*, f and L with their gradients): residual, J and
// Jacobian are bitwise a fresh evaluation's, on both schemes, both terminal forms, clipped
// controls (comm-path2d) and a free final time; after an evaluation at another point, and after
// a failed one, nothing stale is reused.
TEST(PmpResidual, JacobianAtTheLastEvaluatedPointIsBitwiseAFreshOne) {
  struct Case {
    const char* name;
    std::vector<std::string> params;
    double T;
  };
  for (const Case& c : {Case{"comm-path2d", {"channel=0", "tf=4"}, 4.0},
                        Case{"vanderpol", {}, 0.0},
                        Case{"double-integrator-free-time", {}, 1.3}}) {
    const auto ocp = MakeProblem(c.name, c.params, 1);
    for (const auto scheme : {PmpResidual::Scheme::kTrapezoid, kEuler}) {
      for (TerminalMode mode : {TerminalMode::kPenalty, TerminalMode::kHard}) {
        if (mode == TerminalMode::kHard && ocp->num_terminal() == 0) continue;
        SCOPED_TRACE(std::string(c.name) + " " + ToString(mode) +
                     (scheme == kEuler ? " euler" : " trapezoid"));
        const TimeGrid grid = TimeGrid::Uniform(ocp->t0(), ocp->tf(), 6);
        PmpResidual fresh(*ocp, grid, mode, scheme), reused(*ocp, grid, mode, scheme);
        const Vec z0 = PointFor(*ocp, fresh, c.T > 0.0 ? c.T : ocp->tf());
        Vec z1 = z0;
        for (int i = 0; i < z1.size(); ++i) z1[i] += 0.01 * std::sin(3.0 * i);
        // z1 with a NaN in x_N's last component: every node is evaluated at z1's values, then
        // the evaluation fails (a state row of the last interval is NaN).
        Vec bad = z1;
        bad[fresh.NodeColumn(grid.intervals()) + ocp->nx() - 1] =
            std::numeric_limits<double>::quiet_NaN();
        Vec F_fresh(fresh.size()), F(fresh.size()), F_reused(fresh.size());
        double J_fresh = 0.0, J = 0.0, J_reused = 0.0;
        ASSERT_TRUE(fresh.Evaluate(z0, F_fresh, &J_fresh, true)) << fresh.FailureMessage();
        const Mat jacobian_fresh = Mat(fresh.jacobian());
        // The structure built on demand has the layout's count of entries.
        EXPECT_EQ(fresh.jacobian().nonZeros(), fresh.structural_nonzeros());
        auto expect_fresh = [&]() {
          ASSERT_TRUE(reused.Evaluate(z0, F_reused, &J_reused, true)) << reused.FailureMessage();
          EXPECT_EQ(J_reused, J_fresh);
          EXPECT_EQ(F_reused, F_fresh);
          EXPECT_EQ(Mat(reused.jacobian()), jacobian_fresh);
        };
        ASSERT_TRUE(reused.Evaluate(z0, F, &J, false));
        expect_fresh();  // the values of the residual evaluation at z0 reused
        ASSERT_TRUE(reused.Evaluate(z1, F, &J, false));
        expect_fresh();  // z1's values are not z0's: evaluated afresh
        ASSERT_TRUE(reused.Evaluate(z0, F, &J, false));
        EXPECT_FALSE(reused.Evaluate(bad, F, &J, false));
        expect_fresh();  // the failed evaluation overwrote z0's node values
      }
    }
  }
}

// A line-search trial's evaluation is abandoned once the squares of its rows so far exceed the
// caller's bound (PmpResidual::Evaluate's abandon_above): never below the full sum of squares,
// always once the interval rows alone exceed it; otherwise F and J are the unbounded ones.
TEST(PmpResidual, EvaluationIsAbandonedOnlyAboveTheBound) {
  const auto ocp = MakeProblem("comm-path2d", {"channel=0", "tf=4"}, 1);
  for (const auto scheme : {PmpResidual::Scheme::kTrapezoid, kEuler}) {
    for (TerminalMode mode : {TerminalMode::kPenalty, TerminalMode::kHard}) {
      SCOPED_TRACE(std::string(ToString(mode)) + (scheme == kEuler ? " euler" : " trapezoid"));
      PmpResidual pmp(*ocp, TimeGrid::Uniform(0.0, 4.0, 8), mode, scheme);
      const Vec z = PointFor(*ocp, pmp, 4.0);
      Vec F(pmp.size()), F_bounded(pmp.size());
      double J = 0.0, J_bounded = 0.0;
      ASSERT_TRUE(pmp.Evaluate(z, F, &J, false));
      const double squares = F.squaredNorm();
      ASSERT_TRUE(pmp.Evaluate(z, F_bounded, &J_bounded, false, squares));
      EXPECT_EQ(F_bounded, F);
      EXPECT_EQ(J_bounded, J);
      // The initial and interval rows (all but the terminal ones) exceed half their own sum.
      const int interval_rows = pmp.IntervalRow(pmp.intervals());
      const double half = 0.5 * F.head(interval_rows).squaredNorm();
      EXPECT_FALSE(pmp.Evaluate(z, F_bounded, &J_bounded, false, half));
      EXPECT_EQ(pmp.failure(), PmpResidual::Failure::kAbandoned);
      EXPECT_GE(pmp.failure_node(), 0);
      EXPECT_LT(pmp.failure_node(), pmp.intervals());
    }
  }
}

// The identity behind the free-time row (and the descent's dJ/dT): for any controls U, with x
// their Euler states and lambda their discrete adjoint on the grid stretched to T,
// dJ/dT = sum_k ds_k H(x_k, u_k, lambda_{k+1}), against central differences of J(U, T).
TEST(PmpResidualEuler, FreeTimeRowIsTheDiscreteDerivativeOfJ) {
  const auto ocp = MakeProblem("double-integrator-free-time", {}, 0);
  const int N = 20;
  const double T = 1.7;
  const TimeGrid grid = TimeGrid::Uniform(0.0, 1.0, N).StretchedTo(T);
  for (TerminalMode mode : {TerminalMode::kPenalty, TerminalMode::kHard}) {
    Mat U(1, N);
    for (int k = 0; k < N; ++k) U(0, k) = 1.0 - 2.0 * k / (N - 1.0);
    const DiscreteOcp docp(*ocp, grid, Integrator::kEuler, mode);
    Mat X, Lambda, G;
    docp.Simulate(U, &X);
    docp.Adjoint(U, X, &Lambda, &G);
    double sum = 0.0;
    for (int k = 0; k < N; ++k) {
      sum += (grid.h(k) / T) * ocp->Hamiltonian(grid.t(k), X.col(k), U.col(k), Lambda.col(k + 1));
    }
    const double d = 1e-6;
    const double fd =
        (DiscreteOcp(*ocp, grid.StretchedTo(T + d), Integrator::kEuler, mode).Simulate(U, nullptr) -
         DiscreteOcp(*ocp, grid.StretchedTo(T - d), Integrator::kEuler, mode)
             .Simulate(U, nullptr)) /
        (2.0 * d);
    EXPECT_NEAR(sum, fd, 1e-7 * (1.0 + std::abs(fd))) << ToString(mode);
  }
}

// Newton on the Euler maximum principle from the descent (fitted costates) reaches the optimum
// of the Euler transcription's NLP: Ipopt + Euler on the same grid and terminal form.
TEST(IndirectNewtonEuler, PolishReachesTheEulerNlpOptimumOnCommPath2d) {
  const auto ocp = MakeProblem("comm-path2d", {"channel=0"}, 1);
  const int N = 100;
  for (TerminalMode mode : {TerminalMode::kPenalty, TerminalMode::kHard}) {
    SCOPED_TRACE(ToString(mode));
    const SolveResult descent = HamiltonianDescent().Solve(
        *ocp, Request(*ocp, N, TerminalMode::kPenalty, {{"max_iterations", "300"}}));
    const Mat P =
        FitEulerCostates(*ocp, descent.state_grid, mode, descent.controls.values(), descent.states);
    IndirectNewtonOptions no;
    no.scheme = IndirectNewtonOptions::Scheme::kEuler;
    const SolveResult newton =
        IndirectNewton(no).SolveFrom(*ocp, Request(*ocp, N, mode), descent.states, P);
    ExpectConverged(newton);
    ASSERT_EQ(newton.controls.interpolation(),
              ControlTrajectory::Interpolation::kPiecewiseConstant);
    // Its controls, simulated by the common evaluator, give its own Euler J.
    const Evaluation ev = Evaluate(*ocp, newton.controls, newton.state_grid, Integrator::kEuler);
    const double J = mode == TerminalMode::kHard ? ev.Jbar : ev.J;
    EXPECT_NEAR(J, newton.objective, 1e-10 * std::abs(newton.objective));
    if (mode == TerminalMode::kHard) {
      EXPECT_LE(ev.terminal_violation, 1e-8);
    }
    SolveRequest ipopt_request = Request(*ocp, N, mode);
    ipopt_request.transcription = "euler";
    const SolveResult ipopt = FindSolver("ipopt").make()->Solve(*ocp, ipopt_request);
    ASSERT_EQ(ipopt.status, SolveStatus::kConverged) << ipopt.message;
    EXPECT_NEAR(newton.objective, ipopt.objective, 1e-6 * std::abs(ipopt.objective));
    // It is a stationary point of the descent's discrete problem: theta ~ 0 there (penalty).
    if (mode == TerminalMode::kPenalty) {
      const DiscreteOcp docp(*ocp, newton.state_grid, Integrator::kEuler, mode);
      Mat X, Lambda, G, D;
      Vec scratch;
      docp.Simulate(newton.controls.values(), &X);
      docp.Adjoint(newton.controls.values(), X, &Lambda, &G);
      const double theta =
          HamiltonianDescent::Direction(docp, newton.controls.values(), X, Lambda, &D, &scratch);
      EXPECT_LE(std::abs(theta), 1e-8 * std::abs(newton.objective));
      EXPECT_LE(newton.objective, descent.objective);
    }
  }
}

// The fit: for stationary controls (the Euler optimum's), the fitted costates reproduce them,
// u*(x_k, p_{k+1}) = u_k, although the adjoint's terminal value is replaced.
TEST(EulerCostateFit, StationaryControlsKeepTheirCostates) {
  const auto ocp = MakeProblem("vanderpol", {}, 0);
  const int N = 60;
  const SolveResult descent = HamiltonianDescent().Solve(
      *ocp, Request(*ocp, N, TerminalMode::kPenalty, {{"max_iterations", "5000"}}));
  // Stationary to rounding (it ends at theta ~ 1e-15, where no Armijo step decreases J).
  ASSERT_LE(std::abs(descent.solver_stats.at("final_theta")), 1e-12) << descent.message;
  const Mat P = FitEulerCostates(
      *ocp, descent.state_grid, TerminalMode::kPenalty, descent.controls.values(), descent.states);
  EXPECT_LE((P - descent.costates).lpNorm<Eigen::Infinity>(),
            1e-5 * (1.0 + descent.costates.lpNorm<Eigen::Infinity>()));
  Vec u(1);
  for (int k = 0; k < N; ++k) {
    ocp->MinimizeHamiltonian(descent.state_grid.t(k), descent.states.col(k), P.col(k + 1), u);
    EXPECT_NEAR(u[0], descent.controls.values()(0, k), 1e-5) << k;
  }
  EXPECT_THROW(
      FitEulerCostates(
          *ocp, descent.state_grid, TerminalMode::kPenalty, Mat::Zero(1, N - 1), descent.states),
      std::invalid_argument);
}

}  // namespace
}  // namespace ocpb
