#include "transcriptions/single_shooting.h"

#include <cmath>
#include <random>
#include <set>
#include <stdexcept>

#include <gtest/gtest.h>

#include "core/derivative_check.h"
#include "core/discrete_ocp.h"
#include "core/evaluator.h"
#include "problems/registry.h"
#include "solvers/registry.h"
#include "tests/core/test_problems.h"

namespace ocpb {
namespace {

/// A nonlinear problem with every constraint group single shooting has:
///   x1' = x2 + u1 sin(x1) + u3,  x2' = u2 - x1 u3 + 0.3 x3,  x3' = cos(x2) u1 - 0.5 x3
///   L = x1^2 + u1^2 + u2 u3 + exp(0.2 x2),  phi = 0.5 x3^2,
///   psi = (x1 - 0.4, x2 x3),  c = x1 + u1^2 - 1.5,
///   U = ball{|(u1, u2)| <= 1.2} x box{-1 <= u3 <= 2}.
class ConstrainedTestOcp final : public AutoDiffOcp<ConstrainedTestOcp, 3, 3, 2, 1> {
 public:
  ConstrainedTestOcp() {
    SetDimensions(3, 3, 2, 1);
    SetHorizon(0.0, 1.5);
    Vec x0(3);
    x0 << 0.2, -0.1, 0.4;
    SetInitialState(x0);
    SetTerminalWeights(Vec::Constant(2, 5.0));
    ControlSet set;
    set.AddBall(2, 1.2);
    set.AddBox(Vec::Constant(1, -1.0), Vec::Constant(1, 2.0));
    SetControlSet(set);
  }
  std::string name() const override { return "constrained-test"; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 3>& x, const VecT<T, 3>& u, VecT<T, 3>* f) const {
    (*f)[0] = x[1] + u[0] * sin(x[0]) + u[2];
    (*f)[1] = u[1] - x[0] * u[2] + 0.3 * x[2];
    (*f)[2] = cos(x[1]) * u[0] - 0.5 * x[2];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 3>& x, const VecT<T, 3>& u) const {
    return x[0] * x[0] + u[0] * u[0] + u[1] * u[2] + exp(0.2 * x[1]);
  }
  template <class T>
  T EvalTerminalCost(const VecT<T, 3>& x) const {
    return 0.5 * x[2] * x[2];
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 3>& x, VecT<T, 2>* psi) const {
    (*psi)[0] = x[0] - 0.4;
    (*psi)[1] = x[1] * x[2];
  }
  template <class T>
  void EvalPathConstraints(double, const VecT<T, 3>& x, const VecT<T, 3>& u, VecT<T, 1>* c) const {
    (*c)[0] = x[0] + u[0] * u[0] - 1.5;
  }
};

TimeGrid NonUniformGrid(double tf) {
  return TimeGrid::FromPoints(
      {0.0, 0.1 * tf, 0.25 * tf, 0.3 * tf, 0.5 * tf, 0.62 * tf, 0.8 * tf, tf});
}

Vec RandomVector(int n, unsigned seed, double scale = 0.8) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> dist(-scale, scale);
  Vec v(n);
  for (int i = 0; i < n; ++i) v[i] = dist(rng);
  return v;
}

std::unique_ptr<TranscribedNlp> MakeShooting(const Ocp& ocp,
                                             const TimeGrid& grid,
                                             TerminalMode mode,
                                             Integrator integrator,
                                             NlpScaling scaling = NlpScaling()) {
  TranscriptionOptions options;
  options.grid = grid;
  options.terminal = mode;
  options.scaling = scaling;
  options.integrator = integrator;
  return SingleShooting().Transcribe(ocp, options);
}

Mat DenseJacobian(const Nlp& nlp, const Vec& z) {
  Vec values(nlp.jacobian_rows().size());
  EXPECT_TRUE(nlp.JacobianValues(z, values));
  Mat J = Mat::Zero(nlp.num_constraints(), nlp.num_variables());
  for (Eigen::Index k = 0; k < values.size(); ++k) {
    J(nlp.jacobian_rows()[k], nlp.jacobian_cols()[k]) += values[k];
  }
  return J;
}

Vec ConstraintValues(const Nlp& nlp, const Vec& z) {
  Vec g(nlp.num_constraints());
  EXPECT_TRUE(nlp.Constraints(z, g));
  return g;
}

TEST(SingleShooting, ObjectiveIsTheDiscreteCostAndTheEvaluatorsEulerCost) {
  const testing::NonlinearTestOcp ocp;
  const TimeGrid grid = NonUniformGrid(1.0);
  auto nlp = MakeShooting(ocp, grid, TerminalMode::kPenalty, Integrator::kEuler);
  ASSERT_EQ(nlp->num_variables(), 2 * grid.intervals());
  const Vec z = RandomVector(nlp->num_variables(), 3);
  double f = NAN;
  ASSERT_TRUE(nlp->Objective(z, &f));
  const Mat U = Eigen::Map<const Mat>(z.data(), 2, grid.intervals());
  const DiscreteOcp docp(ocp, grid, Integrator::kEuler, TerminalMode::kPenalty);
  EXPECT_DOUBLE_EQ(f, docp.Simulate(U, nullptr));
  const Evaluation ev = Evaluate(ocp, nlp->Controls(z), grid, Integrator::kEuler);
  EXPECT_NEAR(f, ev.J, 1e-12 * std::abs(ev.J));
  EXPECT_EQ(nlp->Controls(z).interpolation(), ControlTrajectory::Interpolation::kPiecewiseConstant);
  EXPECT_EQ(nlp->States(z).size(), 0);  // the interface's rule for single shooting
}

class SingleShootingDerivatives
    : public ::testing::TestWithParam<std::tuple<Integrator, TerminalMode>> {};

TEST_P(SingleShootingDerivatives, GradientMatchesFiniteDifferences) {
  const auto [integrator, mode] = GetParam();
  const testing::NonlinearTestOcp ocp;
  auto nlp = MakeShooting(ocp, NonUniformGrid(1.0), mode, integrator);
  const Vec z = RandomVector(nlp->num_variables(), 11);
  Vec grad(nlp->num_variables());
  ASSERT_TRUE(nlp->Gradient(z, grad));
  const Mat fd = CentralJacobian(
      [&](const Vec& v) {
        double f = NAN;
        EXPECT_TRUE(nlp->Objective(v, &f));
        return Vec::Constant(1, f);
      },
      z);
  EXPECT_LT((grad - fd.row(0).transpose()).norm(), 1e-7 * std::max(1.0, fd.norm()))
      << "analytic " << grad.transpose() << "\nfd " << fd;
}

TEST_P(SingleShootingDerivatives, ConstraintJacobianMatchesFiniteDifferences) {
  const auto [integrator, mode] = GetParam();
  const ConstrainedTestOcp ocp;
  auto nlp = MakeShooting(ocp, NonUniformGrid(1.5), mode, integrator);
  const int N = 7;
  const auto* ss = dynamic_cast<const SingleShootingNlp*>(nlp.get());
  ASSERT_NE(ss, nullptr);
  EXPECT_EQ(ss->num_terminal_rows(), mode == TerminalMode::kHard ? 2 : 0);
  EXPECT_EQ(ss->num_ball_rows(), N);
  EXPECT_EQ(ss->num_path_rows(), N + 1);
  const Vec z = RandomVector(nlp->num_variables(), 5, 0.6);
  const Mat J = DenseJacobian(*nlp, z);
  const Mat fd = CentralJacobian([&](const Vec& v) { return ConstraintValues(*nlp, v); }, z);
  EXPECT_LT((J - fd).cwiseAbs().maxCoeff(), 1e-7 * std::max(1.0, fd.cwiseAbs().maxCoeff()))
      << "analytic\n"
      << J << "\nfd\n"
      << fd;

  // The structure is valid and has no duplicate entries; every FD nonzero is declared.
  std::set<std::pair<int, int>> declared;
  for (size_t k = 0; k < nlp->jacobian_rows().size(); ++k) {
    const int r = nlp->jacobian_rows()[k], c = nlp->jacobian_cols()[k];
    ASSERT_TRUE(r >= 0 && r < nlp->num_constraints() && c >= 0 && c < nlp->num_variables());
    EXPECT_TRUE(declared.insert({r, c}).second) << "duplicate (" << r << ", " << c << ")";
  }
  for (int r = 0; r < fd.rows(); ++r) {
    for (int c = 0; c < fd.cols(); ++c) {
      if (std::abs(fd(r, c)) > 1e-9) {
        EXPECT_TRUE(declared.count({r, c})) << r << ", " << c;
      }
    }
  }
}

TEST_P(SingleShootingDerivatives, CostatesWithZeroMultipliersAreTheDiscreteAdjoint) {
  const auto [integrator, mode] = GetParam();
  const testing::NonlinearTestOcp ocp;
  const TimeGrid grid = NonUniformGrid(1.0);
  auto nlp = MakeShooting(ocp, grid, mode, integrator);
  const Vec z = RandomVector(nlp->num_variables(), 17);
  const Mat P = nlp->Costates(z, Vec::Zero(nlp->num_constraints()));
  const DiscreteOcp docp(ocp, grid, integrator, mode);
  const Mat U = Eigen::Map<const Mat>(z.data(), 2, grid.intervals());
  Mat X, Lambda, G;
  docp.Simulate(U, &X);
  docp.Adjoint(U, X, &Lambda, &G);
  ASSERT_EQ(P.rows(), 3);
  ASSERT_EQ(P.cols(), grid.size());
  EXPECT_TRUE(P.isApprox(Lambda, 1e-12)) << P << "\n\n" << Lambda;
}

INSTANTIATE_TEST_SUITE_P(BothIntegratorsBothModes,
                         SingleShootingDerivatives,
                         ::testing::Combine(::testing::Values(Integrator::kEuler, Integrator::kRk4),
                                            ::testing::Values(TerminalMode::kPenalty,
                                                              TerminalMode::kHard)));

// p_k is the derivative of the Lagrangian J + nu^T psi + sum mu_j c_j with respect to x_k when the
// Euler simulation restarts at x_k (computed here by an independent hand-written loop).
TEST(SingleShooting, EulerCostatesAreLagrangianSensitivities) {
  const ConstrainedTestOcp ocp;
  const TimeGrid grid = NonUniformGrid(1.5);
  const int N = grid.intervals();
  auto nlp = MakeShooting(ocp, grid, TerminalMode::kHard, Integrator::kEuler);
  const auto* ss = dynamic_cast<const SingleShootingNlp*>(nlp.get());
  const Vec z = RandomVector(nlp->num_variables(), 23, 0.6);
  const Vec lambda = RandomVector(nlp->num_constraints(), 29, 2.0);
  const Mat P = nlp->Costates(z, lambda);
  const Mat U = Eigen::Map<const Mat>(z.data(), 3, N);
  const Mat X = ss->SimulatedStates(z);
  for (int k : {0, 3, N}) {
    auto lagrangian_from = [&](const Vec& xk) {
      Vec x = xk, f(3), c(1), psi(2);
      Mat cx(1, 3), cu(1, 3);
      double sum = 0.0;
      for (int j = k; j <= N; ++j) {
        const Vec u = U.col(std::min(j, N - 1));
        // (Jacobian variants here and below: GCC 12 warns falsely, -Wstringop-overflow, on the
        // fixed-size copies inside AutoDiffOcp::PathConstraints / TerminalConstraints when they
        // are inlined into this test)
        ocp.PathConstraintsJacobian(grid.t(j), x, u, c, cx, cu);
        sum += lambda[ss->path_row() + j] * c[0];
        if (j == N) break;
        sum += grid.h(j) * ocp.RunningCost(grid.t(j), x, u);
        ocp.Dynamics(grid.t(j), x, u, f);
        x += grid.h(j) * f;
      }
      Mat psix(2, 3);
      ocp.TerminalConstraintsJacobian(x, psi, psix);
      sum += ocp.TerminalCost(x) + lambda.head(2).dot(psi);
      return Vec::Constant(1, sum);
    };
    const Mat fd = CentralJacobian(lagrangian_from, X.col(k));
    EXPECT_LT((P.col(k) - fd.row(0).transpose()).norm(), 1e-7 * std::max(1.0, fd.norm()))
        << "k = " << k << ": " << P.col(k).transpose() << " vs " << fd;
  }
}

TEST(SingleShooting, ScalingChangesOnlyTheVariablesAndTheObjective) {
  const ConstrainedTestOcp ocp;
  const TimeGrid grid = NonUniformGrid(1.5);
  NlpScaling scaling;
  scaling.objective = 0.01;
  scaling.control = Eigen::Vector3d(2.0, 0.5, 4.0);
  scaling.state = Eigen::Vector3d(10.0, 10.0, 10.0);  // no state variables: no effect
  auto plain = MakeShooting(ocp, grid, TerminalMode::kHard, Integrator::kRk4);
  auto scaled = MakeShooting(ocp, grid, TerminalMode::kHard, Integrator::kRk4, scaling);
  const Vec z = RandomVector(plain->num_variables(), 31, 0.6);
  const Vec d = scaling.control.replicate(grid.intervals(), 1);
  const Vec zs = z.cwiseQuotient(d);
  double f = NAN, fs = NAN;
  ASSERT_TRUE(plain->Objective(z, &f));
  ASSERT_TRUE(scaled->Objective(zs, &fs));
  EXPECT_NEAR(fs, 0.01 * f, 1e-14 * std::abs(f));
  EXPECT_TRUE(ConstraintValues(*scaled, zs).isApprox(ConstraintValues(*plain, z), 1e-14));
  EXPECT_TRUE(scaled->Controls(zs).values().isApprox(plain->Controls(z).values(), 1e-14));
  // Derivatives of the scaled NLP against its own finite differences.
  Vec grad(zs.size());
  ASSERT_TRUE(scaled->Gradient(zs, grad));
  const Mat fdg = CentralJacobian(
      [&](const Vec& v) {
        double val = NAN;
        EXPECT_TRUE(scaled->Objective(v, &val));
        return Vec::Constant(1, val);
      },
      zs);
  EXPECT_LT((grad - fdg.row(0).transpose()).norm(), 1e-7 * std::max(1.0, fdg.norm()));
  const Mat fdj = CentralJacobian([&](const Vec& v) { return ConstraintValues(*scaled, v); }, zs);
  EXPECT_LT((DenseJacobian(*scaled, zs) - fdj).cwiseAbs().maxCoeff(),
            1e-7 * fdj.cwiseAbs().maxCoeff());
  // Bounds: u3 in [-1, 2] becomes [-0.25, 0.5]; the ball's bounding box [-1.2, 1.2] scales too.
  Vec zl, zu, gl, gu;
  scaled->Bounds(&zl, &zu, &gl, &gu);
  EXPECT_DOUBLE_EQ(zl[2], -0.25);
  EXPECT_DOUBLE_EQ(zu[2], 0.5);
  EXPECT_DOUBLE_EQ(zu[0], 0.6);
  EXPECT_DOUBLE_EQ(zu[1], 2.4);
  // Costates are physical: scaled multipliers are objective_scale times the plain ones.
  const Vec lambda = RandomVector(plain->num_constraints(), 37);
  EXPECT_TRUE(scaled->Costates(zs, 0.01 * lambda).isApprox(plain->Costates(z, lambda), 1e-12));
}

TEST(SingleShooting, BoundsAndConstraintRowsFollowTheControlSet) {
  const ConstrainedTestOcp ocp;
  auto nlp =
      MakeShooting(ocp, TimeGrid::Uniform(0.0, 1.5, 4), TerminalMode::kHard, Integrator::kEuler);
  Vec zl, zu, gl, gu;
  nlp->Bounds(&zl, &zu, &gl, &gu);
  ASSERT_EQ(zl.size(), 12);
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(zl[3 * k + 2], -1.0);
    EXPECT_EQ(zu[3 * k + 2], 2.0);
    EXPECT_EQ(zu[3 * k], 1.2);  // the ball's bounding box
  }
  ASSERT_EQ(nlp->num_constraints(), 2 + 4 + 5);
  EXPECT_EQ(gl[0], 0.0);
  EXPECT_EQ(gu[1], 0.0);
  EXPECT_TRUE(std::isinf(gl[2]) && gl[2] < 0);
  EXPECT_NEAR(gu[2], 1.44, 1e-15);  // |(u1, u2)|^2 <= 1.2^2
  EXPECT_EQ(gu[6], 0.0);            // path rows c <= 0
  EXPECT_FALSE(nlp->HasHessian());
}

TEST(SingleShooting, StartingPointIsTheGuessProjectedOntoTheControlSet) {
  const ConstrainedTestOcp ocp;
  const TimeGrid grid = TimeGrid::Uniform(0.0, 1.5, 3);
  TranscriptionOptions options;
  options.grid = grid;
  Mat guess(3, 3);
  guess << 3.0, 0.1, 0.0,  //
      4.0, 0.2, 0.0,       //
      5.0, -7.0, 1.0;
  options.initial_guess = ControlTrajectory::PiecewiseConstant(grid, guess);
  const Vec z0 = SingleShooting().Transcribe(ocp, options)->StartingPoint();
  EXPECT_NEAR(z0[0], 1.2 * 0.6, 1e-15);  // (3, 4) scaled onto the ball of radius 1.2
  EXPECT_NEAR(z0[1], 1.2 * 0.8, 1e-15);
  EXPECT_EQ(z0[2], 2.0);  // box clip
  EXPECT_EQ(z0[4], 0.2);
  EXPECT_EQ(z0[5], -1.0);
  EXPECT_EQ(z0[8], 1.0);
}

TEST(SingleShooting, RejectsInvalidRequests) {
  const ConstrainedTestOcp ocp;
  TranscriptionOptions options;
  options.grid = TimeGrid::Uniform(0.0, 1.0, 10);  // horizon is [0, 1.5]
  EXPECT_THROW(SingleShooting().Transcribe(ocp, options), std::invalid_argument);
  options.grid = TimeGrid::Uniform(0.0, 1.5, 10);
  options.initial_guess = ControlTrajectory::Constant(options.grid, Vec::Zero(2));
  EXPECT_THROW(SingleShooting().Transcribe(ocp, options), std::invalid_argument);
  options.initial_guess.reset();
  options.scaling.control = Vec::Ones(2);
  EXPECT_THROW(SingleShooting().Transcribe(ocp, options), std::invalid_argument);
}

TEST(SingleShooting, EvaluationFailureIsReportedNotThrown) {
  // Huge controls make the double integrator's trajectory overflow.
  const auto ocp = MakeProblem("double-integrator", {}, 0);
  auto nlp =
      MakeShooting(*ocp, TimeGrid::Uniform(0.0, 1.0, 4), TerminalMode::kHard, Integrator::kEuler);
  const Vec z = Vec::Constant(4, 1e308);
  double f = 0.0;
  Vec grad(4), g(2), jac(nlp->jacobian_rows().size());
  EXPECT_FALSE(nlp->Objective(z, &f));
  EXPECT_FALSE(nlp->Gradient(z, grad));
  EXPECT_FALSE(nlp->Constraints(z, g));
  EXPECT_FALSE(nlp->JacobianValues(z, jac));
}

TEST(SingleShooting, IsRegistered) {
  const TranscriptionInfo& info = FindTranscription("single-shooting");
  EXPECT_EQ(info.make()->name(), "single-shooting");
}

}  // namespace
}  // namespace ocpb
