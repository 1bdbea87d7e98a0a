// The Euler transcription is the very problem the Hamiltonian descent solves (DiscreteOcp with
// forward Euler): same objective, same gradient, and its defect multipliers are the discrete
// costates.
#include "transcriptions/euler.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "core/discrete_ocp.h"
#include "problems/registry.h"
#include "tests/core/test_problems.h"
#include "tests/transcriptions/nlp_test_util.h"
#include "transcriptions/collocation_nlp.h"

namespace ocpb {
namespace {

// z from controls U and the Euler-simulated states X (Euler layout: x_0, u_0, ..., x_N).
Vec EulerPoint(const CollocationNlp& nlp, const Mat& X, const Mat& U) {
  Vec z(nlp.num_variables());
  for (size_t j = 0; j < nlp.layout().states.size(); ++j) {
    z.segment(nlp.layout().states[j].offset, X.rows()) = X.col(j);
  }
  for (size_t i = 0; i < nlp.layout().controls.size(); ++i) {
    z.segment(nlp.layout().controls[i].offset, U.rows()) = U.col(i);
  }
  return z;
}

class EulerAgreesWithDiscreteOcp : public ::testing::TestWithParam<TerminalMode> {};

// At a feasible point the NLP objective is DiscreteOcp's J; with lambda_k = -Lambda_{k+1} the
// Lagrangian is stationary in x_1..x_N, its u-gradient is dJ/dU (the descent's gradient), and
// Costates() returns Lambda, column 0 included. Nonlinear problem, non-uniform grid.
TEST_P(EulerAgreesWithDiscreteOcp, ObjectiveGradientAndCostates) {
  const TerminalMode mode = GetParam();
  const testing::NonlinearTestOcp ocp;
  TranscriptionOptions options;
  options.grid = TimeGrid::FromPoints({0.0, 0.1, 0.25, 0.3, 0.5, 0.62, 0.8, 1.0});
  options.terminal = mode;
  const auto nlp_ptr = EulerTranscription().Transcribe(ocp, options);
  const auto& nlp = dynamic_cast<const CollocationNlp&>(*nlp_ptr);
  const int N = options.grid.intervals();

  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> dist(-1.0, 1.0);
  Mat U(2, N);
  for (int i = 0; i < U.size(); ++i) U(i) = dist(rng);
  const DiscreteOcp docp(ocp, options.grid, Integrator::kEuler, mode);
  Mat X, Lambda, G;
  const double J = docp.Simulate(U, &X);
  docp.Adjoint(U, X, &Lambda, &G);
  const Vec z = EulerPoint(nlp, X, U);

  double f;
  ASSERT_TRUE(nlp.Objective(z, &f));
  EXPECT_NEAR(f, J, 1e-12 * std::abs(J));
  Vec g(nlp.num_constraints());
  ASSERT_TRUE(nlp.Constraints(z, g));
  EXPECT_LT(g.head(N * 3).cwiseAbs().maxCoeff(), 1e-14);

  Vec lambda = Vec::Zero(nlp.num_constraints());
  for (int k = 0; k < N; ++k) lambda.segment(nlp.defect_row(k), 3) = -Lambda.col(k + 1);
  const Vec grad_L = testing::LagrangianGradient(nlp, z, 1.0, lambda);
  const auto& layout = nlp.layout();
  for (int k = 1; k <= N; ++k) {
    EXPECT_LT(grad_L.segment(layout.states[k].offset, 3).cwiseAbs().maxCoeff(),
              1e-12 * (1.0 + Lambda.cwiseAbs().maxCoeff()))
        << "stationarity in x_" << k;
  }
  for (int k = 0; k < N; ++k) {
    EXPECT_TRUE(grad_L.segment(layout.controls[k].offset, 2).isApprox(G.col(k), 1e-12))
        << "u_" << k << ": " << grad_L.segment(layout.controls[k].offset, 2).transpose() << " vs "
        << G.col(k).transpose();
  }
  const Mat P = nlp.Costates(z, lambda);
  ASSERT_EQ(P.cols(), N + 1);
  EXPECT_TRUE(P.isApprox(Lambda, 1e-12)) << "Costates\n" << P << "\nAdjoint\n" << Lambda;
}

INSTANTIATE_TEST_SUITE_P(BothModes,
                         EulerAgreesWithDiscreteOcp,
                         ::testing::Values(TerminalMode::kPenalty, TerminalMode::kHard));

// At the solution of the (quadratic) penalized double integrator the costates from the
// multipliers equal DiscreteOcp::Adjoint at the solution's controls, and dJ/dU vanishes.
TEST(EulerTranscription, CostatesAtTheOptimumEqualTheDiscreteAdjoint) {
  const auto ocp = MakeProblem("double-integrator", {}, 0);
  TranscriptionOptions options;
  options.grid = TimeGrid::Uniform(0.0, 1.0, 25);
  const auto nlp = EulerTranscription().Transcribe(*ocp, options);
  const testing::KktSolution sol = testing::SolveEqualityKkt(*nlp, nlp->StartingPoint());
  ASSERT_TRUE(sol.converged);
  const ControlTrajectory u = nlp->Controls(sol.z);
  ASSERT_EQ(u.interpolation(), ControlTrajectory::Interpolation::kPiecewiseConstant);
  const DiscreteOcp docp(*ocp, options.grid, Integrator::kEuler, TerminalMode::kPenalty);
  Mat X, Lambda, G;
  const double J = docp.Simulate(u.values(), &X);
  docp.Adjoint(u.values(), X, &Lambda, &G);
  double f;
  ASSERT_TRUE(nlp->Objective(sol.z, &f));
  EXPECT_NEAR(f, J, 1e-12 * J);
  EXPECT_TRUE(nlp->States(sol.z).isApprox(X, 1e-12));
  EXPECT_LT(G.cwiseAbs().maxCoeff(), 1e-9);
  const Mat P = nlp->Costates(sol.z, sol.lambda);
  EXPECT_LT((P - Lambda).cwiseAbs().maxCoeff(), 1e-8 * Lambda.cwiseAbs().maxCoeff())
      << "Costates\n"
      << P << "\nAdjoint\n"
      << Lambda;
}

// The starting point simulates the projected initial controls with Euler: it is feasible and
// its objective is DiscreteOcp's J for those controls.
TEST(EulerTranscription, StartingPointIsTheEulerSimulationOfTheGuess) {
  const auto ocp = MakeProblem("double-integrator-bounded", {}, 0);  // |u| <= 5
  TranscriptionOptions options;
  options.grid = TimeGrid::Uniform(0.0, 1.0, 10);
  Mat guess(1, 10);
  for (int k = 0; k < 10; ++k) guess(0, k) = 8.0 - 1.5 * k;  // 8, 6.5 exceed the bound
  options.initial_guess = ControlTrajectory::PiecewiseConstant(options.grid, guess);
  const auto nlp = EulerTranscription().Transcribe(*ocp, options);
  const Vec z = nlp->StartingPoint();
  const Mat U = nlp->Controls(z).values();
  EXPECT_EQ(U(0, 0), 5.0);
  EXPECT_EQ(U(0, 1), 5.0);
  EXPECT_EQ(U(0, 2), 5.0);
  EXPECT_EQ(U(0, 3), 3.5);
  Vec g(nlp->num_constraints());
  ASSERT_TRUE(nlp->Constraints(z, g));
  EXPECT_LT(g.cwiseAbs().maxCoeff(), 1e-14);
  const DiscreteOcp docp(*ocp, options.grid, Integrator::kEuler, TerminalMode::kPenalty);
  double f;
  ASSERT_TRUE(nlp->Objective(z, &f));
  EXPECT_NEAR(f, docp.Simulate(U, nullptr), 1e-12 * f);
  // The box is a variable bound; the first state is fixed to x0 by equal bounds.
  Vec zl, zu, gl, gu;
  nlp->Bounds(&zl, &zu, &gl, &gu);
  EXPECT_EQ(zl[2], -5.0);
  EXPECT_EQ(zu[2], 5.0);
  EXPECT_EQ(zl.head(2), ocp->x0());
  EXPECT_EQ(zu.head(2), ocp->x0());
  EXPECT_TRUE((gl.array() == 0.0).all() && (gu.array() == 0.0).all());
}

// With a path constraint, Euler also constrains (t_N, x_N, u_{N-1}): the node the common
// evaluator checks with the left limit of a piecewise-constant control.
TEST(EulerTranscription, PathConstraintAtTheFinalNodeUsesTheLastControl) {
  const testing::NonlinearTestOcp ocp;  // c = x1 + u1^2 - 3
  TranscriptionOptions options;
  options.grid = TimeGrid::Uniform(0.0, 1.0, 4);
  const auto nlp_ptr = EulerTranscription().Transcribe(ocp, options);
  const auto& nlp = dynamic_cast<const CollocationNlp&>(*nlp_ptr);
  EXPECT_EQ(nlp.num_constraints(), 4 * 3 + 5);
  Vec z = nlp.StartingPoint();
  z.segment(nlp.layout().states[4].offset, 3) << 0.25, 0.0, 0.0;
  z.segment(nlp.layout().controls[3].offset, 2) << 2.0, 0.0;
  Vec g(nlp.num_constraints());
  ASSERT_TRUE(nlp.Constraints(z, g));
  EXPECT_DOUBLE_EQ(g[nlp.path_row_begin() + 4], 0.25 + 4.0 - 3.0);
}

}  // namespace
}  // namespace ocpb
