#include "problems/channel/bicubic_spline.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace ocpb {
namespace {

Eigen::MatrixXd Sample(
    int nx, int ny, double x0, double y0, double h, double (*f)(double, double)) {
  Eigen::MatrixXd v(nx, ny);
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) v(i, j) = f(x0 + i * h, y0 + j * h);
  }
  return v;
}

double Cubic(double x, double y) {
  return 1.0 + 2.0 * x - y + 0.5 * x * x * y - 0.3 * x * x * x + 0.2 * y * y * y +
         0.1 * x * y * y * x;
}

// Not-a-knot splines reproduce cubic polynomials in each variable exactly, with their
// derivatives, including outside the nodes (extrapolation by the boundary cell).
TEST(BicubicSpline, ReproducesBicubicPolynomials) {
  for (int n : {4, 5, 9}) {
    const BicubicSpline s(-1.0, 2.0, 0.5, Sample(n, n + 2, -1.0, 2.0, 0.5, Cubic));
    for (const Eigen::Vector2d& q :
         {Eigen::Vector2d(-0.8, 2.3), Eigen::Vector2d(0.1, 3.7), Eigen::Vector2d(-1.2, 1.9)}) {
      double v;
      Eigen::Vector2d g;
      Eigen::Matrix2d H;
      s.Evaluate(q.x(), q.y(), &v, &g, &H);
      const double x = q.x(), y = q.y();
      EXPECT_NEAR(v, Cubic(x, y), 1e-11) << n;
      EXPECT_NEAR(g[0], 2.0 + x * y - 0.9 * x * x + 0.2 * x * y * y, 1e-10);
      EXPECT_NEAR(g[1], -1.0 + 0.5 * x * x + 0.6 * y * y + 0.2 * x * x * y, 1e-10);
      EXPECT_NEAR(H(0, 0), y - 1.8 * x + 0.2 * y * y, 1e-9);
      EXPECT_NEAR(H(0, 1), x + 0.4 * x * y, 1e-9);
      EXPECT_NEAR(H(1, 0), H(0, 1), 1e-12);
      EXPECT_NEAR(H(1, 1), 1.2 * y + 0.2 * x * x, 1e-9);
    }
  }
}

double Smooth(double x, double y) { return std::sin(x) * std::exp(0.3 * y); }

TEST(BicubicSpline, InterpolatesAndIsC2AcrossCells) {
  const double h = 0.1;
  const BicubicSpline s(0.0, 0.0, h, Sample(30, 25, 0.0, 0.0, h, Smooth));
  double v;
  s.Evaluate(7 * h, 11 * h, &v, nullptr, nullptr);
  EXPECT_NEAR(v, Smooth(7 * h, 11 * h), 1e-13);
  // Value, gradient and Hessian agree from both sides of a cell boundary.
  const double eps = 1e-9;
  Eigen::Vector2d ga, gb;
  Eigen::Matrix2d Ha, Hb;
  double va, vb;
  s.Evaluate(12 * h - eps, 1.234, &va, &ga, &Ha);
  s.Evaluate(12 * h + eps, 1.234, &vb, &gb, &Hb);
  EXPECT_NEAR(va, vb, 1e-8);
  EXPECT_NEAR((ga - gb).norm(), 0.0, 1e-7);
  EXPECT_NEAR((Ha - Hb).norm(), 0.0, 1e-6);
  // Fourth-order accurate: error at cell centres well below h^4 |f''''| ~ 1e-4.
  double worst = 0.0;
  for (double x = 0.05; x < 2.85; x += 0.1) {
    s.Evaluate(x, 1.15, &v, nullptr, nullptr);
    worst = std::max(worst, std::abs(v - Smooth(x, 1.15)));
  }
  EXPECT_LT(worst, 2e-6);
}

TEST(BicubicSpline, RejectsBadInput) {
  EXPECT_THROW(BicubicSpline(0, 0, 0.1, Eigen::MatrixXd::Zero(3, 5)), std::invalid_argument);
  EXPECT_THROW(BicubicSpline(0, 0, 0.0, Eigen::MatrixXd::Zero(5, 5)), std::invalid_argument);
  Eigen::MatrixXd v = Eigen::MatrixXd::Zero(5, 5);
  v(2, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(BicubicSpline(0, 0, 0.1, v), std::invalid_argument);
}

}  // namespace
}  // namespace ocpb
