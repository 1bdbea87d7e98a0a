#include "problems/channel/quality_units.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace ocpb {
namespace {

// E[10^(-X/10)] for X ~ N(m, v) by Gauss-Hermite-free brute force: a fine midpoint rule over
// +-12 standard deviations.
double NumericalExpectation(double m, double v) {
  const double sd = std::sqrt(v);
  const int n = 200000;
  const double lo = m - 12 * sd, hi = m + 12 * sd, dx = (hi - lo) / n;
  double sum = 0.0;
  for (int k = 0; k < n; ++k) {
    const double x = lo + (k + 0.5) * dx;
    const double pdf = std::exp(-0.5 * (x - m) * (x - m) / v) / std::sqrt(2 * std::numbers::pi * v);
    sum += std::pow(10.0, -x / 10.0) * pdf * dx;
  }
  return sum;
}

TEST(QualityUnits, ExpectedInverseCnrIsTheLogNormalMean) {
  QualityUnits units;
  units.power_unit_scale = 1.0;
  units.noise_dbm = 0.0;
  for (double v : {0.5, 3.0, 12.9}) {
    const double exact = NumericalExpectation(20.0, v);
    EXPECT_NEAR(ExpectedInverseCnr(20.0, v, units) / exact, 1.0, 1e-9) << v;
  }
}

TEST(QualityUnits, WattsByDefault) {
  // Gamma = -110 dBm = N0: CNR = 1, so E[1/CNR] = 1 (per mW of reference) = 1e-3 W.
  EXPECT_DOUBLE_EQ(ExpectedInverseCnr(-110.0, 0.0, QualityUnits()), 1e-3);
  // 30 dB more received power: 1e-6 W.
  EXPECT_NEAR(ExpectedInverseCnr(-80.0, 0.0, QualityUnits()), 1e-6, 1e-18);
}

TEST(QualityUnits, ComposeMatchesFiniteDifferences) {
  // mean(q) and variance(q): smooth test functions of q with known derivatives.
  auto mean = [](const Eigen::Vector2d& q) { return -80.0 + 3.0 * std::sin(q.x()) * q.y(); };
  auto var = [](const Eigen::Vector2d& q) { return 5.0 + q.x() * q.x() * 0.3 + q.y(); };
  const Eigen::Vector2d q(0.7, -1.3);
  const Eigen::Vector2d mg(3.0 * std::cos(q.x()) * q.y(), 3.0 * std::sin(q.x()));
  Eigen::Matrix2d mh;
  mh << -3.0 * std::sin(q.x()) * q.y(), 3.0 * std::cos(q.x()), 3.0 * std::cos(q.x()), 0.0;
  const Eigen::Vector2d vg(0.6 * q.x(), 1.0);
  Eigen::Matrix2d vh;
  vh << 0.6, 0.0, 0.0, 0.0;
  const QualityUnits units;
  double s;
  Eigen::Vector2d g;
  Eigen::Matrix2d H;
  ComposeInverseCnr(mean(q), mg, mh, var(q), vg, vh, units, &s, &g, &H);
  auto S = [&](const Eigen::Vector2d& x) { return ExpectedInverseCnr(mean(x), var(x), units); };
  EXPECT_DOUBLE_EQ(s, S(q));
  const double h = 1e-5;
  for (int k = 0; k < 2; ++k) {
    const Eigen::Vector2d e = h * Eigen::Vector2d::Unit(k);
    EXPECT_NEAR(g[k], (S(q + e) - S(q - e)) / (2 * h), 1e-6 * std::abs(s));
    for (int l = 0; l < 2; ++l) {
      const Eigen::Vector2d f = h * Eigen::Vector2d::Unit(l);
      const double fd = (S(q + e + f) - S(q + e - f) - S(q - e + f) + S(q - e - f)) / (4 * h * h);
      EXPECT_NEAR(H(k, l), fd, 1e-4 * std::abs(s));
    }
  }
}

}  // namespace
}  // namespace ocpb
