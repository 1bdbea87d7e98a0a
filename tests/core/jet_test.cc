#include "core/jet.h"

#include <cmath>

#include <gtest/gtest.h>

namespace ocpb {
namespace {

// g(a, b) = exp(a) sin(b) / (1 + a^2) + sqrt(b) log(a) - pow(b, 2.5) + atan(a b)
template <class T>
T TestFunction(const T& a, const T& b) {
  return exp(a) * sin(b) / (1.0 + a * a) + sqrt(b) * log(a) - pow(b, 2.5) + atan(a * b) +
         tan(0.1 * a) - cos(b) * 2.0;
}

TEST(Jet, GradientAndHessianMatchCentralDifferences) {
  const double a = 1.3, b = 0.7;
  const Jet2<2> r = TestFunction(Jet2<2>::Variable(a, 0), Jet2<2>::Variable(b, 1));
  const Jet1<2> r1 = TestFunction(Jet1<2>::Variable(a, 0), Jet1<2>::Variable(b, 1));
  EXPECT_NEAR(r.a, TestFunction(a, b), 1e-15);
  EXPECT_NEAR(r1.a, TestFunction(a, b), 1e-15);
  const double h = 1e-5;
  const double ga = (TestFunction(a + h, b) - TestFunction(a - h, b)) / (2 * h);
  const double gb = (TestFunction(a, b + h) - TestFunction(a, b - h)) / (2 * h);
  EXPECT_NEAR(r.g[0], ga, 1e-8);
  EXPECT_NEAR(r.g[1], gb, 1e-8);
  EXPECT_NEAR(r1.g[0], r.g[0], 1e-14);
  EXPECT_NEAR(r1.g[1], r.g[1], 1e-14);
  // Hessian from differences of the exact gradient.
  auto grad = [](double x, double y) {
    const Jet1<2> j = TestFunction(Jet1<2>::Variable(x, 0), Jet1<2>::Variable(y, 1));
    return Eigen::Vector2d(j.g);
  };
  const Eigen::Vector2d ha = (grad(a + h, b) - grad(a - h, b)) / (2 * h);
  const Eigen::Vector2d hb = (grad(a, b + h) - grad(a, b - h)) / (2 * h);
  EXPECT_NEAR(r.h(0, 0), ha[0], 1e-7);
  EXPECT_NEAR(r.h(1, 0), ha[1], 1e-7);
  EXPECT_NEAR(r.h(0, 1), hb[0], 1e-7);
  EXPECT_NEAR(r.h(1, 1), hb[1], 1e-7);
  EXPECT_DOUBLE_EQ(r.h(0, 1), r.h(1, 0));
}

TEST(Jet, ApplyBinaryIsTheChainRule) {
  // phi(x, y) = x^2 y evaluated through ApplyBinary at x = 2a, y = a + b.
  const double a = 0.4, b = -1.1;
  const Jet2<2> ja = Jet2<2>::Variable(a, 0), jb = Jet2<2>::Variable(b, 1);
  const Jet2<2> x = 2.0 * ja, y = ja + jb;
  const double xv = x.a, yv = y.a;
  Eigen::Vector2d g(2 * xv * yv, xv * xv);
  Eigen::Matrix2d hs;
  hs << 2 * yv, 2 * xv, 2 * xv, 0.0;
  const Jet2<2> lifted = ApplyBinary(x, y, xv * xv * yv, g, hs);
  const Jet2<2> direct = x * x * y;
  EXPECT_NEAR(lifted.a, direct.a, 1e-14);
  EXPECT_TRUE(lifted.g.isApprox(direct.g, 1e-14));
  EXPECT_TRUE(lifted.h.isApprox(direct.h, 1e-14));
}

}  // namespace
}  // namespace ocpb
