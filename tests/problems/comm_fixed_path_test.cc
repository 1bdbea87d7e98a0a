#include "problems/comm_fixed_path.h"

#include <cmath>
#include <memory>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>

#include "core/derivative_check.h"
#include "core/evaluator.h"
#include "problems/registry.h"

namespace ocpb {
namespace {

const Eigen::Vector2d kS(20.0, 40.0), kW(7.0, 9.0), kD(10.0, 5.0);

std::shared_ptr<const PlanarPath> DefaultPath(double fillet = 2.0) {
  return std::make_shared<PlanarPath>(std::vector<Eigen::Vector2d>{kS, kW, kD}, fillet);
}

TEST(PlanarPath, LengthAndEndpoints) {
  const auto sharp = DefaultPath(0.0);
  EXPECT_NEAR(sharp->length(), (kW - kS).norm() + (kD - kW).norm(), 1e-12);
  const auto path = DefaultPath(2.0);
  // Cut back r tan(phi/2) on both sides, add the arc r phi.
  const Eigen::Vector2d a = (kW - kS).normalized(), b = (kD - kW).normalized();
  const double phi = std::acos(a.dot(b));
  EXPECT_NEAR(path->length(), sharp->length() - 4.0 * std::tan(0.5 * phi) + 2.0 * phi, 1e-12);
  EXPECT_NEAR(path->length(), 38.405, 1e-3);
  Eigen::Vector2d q, dq;
  path->Evaluate(0.0, &q, &dq, nullptr);
  EXPECT_LT((q - kS).norm(), 1e-12);
  EXPECT_LT((dq - a).norm(), 1e-12);
  path->Evaluate(path->length(), &q, &dq, nullptr);
  EXPECT_LT((q - kD).norm(), 1e-12);
  EXPECT_LT((dq - b).norm(), 1e-12);
  // Beyond the ends the path continues along the end tangents.
  path->Evaluate(path->length() + 2.0, &q, nullptr, nullptr);
  EXPECT_LT((q - (kD + 2.0 * b)).norm(), 1e-12);
  path->Evaluate(-1.0, &q, nullptr, nullptr);
  EXPECT_LT((q - (kS - a)).norm(), 1e-12);
}

TEST(PlanarPath, ArcLengthParameterizationIsC1WithTheRightCurvature) {
  for (bool left : {false, true}) {
    // A right turn (the default) and a left turn (its mirror image).
    std::vector<Eigen::Vector2d> pts = {kS, kW, kD};
    if (left) {
      for (auto& p : pts) p[0] = 50.0 - p[0];
    }
    const PlanarPath path(pts, 2.0);
    const int n = 4000;
    Eigen::Vector2d q_prev, dq_prev;
    path.Evaluate(0.0, &q_prev, &dq_prev, nullptr);
    double max_jump = 0.0, max_speed_error = 0.0;
    for (int i = 1; i <= n; ++i) {
      const double s = path.length() * i / n, h = path.length() / n;
      Eigen::Vector2d q, dq;
      path.Evaluate(s, &q, &dq, nullptr);
      max_speed_error = std::max(max_speed_error, std::abs((q - q_prev).norm() / h - 1.0));
      max_jump = std::max(max_jump, (dq - dq_prev).norm());
      q_prev = q;
      dq_prev = dq;
    }
    EXPECT_LT(max_speed_error, 1e-4);  // |q'| = 1: arc-length parameterized, no jumps in q
    // q' continuous, |q''| <= 1/fillet: |dq' / step| <= 1/2 (the sharp corner jumps by ~0.99).
    EXPECT_LT(max_jump, 1.001 * 0.5 * path.length() / n);
    // q' and q'' against central differences at points inside the pieces.
    for (double s : {3.0, 20.0, 32.5, 33.0, 33.6, 36.0}) {
      Eigen::Vector2d q, dq, ddq;
      path.Evaluate(s, &q, &dq, &ddq);
      const Mat fd1 = CentralJacobian(
          [&](const Vec& v) {
            Eigen::Vector2d qq;
            path.Evaluate(v[0], &qq, nullptr, nullptr);
            return Vec(qq);
          },
          Vec::Constant(1, s));
      const Mat fd2 = CentralJacobian(
          [&](const Vec& v) {
            Eigen::Vector2d dd;
            path.Evaluate(v[0], nullptr, &dd, nullptr);
            return Vec(dd);
          },
          Vec::Constant(1, s));
      EXPECT_LT((fd1.col(0) - dq).norm(), 1e-8) << "s = " << s;
      EXPECT_LT((fd2.col(0) - ddq).norm(), 1e-7) << "s = " << s;
    }
  }
}

TEST(PlanarPath, RejectsBadInput) {
  EXPECT_THROW(PlanarPath({kS}, 1.0), std::invalid_argument);
  EXPECT_THROW(PlanarPath({kS, kS, kD}, 1.0), std::invalid_argument);
  EXPECT_THROW(PlanarPath({kS, kW, kD}, -1.0), std::invalid_argument);
  EXPECT_THROW(PlanarPath({kS, kW, kD}, 10.0), std::invalid_argument);  // cut-back 5.7 > 2.5
  EXPECT_THROW(PlanarPath({kS, kW, kS}, 1.0), std::invalid_argument);   // turns back
}

// Every derivative of the Ocp interface against central differences, at random interior points
// (on the lines and on the arc; away from piece boundaries, where q'' jumps).
TEST(CommFixedPath, DerivativesMatchFiniteDifferences) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (const auto& [k5, k6] : {std::pair{0.0, 0.0}, std::pair{0.7, 1.3}}) {
    CommFixedPath::Options o;
    o.power.k[4] = k5;
    o.power.k[5] = k6;
    const CommFixedPath ocp(o, DefaultPath(), std::make_shared<PathLossChannel>());
    for (double sigma : {5.0, 20.0, 32.9, 33.2, 36.5}) {
      Vec x(3), u(2), lambda(3), mu(0), nu(3);
      x << sigma, 0.8 + 0.5 * unit(rng), 80.0 + 50.0 * unit(rng);
      u << 0.3 * unit(rng), 3.0 + 2.5 * unit(rng);
      for (int i = 0; i < 3; ++i) lambda[i] = 5.0 * unit(rng);
      for (int i = 0; i < 3; ++i) nu[i] = 5.0 * unit(rng);
      const DerivativeCheck check = CheckOcpDerivatives(ocp, 1.0, x, u, lambda, mu, nu);
      EXPECT_LT(check.max_error, 1e-6) << "sigma = " << sigma << ", k5 = " << k5 << "\n"
                                       << check.log;
    }
  }
}

TEST(CommFixedPath, MinimizerBeatsBruteForce) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), logmag(-4.0, 1.0);
  for (const auto& [k5, k6] : {std::pair{0.0, 0.0}, std::pair{2.0, 3.0}}) {
    CommFixedPath::Options o;
    o.power.k[4] = k5;
    o.power.k[5] = k6;
    const CommFixedPath ocp(o, DefaultPath(), std::make_shared<PathLossChannel>());
    for (int trial = 0; trial < 24; ++trial) {
      Vec x(3), p(3), u(2), v(2);
      x << 19.0 * (1.0 + unit(rng)), trial % 8 == 0 ? 0.0 : 1.5 * unit(rng), 0.0;
      for (int i = 0; i < 3; ++i) p[i] = std::pow(10.0, logmag(rng)) * unit(rng);
      Eigen::Vector2d q;
      ocp.path().Evaluate(x[0], &q, nullptr, nullptr);
      double s;
      PathLossChannel().Evaluate(q, &s, nullptr, nullptr);
      p[2] = -std::log(2.0) * s / 0.130288 * std::pow(2.0, 7.0 * (0.5 + 0.5 * unit(rng)));
      ocp.MinimizeHamiltonian(0.0, x, p, u);
      ASSERT_LE(ocp.control_set().Violation(u), 0.0);
      const double h_star = ocp.Hamiltonian(0.0, x, u, p);
      double best = INFINITY;
      for (int iu = 0; iu <= 400; ++iu) {
        for (int iR = 0; iR <= 60; iR += 4) {
          v << -0.5 + iu / 400.0, 6.0 * iR / 60.0;
          best = std::min(best, ocp.Hamiltonian(0.0, x, v, p));
        }
      }
      for (int iR = 0; iR <= 6000; ++iR) {
        v << u[0], 6.0 * iR / 6000.0;
        best = std::min(best, ocp.Hamiltonian(0.0, x, v, p));
      }
      for (int i = 0; i < 2000; ++i) {
        v = u + Eigen::Vector2d(unit(rng), unit(rng)) * std::pow(10.0, -1.0 - (i % 6));
        ocp.control_set().Project(v);
        best = std::min(best, ocp.Hamiltonian(0.0, x, v, p));
      }
      EXPECT_LE(h_star, best + 1e-12 * (1.0 + std::abs(best)))
          << "x = " << x.transpose() << "\np = " << p.transpose() << "\nu* = " << u.transpose();
    }
  }
}

// u = R = 0: J = C1 length^2 + C3 c^2 + gamma k4 tf.
TEST(CommFixedPath, InitialCost) {
  const CommFixedPath ocp(
      CommFixedPath::Options(), DefaultPath(), std::make_shared<PathLossChannel>());
  const TimeGrid grid = TimeGrid::Uniform(0.0, 40.0, 400);
  const Evaluation ev =
      Evaluate(ocp, ControlTrajectory::Constant(grid, Vec::Zero(2)), grid, Integrator::kEuler);
  const double L = ocp.path().length();
  EXPECT_NEAR(ev.J, 10.0 * L * L + 10.0 * 150.0 * 150.0 + 470.0, 1e-6);
  EXPECT_NEAR(ev.Jbar, 470.0, 1e-9);
}

TEST(CommFixedPath, RegistryEntryAndValidation) {
  const ProblemInfo& info = FindProblem("comm-fixed-path");
  EXPECT_EQ(info.default_intervals, 400);
  const auto ocp = MakeProblem("comm-fixed-path", {"channel=0", "fillet=0"}, 1);
  EXPECT_EQ(ocp->nx(), 3);
  EXPECT_EQ(ocp->nu(), 2);
  EXPECT_EQ(ocp->num_terminal(), 3);
  EXPECT_NEAR(static_cast<const CommFixedPath&>(*ocp).path().length(),
              (kW - kS).norm() + (kD - kW).norm(),
              1e-12);
  EXPECT_THROW(MakeProblem("comm-fixed-path", {"channel=0", "W=20,40"}, 1), std::invalid_argument);
  EXPECT_THROW(MakeProblem("comm-fixed-path", {"channel=0", "fillet=20"}, 1),
               std::invalid_argument);
  EXPECT_THROW(MakeProblem("comm-fixed-path", {"channel=0", "W=70,9"}, 1), std::invalid_argument);
}

}  // namespace
}  // namespace ocpb
