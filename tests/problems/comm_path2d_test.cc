#include "problems/comm_path2d.h"

#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/derivative_check.h"
#include "core/evaluator.h"
#include "problems/channel/channel_map.h"
#include "problems/registry.h"

namespace ocpb {
namespace {

std::shared_ptr<const ChannelQuality> PaperPathLoss() {
  return std::make_shared<PathLossChannel>();
}

CommPath2d::Options WithK56(double k5, double k6) {
  CommPath2d::Options o;
  o.power.k[4] = k5;
  o.power.k[5] = k6;
  return o;
}

TEST(CommPowerModel, KOfThePaper) {
  CommPowerModel m;
  EXPECT_NEAR(m.K(), 0.130288, 5e-7);
}

TEST(PathLossChannel, ValueMatchesThePathLossFormula) {
  const PathLossChannel channel;  // K_PL = -41.34, n_PL = 3.86, N0 = -110 dBm, base (5, 5)
  double s = 0.0;
  channel.Evaluate(Eigen::Vector2d(20.0, 40.0), &s, nullptr, nullptr);
  const double d = std::sqrt(15.0 * 15.0 + 35.0 * 35.0 + 0.01);
  const double cnr = std::pow(10.0, (-41.34 - 38.6 * std::log10(d)) / 10.0) / 1e-11;
  EXPECT_NEAR(s, 1.0 / cnr / 1000.0, 1e-9 * s);
}

TEST(PathLossChannel, GradientAndHessianMatchFiniteDifferences) {
  const PathLossChannel channel;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> pos(0.0, 50.0);
  for (int trial = 0; trial < 20; ++trial) {
    const Vec q = Eigen::Vector2d(pos(rng), pos(rng));
    double s;
    Eigen::Vector2d g;
    Eigen::Matrix2d h;
    channel.Evaluate(q, &s, &g, &h);
    const Mat fd_g = CentralJacobian(
        [&](const Vec& v) {
          double sv;
          channel.Evaluate(v, &sv, nullptr, nullptr);
          return Vec::Constant(1, sv);
        },
        q);
    const Mat fd_h = CentralJacobian(
        [&](const Vec& v) {
          double sv;
          Eigen::Vector2d gv;
          channel.Evaluate(v, &sv, &gv, nullptr);
          return Vec(gv);
        },
        q);
    EXPECT_LT((fd_g.transpose() - g).norm(), 1e-6 * g.norm()) << "q = " << q.transpose();
    EXPECT_LT((fd_h - h).norm(), 1e-6 * h.norm()) << "q = " << q.transpose();
  }
}

// A bicubic channel map (the kind the paper's problem uses) of a smooth, non-radial s on a
// 0.5 m grid: path loss times a log-normal-like ripple. Cheap to build, unlike the simulated one.
std::shared_ptr<const ChannelQuality> RippleMap() {
  const GridSpec grid = GridSpec::Workspace(50.0, 50.0, 0.5);
  const PathLossChannel path_loss;
  Eigen::MatrixXd s(grid.nx, grid.ny);
  for (int i = 0; i < grid.nx; ++i) {
    for (int j = 0; j < grid.ny; ++j) {
      const Eigen::Vector2d q = grid.Point(i, j);
      path_loss.Evaluate(q, &s(i, j), nullptr, nullptr);
      s(i, j) *= std::exp(0.8 * std::sin(q[0] / 3.0) * std::cos(q[1] / 4.0));
    }
  }
  return std::make_shared<ChannelMap>(grid, s, MapOptions(), "ripple test map");
}

// Every derivative of the Ocp interface against central differences, at random interior points
// (speed and acceleration away from 0), for k5 = k6 = 0 and for k5, k6 > 0, on the smooth
// path-loss channel and on a bicubic map.
TEST(CommPath2d, DerivativesMatchFiniteDifferences) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> pos(2.0, 48.0), vel(-1.5, 1.5), unit(-1.0, 1.0);
  const auto map = RippleMap();
  for (const auto& [k5, k6, channel] : {std::tuple{0.0, 0.0, PaperPathLoss()},
                                        std::tuple{0.7, 1.3, PaperPathLoss()},
                                        std::tuple{0.0, 0.0, map},
                                        std::tuple{0.7, 1.3, map}}) {
    const CommPath2d ocp(WithK56(k5, k6), channel);
    for (int trial = 0; trial < 10; ++trial) {
      Vec x(5), u(3), lambda(5), mu(0), nu(5);
      x << pos(rng), pos(rng), vel(rng), vel(rng), 100.0 * (1.0 + unit(rng));
      u << 0.3 * unit(rng), 0.3 * unit(rng), 3.0 + 2.5 * unit(rng);
      for (int i = 0; i < 5; ++i) lambda[i] = 5.0 * unit(rng);
      for (int i = 0; i < 5; ++i) nu[i] = 5.0 * unit(rng);
      const DerivativeCheck check = CheckOcpDerivatives(ocp, 1.0, x, u, lambda, mu, nu);
      EXPECT_LT(check.max_error, 1e-6) << "k5 = " << k5 << "\n" << check.log;
    }
  }
}

// The hand-written values and gradients equal forward-mode AD of the template definition (which
// also gives the Hessians), so the two faces of the problem cannot drift apart.
TEST(CommPath2d, HandWrittenDerivativesMatchTheTemplate) {
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> pos(0.0, 50.0), vel(-1.5, 1.5), unit(-1.0, 1.0);
  for (const auto& [k5, k6] : {std::pair{0.0, 0.0}, std::pair{0.7, 1.3}}) {
    const CommPath2d ocp(WithK56(k5, k6), PaperPathLoss());
    for (int trial = 0; trial < 20; ++trial) {
      Vec x(5), u(3);
      x << pos(rng), pos(rng), vel(rng), vel(rng), 150.0 * unit(rng);
      u << 0.3 * unit(rng), 0.3 * unit(rng), 3.0 + 3.0 * unit(rng);
      if (trial == 0) x[2] = x[3] = u[0] = u[1] = 0.0;  // at rest
      using J = Jet1<8>;
      VecT<J, 5> xj;
      VecT<J, 3> uj;
      for (int i = 0; i < 5; ++i) xj[i] = J::Variable(x[i], i);
      for (int i = 0; i < 3; ++i) uj[i] = J::Variable(u[i], 5 + i);
      const J L_ad = ocp.EvalRunningCost(0.0, xj, uj);
      VecT<J, 5> f_ad;
      ocp.EvalDynamics(0.0, xj, uj, &f_ad);

      double L;
      Vec Lx(5), Lu(3), f(5), f2(5);
      Mat fx(5, 5), fu(5, 3);
      ocp.RunningCostGradient(0.0, x, u, &L, Lx, Lu);
      ocp.DynamicsJacobian(0.0, x, u, f, fx, fu);
      ocp.Dynamics(0.0, x, u, f2);
      EXPECT_EQ(L, ocp.RunningCost(0.0, x, u));
      EXPECT_NEAR(L, L_ad.a, 1e-13 * std::abs(L_ad.a));
      EXPECT_EQ(ocp.RunningCost(0.0, x, u),
                ocp.EvalRunningCost(0.0, VecT<double, 5>(x), VecT<double, 3>(u)));
      for (int i = 0; i < 5; ++i) {
        EXPECT_NEAR(Lx[i], L_ad.g[i], 1e-12 * (1.0 + std::abs(L_ad.g[i]))) << "Lx " << i;
        EXPECT_EQ(f[i], f_ad[i].a);
        EXPECT_EQ(f2[i], f_ad[i].a);
        for (int j = 0; j < 5; ++j) EXPECT_EQ(fx(i, j), f_ad[i].g[j]);
        for (int j = 0; j < 3; ++j) EXPECT_EQ(fu(i, j), f_ad[i].g[5 + j]);
      }
      for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(Lu[i], L_ad.g[5 + i], 1e-12 * (1.0 + std::abs(L_ad.g[5 + i]))) << "Lu " << i;
      }
    }
  }
}

// The hand-written PointHessian equals the Jet2 Hessian of the template (the base class's
// PointHessian, called non-virtually) at random points, at rest and on the bicubic map, whatever
// lambda (the dynamics are affine); finite differences check it in
// DerivativesMatchFiniteDifferences.
TEST(CommPath2d, HandWrittenHessianMatchesTheTemplate) {
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> pos(2.0, 48.0), vel(-1.5, 1.5), unit(-1.0, 1.0);
  const auto map = RippleMap();
  for (const auto& [k5, k6, channel] : {std::tuple{0.0, 0.0, PaperPathLoss()},
                                        std::tuple{0.7, 1.3, PaperPathLoss()},
                                        std::tuple{0.7, 1.3, map}}) {
    const CommPath2d ocp(WithK56(k5, k6), channel);
    using Base = AutoDiffOcp<CommPath2d, 5, 3, 5, 0>;
    for (int trial = 0; trial < 20; ++trial) {
      Vec x(5), u(3), lambda(5), mu(0);
      x << pos(rng), pos(rng), vel(rng), vel(rng), 150.0 * unit(rng);
      u << 0.3 * unit(rng), 0.3 * unit(rng), 3.0 + 3.0 * unit(rng);
      if (trial == 0) x[2] = x[3] = u[0] = u[1] = 0.0;  // at rest: the smoothing's curvature
      for (int i = 0; i < 5; ++i) lambda[i] = 5.0 * unit(rng);
      const double sigma = trial == 1 ? 0.0 : 0.5 + unit(rng);
      Mat h(8, 8), h_ad(8, 8);
      ocp.PointHessian(0.0, x, u, sigma, lambda, mu, h);
      ocp.Base::PointHessian(0.0, x, u, sigma, lambda, mu, h_ad);
      EXPECT_LE((h - h_ad).cwiseAbs().maxCoeff(), 1e-12 * (1.0 + h_ad.cwiseAbs().maxCoeff()))
          << "k5 = " << k5 << ", trial " << trial << "\n"
          << h << "\n\n"
          << h_ad;
    }
  }
}

// H(t, x, u, p) for the closed form is no worse than any of many points of U (a polar grid of
// the ball times a grid of [0, Rmax], plus random points), at random (x, p).
void ExpectMinimizerBeatsBruteForce(const Ocp& ocp, double umax, double rmax, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> pos(0.0, 50.0), vel(-2.0, 2.0), unit(-1.0, 1.0);
  std::uniform_real_distribution<double> logmag(-4.0, 1.0);
  for (int trial = 0; trial < 16; ++trial) {
    Vec x(5), p(5), u(3);
    x << pos(rng), pos(rng), vel(rng), vel(rng), 0.0;
    if (trial % 8 == 0) x[2] = x[3] = 0.0;  // at rest, where the smoothing matters
    for (int i = 0; i < 5; ++i) p[i] = std::pow(10.0, logmag(rng)) * unit(rng);
    // p3 of the scale that makes R* interior somewhere: -ln2 s / K ... -ln2 s 2^Rmax / K.
    double s;
    static_cast<const CommPath2d&>(ocp).channel().Evaluate(
        Eigen::Vector2d(x[0], x[1]), &s, nullptr, nullptr);
    p[4] = -std::log(2.0) * s / 0.130288 * std::pow(2.0, 7.0 * (0.5 + 0.5 * unit(rng)));
    ocp.MinimizeHamiltonian(0.0, x, p, u);
    ASSERT_LE(ocp.control_set().Violation(u), 1e-12);
    const double h_star = ocp.Hamiltonian(0.0, x, u, p);
    double best = INFINITY;
    Vec v(3);
    for (int ir = 0; ir <= 20; ++ir) {
      for (int ia = 0; ia < 48; ++ia) {
        const double r = umax * ir / 20.0, a = 2.0 * M_PI * ia / 48.0;
        for (int iR = 0; iR <= 60; iR += 4) {
          v << r * std::cos(a), r * std::sin(a), rmax * iR / 60.0;
          best = std::min(best, ocp.Hamiltonian(0.0, x, v, p));
        }
      }
    }
    // R and u separate: a fine line search in R at u*, and random points near u*.
    for (int iR = 0; iR <= 3000; ++iR) {
      v << u[0], u[1], rmax * iR / 3000.0;
      best = std::min(best, ocp.Hamiltonian(0.0, x, v, p));
    }
    for (int i = 0; i < 2000; ++i) {
      v = u + Eigen::Vector3d(unit(rng), unit(rng), unit(rng)) *
                  std::pow(10.0, -1.0 - 5.0 * (i % 6) / 5.0);
      ocp.control_set().Project(v);
      best = std::min(best, ocp.Hamiltonian(0.0, x, v, p));
    }
    EXPECT_LE(h_star, best + 1e-12 * (1.0 + std::abs(best)))
        << "x = " << x.transpose() << "\np = " << p.transpose() << "\nu* = " << u.transpose();
  }
}

TEST(CommPath2d, MinimizerBeatsBruteForceWithK5K6Zero) {
  const CommPath2d ocp(CommPath2d::Options(), PaperPathLoss());
  ExpectMinimizerBeatsBruteForce(ocp, 0.5, 6.0, 21);
}

TEST(CommPath2d, MinimizerBeatsBruteForceWithK5K6Positive) {
  const CommPath2d ocp(WithK56(2.0, 3.0), PaperPathLoss());
  ExpectMinimizerBeatsBruteForce(ocp, 0.5, 6.0, 22);
}

TEST(CommPath2d, MinimizerBeatsBruteForceOnAMap) {
  const CommPath2d ocp(WithK56(0.5, 0.5), RippleMap());
  ExpectMinimizerBeatsBruteForce(ocp, 0.5, 6.0, 23);
}

// The fused direction step (one channel evaluation) returns what the default composition of
// MinimizeHamiltonian, Dynamics and RunningCost returns, at random (x, p, u).
void ExpectFusedStepMatchesTheDefault(const CommPath2d& ocp, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> pos(0.0, 50.0), vel(-2.0, 2.0), unit(-1.0, 1.0);
  for (int trial = 0; trial < 50; ++trial) {
    Vec x(5), p(5), u(3), u_star(3), u_ref(3), f(5);
    x << pos(rng), pos(rng), vel(rng), vel(rng), 10.0 * unit(rng);
    if (trial % 10 == 0) x[2] = x[3] = 0.0;
    for (int i = 0; i < 5; ++i) p[i] = 5.0 * unit(rng);
    p[4] = -std::abs(p[4]) * 1e-3;
    u << 0.3 * unit(rng), 0.3 * unit(rng), 3.0 + 3.0 * unit(rng);
    double h_star = NAN, h_now = NAN;
    ocp.MinimizeAndCompareHamiltonian(0.0, x, p, u, u_star, &h_star, &h_now, f);
    ocp.MinimizeHamiltonian(0.0, x, p, u_ref);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(u_star[i], u_ref[i]) << i;
    const double h_star_ref = ocp.Hamiltonian(0.0, x, u_ref, p);
    const double h_now_ref = ocp.Hamiltonian(0.0, x, u, p);
    EXPECT_NEAR(h_star, h_star_ref, 1e-13 * (1.0 + std::abs(h_star_ref)));
    EXPECT_NEAR(h_now, h_now_ref, 1e-13 * (1.0 + std::abs(h_now_ref)));
    EXPECT_LE(h_star, h_now + 1e-13 * (1.0 + std::abs(h_now)));
  }
}

// HasAffineDynamics() is a claim the Armijo prefilter relies on: f at a convex combination of
// two points (x, u) is the same combination of f at them.
TEST(CommPath2d, DynamicsAreAffineAsDeclared) {
  const CommPath2d ocp(CommPath2d::Options(), PaperPathLoss());
  ASSERT_TRUE(ocp.HasAffineDynamics());
  std::mt19937_64 rng(33);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    Vec x1 = 20.0 * Vec::Random(5), x2 = 20.0 * Vec::Random(5), u1 = Vec::Random(3),
        u2 = Vec::Random(3), f1(5), f2(5), fm(5);
    const double a = 0.5 + 0.5 * unit(rng);
    ocp.Dynamics(1.0, x1, u1, f1);
    ocp.Dynamics(1.0, x2, u2, f2);
    ocp.Dynamics(1.0, a * x1 + (1.0 - a) * x2, a * u1 + (1.0 - a) * u2, fm);
    EXPECT_LE((fm - (a * f1 + (1.0 - a) * f2)).norm(), 1e-12 * (1.0 + f1.norm() + f2.norm()));
  }
}

TEST(CommPath2d, FusedDirectionStepMatchesTheDefault) {
  ExpectFusedStepMatchesTheDefault(CommPath2d(CommPath2d::Options(), PaperPathLoss()), 31);
  ExpectFusedStepMatchesTheDefault(CommPath2d(WithK56(0.5, 0.5), RippleMap()), 32);
}

// The registry's paper channel (simulated, measured, predicted, mapped), with few samples to keep
// it cheap: the map is what the problem evaluates, the starting cost is still 238720, and the
// derivatives through the map match finite differences.
TEST(CommPath2d, PaperChannelFromTheRegistry) {
  const auto ocp = MakeProblem("comm-path2d", {"samples=60", "estimate=0"}, 3);
  const auto& cp = static_cast<const CommPath2d&>(*ocp);
  EXPECT_NE(cp.channel().Describe().find("map"), std::string::npos) << cp.channel().Describe();
  const TimeGrid grid = TimeGrid::Uniform(0.0, 40.0, 400);
  const Evaluation ev =
      Evaluate(*ocp, ControlTrajectory::Constant(grid, Vec::Zero(3)), grid, Integrator::kEuler);
  EXPECT_NEAR(ev.J, 238720.0, 1.0);
  Vec x(5), u(3), lambda(5), mu(0), nu(5);
  x << 17.3, 22.1, 0.4, -0.9, 75.0;
  u << 0.2, -0.1, 4.0;
  lambda << 1.0, -2.0, 3.0, 0.5, -1.5;
  nu << 0.3, 0.2, -0.4, 1.1, -2.0;
  const DerivativeCheck check = CheckOcpDerivatives(*ocp, 3.0, x, u, lambda, mu, nu);
  EXPECT_LT(check.max_error, 1e-6) << check.log;
  // Another seed is another channel.
  const auto other = MakeProblem("comm-path2d", {"samples=60", "estimate=0"}, 4);
  double s3, s4;
  cp.channel().Evaluate(Eigen::Vector2d(30.0, 20.0), &s3, nullptr, nullptr);
  static_cast<const CommPath2d&>(*other).channel().Evaluate(
      Eigen::Vector2d(30.0, 20.0), &s4, nullptr, nullptr);
  EXPECT_NE(s3, s4);
}

TEST(CommPowerModel, AccelerationMagnitudeMatchesTheClosedFormsAndA1dSearch) {
  CommPowerModel m;
  // k5 = k6 = 0: the paper's r = min(a / (2 gamma k1), rmax).
  EXPECT_DOUBLE_EQ(m.AccelerationMagnitude(0.1, 0.0, 0.5), 0.1 / (2.0 * 0.01 * 17.75));
  EXPECT_DOUBLE_EQ(m.AccelerationMagnitude(1.0, 0.0, 0.5), 0.5);
  EXPECT_EQ(m.AccelerationMagnitude(0.0, 0.0, 0.5), 0.0);
  // k5 > 0: the minimizer of -a r + gamma (k1 r^2 + k5 n(r)) on [0, rmax], against a fine search.
  m.k[4] = 5.0;
  m.k[5] = 2.0;
  for (double a : {0.001, 0.03, 0.05, 0.07, 0.12, 0.3, 5.0}) {
    const double nv = 0.4, rmax = 0.5;
    const double b = m.gamma * (m.k[4] + m.k[5] * nv);
    auto phi = [&](double r) {
      return -a * r + m.gamma * m.k[0] * r * r + b * (std::sqrt(r * r + m.eps * m.eps) - m.eps);
    };
    const double r = m.AccelerationMagnitude(a, nv, rmax);
    double best = INFINITY;
    for (int i = 0; i <= 200000; ++i) best = std::min(best, phi(rmax * i / 200000.0));
    EXPECT_LE(phi(r), best + 1e-15) << "a = " << a;
    EXPECT_GE(r, 0.0);
    EXPECT_LE(r, rmax);
  }
}

TEST(CommPowerModel, RateIsClippedLog2) {
  const CommPowerModel m;
  const double s = 2e-4, K = m.K(), threshold = -std::log(2.0) * s / K;
  EXPECT_EQ(m.Rate(0.5 * threshold, s, 6.0), 0.0);  // p3 above the threshold: 0
  EXPECT_EQ(m.Rate(threshold, s, 6.0), 0.0);
  EXPECT_NEAR(m.Rate(8.0 * threshold, s, 6.0), 3.0, 1e-12);  // 2^R = 8
  EXPECT_EQ(m.Rate(1000.0 * threshold, s, 6.0), 6.0);        // clipped at Rmax
  EXPECT_EQ(m.Rate(1.0, s, 6.0), 0.0);
}

// With u = 0 and R = 0 the robot stays at S: J = C1 |S - D|^2 + C3 c^2 + gamma k4 tf
// = 10 * 1325 + 10 * 22500 + 470 = 238720 (the paper's 2.3872e5), and 1.1913e7 for C = 500.
TEST(CommPath2d, InitialCostOfThePaper) {
  const CommPath2d ocp(CommPath2d::Options(), PaperPathLoss());
  const TimeGrid grid = TimeGrid::Uniform(0.0, 40.0, 400);
  const ControlTrajectory zero = ControlTrajectory::Constant(grid, Vec::Zero(3));
  const Evaluation ev = Evaluate(ocp, zero, grid, Integrator::kEuler);
  EXPECT_NEAR(ev.J, 238720.0, 1.0);
  EXPECT_NEAR(ev.Jbar, 470.0, 1e-9);

  CommPath2d::Options big;
  big.penalty = Eigen::Vector3d(500.0, 500.0, 500.0);
  const CommPath2d ocp500(big, PaperPathLoss());
  const Evaluation ev500 = Evaluate(ocp500, zero, grid, Integrator::kEuler);
  EXPECT_NEAR(ev500.J, 11912970.0, 1.0);
  EXPECT_NEAR(ev500.J / 1e7, 1.1913, 5e-5);
}

// The bound the descent's Armijo prefilter relies on: L >= gamma k4 on U, attained at rest.
TEST(CommPath2d, RunningCostLowerBoundHolds) {
  const CommPath2d ocp(WithK56(0.5, 0.5), RippleMap());
  ASSERT_TRUE(ocp.RunningCostLowerBound().has_value());
  const double m = *ocp.RunningCostLowerBound();
  EXPECT_DOUBLE_EQ(m, 0.01 * 1175.0);
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> pos(-10.0, 60.0), vel(-3.0, 3.0), unit(-1.0, 1.0);
  for (int i = 0; i < 2000; ++i) {
    Vec x(5), u(3);
    x << pos(rng), pos(rng), vel(rng), vel(rng), 0.0;
    u << unit(rng), unit(rng), 3.0 + 3.0 * unit(rng);
    if (i % 4 == 0) x[2] = x[3] = u[0] = u[1] = u[2] = 0.0;
    ocp.control_set().Project(u);
    EXPECT_GE(ocp.RunningCost(0.0, x, u), m);
  }
  EXPECT_EQ(ocp.RunningCost(0.0, Vec::Zero(5), Vec::Zero(3)), m);
}

// ---- EulerStageModel: the descent's fast path returns the generic functions' numbers bitwise ----

// At random (x, u, p) for k5 = k6 = 0 and > 0, on the path-loss channel and a map: the cached
// running cost, the pointwise bound, the Euler step and the backward point against RunningCost,
// Dynamics, MinimizeAndCompareHamiltonian, DynamicsJacobian and RunningCostGradient.
TEST(CommPath2d, StageModelIsBitwiseTheGenericFunctions) {
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> pos(-5.0, 55.0), vel(-2.0, 2.0), unit(-1.0, 1.0);
  const auto map = RippleMap();
  for (const auto& [k5, k6, channel] : {std::tuple{0.0, 0.0, PaperPathLoss()},
                                        std::tuple{0.7, 1.3, PaperPathLoss()},
                                        std::tuple{0.0, 0.0, map},
                                        std::tuple{0.7, 1.3, map}}) {
    const CommPath2d ocp(WithK56(k5, k6), channel);
    const EulerStageModel& model = ocp;
    ASSERT_EQ(model.StageCacheSize(), 6);
    for (int trial = 0; trial < 60; ++trial) {
      Vec x(5), u(3), p(5), f(5), Lx(5), Lu(3), u_ref(3), cache(6), x_next(5);
      x << pos(rng), pos(rng), vel(rng), vel(rng), 100.0 * (1.0 + unit(rng));
      u << 0.4 * unit(rng), 0.4 * unit(rng), 3.0 + 3.0 * unit(rng);
      if (trial % 10 == 0) x[2] = x[3] = 0.0;
      if (trial % 10 == 1) u[0] = u[1] = u[2] = 0.0;
      ocp.control_set().Project(u);
      for (int i = 0; i < 5; ++i) p[i] = 5.0 * unit(rng);
      p[4] = -std::abs(p[4]) * std::pow(10.0, -4.0 * std::abs(unit(rng)));
      const double t = 3.0, h = 0.1;

      const double L = model.RunningCostCaching(t, x.data(), u.data(), cache.data());
      EXPECT_EQ(L, ocp.RunningCost(t, x, u));
      EXPECT_LE(model.PointwiseRunningCostBound(t, x.data(), u.data()), L);

      model.EulerStep(t, h, x.data(), u.data(), x_next.data());
      ocp.Dynamics(t, x, u, f);
      EXPECT_EQ(x_next, (x + h * f).eval());

      // The generic backward step of DescentPasses (DiscreteOcp::Adjoint's Euler recursion and
      // HamiltonianDescent::Direction's pointwise work).
      double h_star_ref = 0.0, h_now_ref = 0.0, L2 = 0.0;
      ocp.MinimizeAndCompareHamiltonian(t, x, p, u, u_ref, &h_star_ref, &h_now_ref, f);
      Mat fx(5, 5), fu(5, 3);
      ocp.DynamicsJacobian(t, x, u, f, fx, fu);
      ocp.RunningCostGradient(t, x, u, &L2, Lx, Lu);
      Vec lam_ref = p;
      const Vec tmp = fx.transpose().lazyProduct(p);
      lam_ref += h * (tmp + Lx);

      Vec lam = p, u_star(3);
      double h_star = 0.0, h_now = 0.0;
      model.BackwardPoint(t,
                          h,
                          x.data(),
                          u.data(),
                          cache.data(),
                          std::numeric_limits<double>::infinity(),
                          lam.data(),
                          u_star.data(),
                          &h_star,
                          &h_now,
                          nullptr);
      EXPECT_EQ(u_star, u_ref);
      EXPECT_EQ(h_star, h_star_ref);
      EXPECT_EQ(h_now, h_now_ref);
      EXPECT_EQ(lam, lam_ref);
    }
  }
}

// The whole-trial calls of the descent (EulerStates, PointwiseRunningCostBounds: one loop each
// on comm-path2d) return the per-point calls' numbers bitwise, and so does the interface's
// default (the per-point calls), on a non-uniform grid with random controls.
TEST(CommPath2d, WholeTrialStageCallsAreBitwiseThePointCalls) {
  std::mt19937_64 rng(47);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<double> points = {0.0};
  for (int k = 0; k < 37; ++k) points.push_back(points.back() + 0.05 + 0.1 * std::abs(unit(rng)));
  const TimeGrid grid = TimeGrid::FromPoints(points);
  const int N = grid.intervals();
  for (const auto& [k5, k6] : {std::pair{0.0, 0.0}, std::pair{0.7, 1.3}}) {
    const CommPath2d ocp(WithK56(k5, k6), PaperPathLoss());
    const EulerStageModel& model = ocp;
    Mat U(3, N);
    for (int k = 0; k < N; ++k) {
      U.col(k) << 0.4 * unit(rng), 0.4 * unit(rng), 3.0 + 3.0 * unit(rng);
      if (k % 7 == 3) U.col(k).setZero();
    }
    Mat X(5, N + 1), X_default(5, N + 1), X_ref(5, N + 1);
    X.col(0) << 20.0, 40.0, 0.3, -0.2, 1.0;
    X_default.col(0) = X_ref.col(0) = X.col(0);
    for (int k = 0; k < N; ++k) {
      model.EulerStep(
          grid.t(k), grid.h(k), X_ref.col(k).data(), U.col(k).data(), X_ref.col(k + 1).data());
    }
    model.EulerStates(grid, 5, 3, U.data(), X.data());
    model.EulerStageModel::EulerStates(grid, 5, 3, U.data(), X_default.data());
    EXPECT_EQ(X, X_ref);
    EXPECT_EQ(X_default, X_ref);

    std::vector<double> m(N), m_default(N);
    model.PointwiseRunningCostBounds(grid, 5, 3, X.data(), U.data(), m.data());
    model.EulerStageModel::PointwiseRunningCostBounds(
        grid, 5, 3, X.data(), U.data(), m_default.data());
    for (int k = 0; k < N; ++k) {
      const double ref =
          model.PointwiseRunningCostBound(grid.t(k), X.col(k).data(), U.col(k).data());
      EXPECT_EQ(m[k], ref) << k;
      EXPECT_EQ(m_default[k], ref) << k;
    }
  }
}

// The indirect method's fused node evaluation (one channel evaluation) returns the numbers of
// MinimizeHamiltonian, DynamicsJacobian and RunningCostGradient bitwise (Ocp's default), on the
// path-loss channel and a map, with u* interior, on the ball and at both rate bounds; the
// gradients it returns are the hand-written ones that DerivativesMatchFiniteDifferences checks.
TEST(CommPath2d, FusedMinimizerWithGradientsIsBitwiseTheThreeCalls) {
  std::mt19937_64 rng(43);
  std::uniform_real_distribution<double> pos(-5.0, 55.0), vel(-2.0, 2.0), unit(-1.0, 1.0);
  const auto map = RippleMap();
  for (const auto& [k5, k6, channel] : {std::tuple{0.0, 0.0, PaperPathLoss()},
                                        std::tuple{0.7, 1.3, PaperPathLoss()},
                                        std::tuple{0.0, 0.0, map},
                                        std::tuple{0.7, 1.3, map}}) {
    const CommPath2d ocp(WithK56(k5, k6), channel);
    for (int trial = 0; trial < 60; ++trial) {
      Vec x(5), p(5);
      x << pos(rng), pos(rng), vel(rng), vel(rng), 100.0 * (1.0 + unit(rng));
      if (trial % 10 == 0) x[2] = x[3] = 0.0;
      for (int i = 0; i < 5; ++i) p[i] = 5.0 * unit(rng);
      // |p2| from tiny (interior u) to large (on the ball); p3 from rate 0 to Rmax.
      p[2] *= std::pow(10.0, -3.0 * std::abs(unit(rng)));
      p[4] = -std::abs(p[4]) * std::pow(10.0, -6.0 * std::abs(unit(rng)));
      if (trial % 10 == 1) p[4] = 1.0;
      const double t = 3.0;

      Vec u_ref(3), f_ref(5), Lx_ref(5), Lu_ref(3);
      Mat fx_ref(5, 5), fu_ref(5, 3);
      double L_ref = 0.0;
      ocp.MinimizeHamiltonian(t, x, p, u_ref);
      ocp.DynamicsJacobian(t, x, u_ref, f_ref, fx_ref, fu_ref);
      ocp.RunningCostGradient(t, x, u_ref, &L_ref, Lx_ref, Lu_ref);

      Vec u(3), f(5), Lx(5), Lu(3);
      Mat fx(5, 5), fu(5, 3);
      double L = 0.0;
      ocp.MinimizeHamiltonianWithGradients(t, x, p, u, f, fx, fu, &L, Lx, Lu);
      EXPECT_EQ(u, u_ref);
      EXPECT_EQ(f, f_ref);
      EXPECT_EQ(fx, fx_ref);
      EXPECT_EQ(fu, fu_ref);
      EXPECT_EQ(L, L_ref);
      EXPECT_EQ(Lx, Lx_ref);
      EXPECT_EQ(Lu, Lu_ref);
    }
  }
}

// The proximal minimizer (Sakawa-Shindo's direction) beats a brute-force search over U of
// H + |w - center|^2 / (2 eps) (a polar grid of the ball times a grid of [0, Rmax], a fine line in
// R at w, and random points near w), for k5 = k6 = 0 and > 0 and eps from small to large; and
// the fast path's BackwardPoint with eps returns the same w and H(w).
TEST(CommPath2d, ProximalMinimizerBeatsBruteForce) {
  const auto map = RippleMap();
  std::mt19937_64 rng(44);
  std::uniform_real_distribution<double> pos(0.0, 50.0), vel(-2.0, 2.0), unit(-1.0, 1.0);
  for (const auto& [k5, k6, channel] : {std::tuple{0.0, 0.0, PaperPathLoss()},
                                        std::tuple{2.0, 3.0, PaperPathLoss()},
                                        std::tuple{0.5, 0.5, map}}) {
    const CommPath2d ocp(WithK56(k5, k6), channel);
    for (int trial = 0; trial < 8; ++trial) {
      Vec x(5), p(5), c(3), w(3);
      x << pos(rng), pos(rng), vel(rng), vel(rng), 0.0;
      if (trial % 4 == 0) x[2] = x[3] = 0.0;
      for (int i = 0; i < 4; ++i)
        p[i] = std::pow(10.0, -3.0 + 3.0 * std::abs(unit(rng))) * unit(rng);
      double s;
      ocp.channel().Evaluate(Eigen::Vector2d(x[0], x[1]), &s, nullptr, nullptr);
      p[4] = -std::log(2.0) * s / 0.130288 * std::pow(2.0, 7.0 * (0.5 + 0.5 * unit(rng)));
      c << 0.3 * unit(rng), 0.3 * unit(rng), 3.0 + 3.0 * unit(rng);
      ocp.control_set().Project(c);
      for (double eps : {1e-3, 0.3, 30.0}) {
        ocp.MinimizeProximalHamiltonian(0.0, x, p, c, eps, w);
        ASSERT_LE(ocp.control_set().Violation(w), 1e-12);
        auto phi = [&](const Vec& v) {
          return ocp.Hamiltonian(0.0, x, v, p) + (v - c).squaredNorm() / (2.0 * eps);
        };
        const double at_w = phi(w);
        double best = INFINITY;
        Vec v(3);
        for (int ir = 0; ir <= 20; ++ir) {
          for (int ia = 0; ia < 48; ++ia) {
            const double r = 0.5 * ir / 20.0, a = 2.0 * M_PI * ia / 48.0;
            for (int iR = 0; iR <= 60; iR += 4) {
              v << r * std::cos(a), r * std::sin(a), 6.0 * iR / 60.0;
              best = std::min(best, phi(v));
            }
          }
        }
        for (int iR = 0; iR <= 3000; ++iR) {
          v << w[0], w[1], 6.0 * iR / 3000.0;
          best = std::min(best, phi(v));
        }
        for (int i = 0; i < 2000; ++i) {
          v = w + Eigen::Vector3d(unit(rng), unit(rng), unit(rng)) *
                      std::pow(10.0, -1.0 - 5.0 * (i % 6) / 5.0);
          ocp.control_set().Project(v);
          best = std::min(best, phi(v));
        }
        EXPECT_LE(at_w, best + 1e-12 * (1.0 + std::abs(best)))
            << "eps " << eps << "\nx = " << x.transpose() << "\np = " << p.transpose();
        // The fast path's proximal step at the same point.
        const EulerStageModel& model = ocp;
        Vec cache(6), lam = p, w2(3);
        model.RunningCostCaching(0.0, x.data(), c.data(), cache.data());
        double h_star = 0.0, h_now = 0.0, h_min = 0.0;
        model.BackwardPoint(0.0,
                            0.1,
                            x.data(),
                            c.data(),
                            cache.data(),
                            eps,
                            lam.data(),
                            w2.data(),
                            &h_star,
                            &h_now,
                            &h_min);
        EXPECT_EQ(w2, w);
        EXPECT_NEAR(h_star, ocp.Hamiltonian(0.0, x, w, p), 1e-12 * (1.0 + std::abs(h_star)));
        Vec u_star(3);
        ocp.MinimizeHamiltonian(0.0, x, p, u_star);
        EXPECT_NEAR(h_min, ocp.Hamiltonian(0.0, x, u_star, p), 1e-12 * (1.0 + std::abs(h_min)));
        EXPECT_LE(h_min, h_star);
      }
    }
  }
}

// The pointwise bound the descent rejects trials with: the motion power, below L on U.
TEST(CommPath2d, PointwiseRunningCostBoundIsTheMotionPowerAndHolds) {
  const CommPath2d ocp(WithK56(0.5, 0.5), RippleMap());
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> pos(-10.0, 60.0), vel(-3.0, 3.0), unit(-1.0, 1.0);
  for (int i = 0; i < 2000; ++i) {
    Vec x(5), u(3);
    x << pos(rng), pos(rng), vel(rng), vel(rng), 0.0;
    u << unit(rng), unit(rng), 3.0 + 3.0 * unit(rng);
    if (i % 4 == 0) u[2] = 0.0;  // no transmission: the bound is L itself
    ocp.control_set().Project(u);
    const double m = ocp.PointwiseRunningCostBound(0.0, x.data(), u.data());
    const double L = ocp.RunningCost(0.0, x, u);
    EXPECT_LE(m, L);
    if (u[2] == 0.0) {
      EXPECT_EQ(m, L);
    }
    EXPECT_GE(m, *ocp.RunningCostLowerBound());
  }
}

// The double overloads the fast path uses: the same numbers as the template and Rate().
TEST(CommPowerModel, MotionGivenSpeedNormAndRateGivenKAreBitwiseTheOriginals) {
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (const auto& k : {std::array<double, 6>{17.75, 1.16, 10.46, 1175.0, 0.0, 0.0},
                        std::array<double, 6>{17.75, 1.16, 0.0, 1175.0, 0.0, 0.0},
                        std::array<double, 6>{17.75, 1.16, 10.46, 1175.0, 2.0, 0.0},
                        std::array<double, 6>{17.75, 1.16, 0.0, 1175.0, 2.0, 0.0},
                        std::array<double, 6>{17.75, 1.16, 10.46, 1175.0, 2.0, 3.0}}) {
    CommPowerModel m;
    m.k = k;
    for (int i = 0; i < 200; ++i) {
      const double acc2 = 0.25 * std::abs(unit(rng)), speed2 = 4.0 * std::abs(unit(rng));
      EXPECT_EQ(m.Motion(acc2, speed2, m.SmoothNorm(speed2)), m.Motion<double>(acc2, speed2));
      const double p3 = -std::pow(10.0, -6.0 * std::abs(unit(rng))), s = 1e-4 * (1.5 + unit(rng));
      EXPECT_EQ(m.Rate(p3, s, 6.0, m.K()), m.Rate(p3, s, 6.0));
    }
  }
}

TEST(CommPath2d, SmoothingIsWithinEpsOfTheNorm) {
  const CommPowerModel m;
  for (double v : {0.0, 1e-4, 1e-3, 0.1, 1.0, 10.0}) {
    const double n = m.SmoothNorm(v * v);
    EXPECT_LE(n, v);
    EXPECT_GE(n, v - m.eps);
  }
  EXPECT_EQ(m.SmoothNorm(0.0), 0.0);
}

TEST(CommPath2d, RegistryEntryAndParameters) {
  const ProblemInfo& info = FindProblem("comm-path2d");
  EXPECT_EQ(info.default_intervals, 400);
  EXPECT_TRUE(info.uses_seed);
  Parameters resolved;
  const auto ocp =
      MakeProblem("comm-path2d", {"channel=0", "C=500,500,500", "k=1,2,3,4,5,6"}, 1, &resolved);
  ASSERT_EQ(ocp->name(), "comm-path2d");
  EXPECT_EQ(ocp->nx(), 5);
  EXPECT_EQ(ocp->nu(), 3);
  EXPECT_EQ(ocp->num_terminal(), 5);
  EXPECT_EQ(ocp->num_path(), 0);
  EXPECT_DOUBLE_EQ(ocp->terminal_weights()[4], 500.0);
  const auto& cp = static_cast<const CommPath2d&>(*ocp);
  EXPECT_EQ(cp.options().power.k[5], 6.0);
  EXPECT_EQ(resolved.Vector("S"), Eigen::Vector2d(20.0, 40.0));
}

void ExpectRejected(const std::vector<std::string>& set, const std::string& field) {
  try {
    MakeProblem("comm-path2d", set, 1);
    ADD_FAILURE() << "accepted " << set.back();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
  }
}

TEST(CommPath2d, RejectsInvalidParametersNamingTheField) {
  ExpectRejected({"channel=0", "S=60,10"}, "S must lie in the workspace [0, 50]^2");
  ExpectRejected({"channel=0", "workspace=30"}, "S must lie in the workspace [0, 30]^2");
  ExpectRejected({"channel=0", "D=10,-1"}, "'D'");
  ExpectRejected({"channel=0", "base=51,5"}, "base must lie in the workspace [0, 50]^2");
  ExpectRejected({"channel=0", "grid_step=0"}, "'grid_step'");
  ExpectRejected({"channel=0", "min_pairs=1.5"}, "'min_pairs'");
  ExpectRejected({"channel=0", "tf=0"}, "'tf'");
  ExpectRejected({"channel=0", "umax=0"}, "'umax'");
  ExpectRejected({"channel=0", "Rmax=-1"}, "'Rmax'");
  ExpectRejected({"channel=0", "c=-5"}, "'c'");
  ExpectRejected({"channel=0", "eps=0"}, "'eps'");
  ExpectRejected({"channel=0", "k=1,1,1,1,1"}, "'k'");
}

TEST(CommPath2d, OptionsValidation) {
  std::string error;
  EXPECT_TRUE(CommPath2d::Options().IsValid(&error)) << error;
  CommPath2d::Options o;
  o.start = Eigen::Vector2d(-1.0, 3.0);
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("S "), std::string::npos) << error;
  o = CommPath2d::Options();
  o.tf = 0.0;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("tf"), std::string::npos) << error;
  o = CommPath2d::Options();
  o.power.k[2] = -1.0;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("k3"), std::string::npos) << error;
  EXPECT_THROW(CommPath2d(o, PaperPathLoss()), std::invalid_argument);
  EXPECT_THROW(CommPath2d(CommPath2d::Options(), nullptr), std::invalid_argument);
}

}  // namespace
}  // namespace ocpb
