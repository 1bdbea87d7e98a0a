// The elementary functions of core/jet.h beyond the first set (atan2, hypot, sinh, cosh, tanh,
// asin, acos, log1p, expm1, SmoothMax, SmoothMin), jet by jet: values against <cmath>, gradients
// against central differences of the double version, Hessians against central differences of
// the exact gradient, at points of both signs, in every quadrant for atan2, and at the domain
// edges each function documents.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/jet.h"

// Written as a problem outside namespace ocpb is: qualified names, one template for doubles and
// jets alike.
template <class T>
T UserWrittenFunction(const T& a, const T& b) {
  return ocpb::atan2(a, b) + ocpb::hypot(a, 1.5) * ocpb::tanh(b) + ocpb::log1p(b * b) -
         ocpb::expm1(0.5 * a) + ocpb::asin(0.5 * b) * ocpb::acos(0.3 * a) +
         ocpb::sinh(a) * ocpb::cosh(b) + ocpb::SmoothMax(a, b, 0.1) + ocpb::SmoothMin(a, 0.2, 0.1) +
         ocpb::atan2(0.7, b) + ocpb::hypot(-0.4, a);
}

namespace ocpb {
namespace {

struct JetCheck {
  double value_error = 0.0;     // |jet value - double value|
  double gradient_error = 0.0;  // max |g - fd| / max(1, |fd|), Jet1 and Jet2
  double hessian_error = 0.0;   // max |H - fd of g| / max(1, |fd|), and its asymmetry
};

// Evaluates fn(a, b) (a generic callable, written once for double and jets) at (a0, b0) as a
// double, a Jet1<2> and a Jet2<2>, and compares with central differences.
template <class Fn>
JetCheck CheckTwoVariableFunction(const Fn& fn, double a0, double b0) {
  JetCheck c;
  const double v = fn(a0, b0);
  const Jet1<2> j1 = fn(Jet1<2>::Variable(a0, 0), Jet1<2>::Variable(b0, 1));
  const Jet2<2> j2 = fn(Jet2<2>::Variable(a0, 0), Jet2<2>::Variable(b0, 1));
  c.value_error = std::max(std::abs(j1.a - v), std::abs(j2.a - v));
  if (std::isnan(j1.a) || std::isnan(j2.a)) c.value_error = INFINITY;
  const auto rel = [](double got, double want) {
    const double e = std::abs(got - want) / std::max(1.0, std::abs(want));
    return std::isnan(e) ? INFINITY : e;
  };
  const double ha = 1e-6 * std::max(1.0, std::abs(a0)), hb = 1e-6 * std::max(1.0, std::abs(b0));
  const double fd_a = (fn(a0 + ha, b0) - fn(a0 - ha, b0)) / (2.0 * ha);
  const double fd_b = (fn(a0, b0 + hb) - fn(a0, b0 - hb)) / (2.0 * hb);
  for (const Eigen::Vector2d& g : {Eigen::Vector2d(j1.g), Eigen::Vector2d(j2.g)}) {
    c.gradient_error = std::max({c.gradient_error, rel(g[0], fd_a), rel(g[1], fd_b)});
  }
  const auto grad = [&](double a, double b) {
    return Eigen::Vector2d(fn(Jet1<2>::Variable(a, 0), Jet1<2>::Variable(b, 1)).g);
  };
  const Eigen::Vector2d col_a = (grad(a0 + ha, b0) - grad(a0 - ha, b0)) / (2.0 * ha);
  const Eigen::Vector2d col_b = (grad(a0, b0 + hb) - grad(a0, b0 - hb)) / (2.0 * hb);
  c.hessian_error = std::max({rel(j2.h(0, 0), col_a[0]),
                              rel(j2.h(1, 0), col_a[1]),
                              rel(j2.h(0, 1), col_b[0]),
                              rel(j2.h(1, 1), col_b[1]),
                              rel(j2.h(0, 1), j2.h(1, 0))});
  return c;
}

// The arguments the functions below are applied to: nonlinear in (a, b), so that both the first
// and the second derivative of the function reach the Hessian (H = phi' p_zz + phi'' p_z p_z^T),
// and equal to (a0, b0) at the checked point.
struct Arguments {
  double k;  // a0 * b0
  template <class T>
  T P(const T& a, const T& b) const {
    return a + 0.1 * (a * b - k);
  }
  template <class T>
  T Q(const T& a, const T& b) const {
    return b - 0.2 * (a * b - k);
  }
};

void ExpectAccurate(const JetCheck& c, const std::string& what) {
  EXPECT_EQ(c.value_error, 0.0) << what;  // the same operations on the same doubles
  EXPECT_LT(c.gradient_error, 1e-8) << what;
  EXPECT_LT(c.hessian_error, 1e-7) << what;
}

// phi(p(a, b)) for each unary function at each point, b0 = 0.7.
#define OCPB_CHECK_UNARY(FN, ...)                                                               \
  for (const double x0 : std::vector<double>{__VA_ARGS__}) {                                    \
    const Arguments arg{x0 * 0.7};                                                              \
    ExpectAccurate(CheckTwoVariableFunction(                                                    \
                       [&](const auto& a, const auto& b) { return FN(arg.P(a, b)); }, x0, 0.7), \
                   std::string(#FN " at ") + std::to_string(x0));                               \
  }

TEST(JetFunctions, UnaryFunctionsMatchCentralDifferences) {
  OCPB_CHECK_UNARY(sinh, -3.0, -0.7, -1e-3, 0.0, 0.4, 2.5)
  OCPB_CHECK_UNARY(cosh, -3.0, -0.7, -1e-3, 0.0, 0.4, 2.5)
  OCPB_CHECK_UNARY(tanh, -6.0, -0.7, -1e-3, 0.0, 0.4, 2.5)
  OCPB_CHECK_UNARY(asin, -0.95, -0.5, 0.0, 0.3, 0.9)
  OCPB_CHECK_UNARY(acos, -0.95, -0.5, 0.0, 0.3, 0.9)
  OCPB_CHECK_UNARY(log1p, -0.9, -0.3, 1e-8, 0.5, 3.0)
  OCPB_CHECK_UNARY(expm1, -3.0, -0.7, -1e-8, 0.0, 0.4, 2.5)
}
#undef OCPB_CHECK_UNARY

// phi(p, q), phi(p, q0) and phi(p0, q): the jet-jet, jet-double and double-jet forms.
template <class Fn>
void CheckBinaryForms(const Fn& phi, double p0, double q0, const std::string& name) {
  const Arguments arg{p0 * q0};
  const std::string at = " at (" + std::to_string(p0) + ", " + std::to_string(q0) + ")";
  ExpectAccurate(
      CheckTwoVariableFunction(
          [&](const auto& a, const auto& b) { return phi(arg.P(a, b), arg.Q(a, b)); }, p0, q0),
      name + "(jet, jet)" + at);
  ExpectAccurate(CheckTwoVariableFunction(
                     [&](const auto& a, const auto& b) { return phi(arg.P(a, b), q0); }, p0, q0),
                 name + "(jet, double)" + at);
  ExpectAccurate(CheckTwoVariableFunction(
                     [&](const auto& a, const auto& b) { return phi(p0, arg.Q(a, b)); }, p0, q0),
                 name + "(double, jet)" + at);
}

// (y, x) in each quadrant, on the axes, and on both sides of the negative x axis, where the
// value jumps by 2 pi but the derivatives do not.
const std::vector<std::pair<double, double>> kPlanePoints = {
    {0.5, 0.8},
    {0.5, -0.8},
    {-0.5, -0.8},
    {-0.5, 0.8},
    {1e-3, -1.0},
    {-1e-3, -1.0},
    {2.0, 0.0},
    {-2.0, 0.0},
    {0.0, 1.5},
    {0.0, -1.5},
    {3.0, -40.0},
    {-0.02, 0.03},
};

TEST(JetFunctions, Atan2MatchesCentralDifferencesInEveryQuadrant) {
  const auto phi = [](const auto& y, const auto& x) { return atan2(y, x); };
  for (const auto& [y, x] : kPlanePoints) {
    // On the negative x axis itself the value jumps: differences across it mean nothing (the
    // derivatives there are checked against their formula below).
    if (y == 0.0 && x < 0.0) continue;
    CheckBinaryForms(phi, y, x, "atan2");
  }
}

TEST(JetFunctions, HypotMatchesCentralDifferences) {
  const auto phi = [](const auto& x, const auto& y) { return hypot(x, y); };
  for (const auto& [x, y] : kPlanePoints) CheckBinaryForms(phi, x, y, "hypot");
}

TEST(JetFunctions, SmoothMaxAndMinMatchCentralDifferences) {
  const auto smax = [](const auto& a, const auto& b) { return SmoothMax(a, b, 0.3); };
  const auto smin = [](const auto& a, const auto& b) { return SmoothMin(a, b, 0.3); };
  for (const auto& [a, b] : std::vector<std::pair<double, double>>{
           {0.4, -0.9}, {-0.9, 0.4}, {0.25, 0.25}, {-1.5, -1.4}, {2.0, 2.1}}) {
    CheckBinaryForms(smax, a, b, "SmoothMax");
    CheckBinaryForms(smin, a, b, "SmoothMin");
  }
}

TEST(JetFunctions, AProblemOutsideTheNamespaceCallsThemQualified) {
  const auto fn = [](const auto& a, const auto& b) { return UserWrittenFunction(a, b); };
  for (const auto& [a, b] : std::vector<std::pair<double, double>>{{0.4, -0.9}, {-0.6, 0.5}}) {
    ExpectAccurate(CheckTwoVariableFunction(fn, a, b), "a user's function");
  }
}

TEST(JetFunctions, Atan2ValuesAreStdAtan2AndItsDerivativesAreContinuousAcrossTheCut) {
  for (const auto& [y, x] : kPlanePoints) {
    const Jet2<2> r = atan2(Jet2<2>::Variable(y, 0), Jet2<2>::Variable(x, 1));
    EXPECT_EQ(r.a, std::atan2(y, x));
    // d/dy = x / r^2, d/dx = -y / r^2.
    EXPECT_NEAR(r.g[0], x / (x * x + y * y), 1e-12 / (x * x + y * y));
    EXPECT_NEAR(r.g[1], -y / (x * x + y * y), 1e-12 / (x * x + y * y));
  }
  const Jet2<2> above = atan2(Jet2<2>::Variable(1e-9, 0), Jet2<2>::Variable(-1.0, 1));
  const Jet2<2> below = atan2(Jet2<2>::Variable(-1e-9, 0), Jet2<2>::Variable(-1.0, 1));
  EXPECT_NEAR(above.a - below.a, 2.0 * std::numbers::pi, 1e-8);
  EXPECT_TRUE(above.g.isApprox(below.g, 1e-8))
      << above.g.transpose() << " / " << below.g.transpose();
  EXPECT_LT((above.h - below.h).norm(), 1e-8) << above.h << "\n" << below.h;
}

TEST(JetFunctions, Atan2AndHypotTakeZeroDerivativesAtTheOrigin) {
  const Jet2<2> y = Jet2<2>::Variable(0.0, 0), x = Jet2<2>::Variable(0.0, 1);
  for (const Jet2<2>& r :
       {atan2(y, x), hypot(x, y), atan2(y, 0.0), atan2(0.0, x), hypot(x, 0.0), hypot(0.0, y)}) {
    EXPECT_EQ(r.a, 0.0);
    EXPECT_TRUE(r.g.isZero(0.0)) << r.g.transpose();
    EXPECT_TRUE(r.h.isZero(0.0)) << r.h;
  }
}

TEST(JetFunctions, HypotOfXAndZeroHasTheDerivativeOfAbsAndNoOverflow) {
  for (const double v : {-2.0, 0.5}) {
    const Jet2<1> x = Jet2<1>::Variable(v, 0);
    const Jet2<1> h = hypot(x, 0.0), a = abs(x);
    EXPECT_EQ(h.a, a.a);
    EXPECT_EQ(h.g[0], a.g[0]);
    EXPECT_EQ(h.h(0, 0), 0.0);
  }
  // sqrt(x^2 + y^2) would overflow to inf here, and underflow to 0 for tiny arguments.
  const Jet2<2> big = hypot(Jet2<2>::Variable(3e200, 0), Jet2<2>::Variable(4e200, 1));
  EXPECT_NEAR(big.a / 5e200, 1.0, 1e-15);
  EXPECT_NEAR(big.g[0], 0.6, 1e-15);
  EXPECT_NEAR(big.g[1], 0.8, 1e-15);
  EXPECT_TRUE(big.h.allFinite());
  const Jet1<2> tiny = hypot(Jet1<2>::Variable(3e-200, 0), Jet1<2>::Variable(-4e-200, 1));
  EXPECT_NEAR(tiny.a / 5e-200, 1.0, 1e-15);
  EXPECT_NEAR(tiny.g[1], -0.8, 1e-15);
}

TEST(JetFunctions, TanhKeepsItsDerivativeWhereOneMinusTanhSquaredCancels) {
  for (const double v : {-20.0, 20.0}) {
    const Jet2<1> t = tanh(Jet2<1>::Variable(v, 0));
    // 1 / cosh(20)^2 = 4 / (e^20 + e^-20)^2 ~ 4 e^-40 = 1.7e-17, while 1 - tanh(20)^2 == 0.
    EXPECT_NEAR(t.g[0] / (4.0 * std::exp(-40.0)), 1.0, 1e-12);
    EXPECT_NEAR(t.h(0, 0) / (-2.0 * std::tanh(v) * 4.0 * std::exp(-40.0)), 1.0, 1e-12);
  }
}

TEST(JetFunctions, DomainEdgesAreTheDocumentedOnes) {
  const double inf = std::numeric_limits<double>::infinity();
  // asin, acos at +-1: finite values, infinite derivatives (as sqrt at 0); outside: NaN.
  EXPECT_EQ(asin(Jet1<1>::Variable(1.0, 0)).a, std::numbers::pi / 2);
  EXPECT_EQ(asin(Jet1<1>::Variable(1.0, 0)).g[0], inf);
  EXPECT_EQ(asin(Jet2<1>::Variable(-1.0, 0)).g[0], inf);
  EXPECT_EQ(acos(Jet1<1>::Variable(-1.0, 0)).a, std::numbers::pi);
  EXPECT_EQ(acos(Jet1<1>::Variable(-1.0, 0)).g[0], -inf);
  EXPECT_TRUE(std::isnan(asin(Jet1<1>::Variable(1.5, 0)).a));
  EXPECT_TRUE(std::isnan(asin(Jet1<1>::Variable(1.5, 0)).g[0]));
  EXPECT_TRUE(std::isnan(acos(Jet2<1>::Variable(-1.5, 0)).h(0, 0)));
  // log1p at -1: -inf, with an infinite derivative (as log at 0).
  EXPECT_EQ(log1p(Jet1<1>::Variable(-1.0, 0)).a, -inf);
  EXPECT_EQ(log1p(Jet1<1>::Variable(-1.0, 0)).g[0], inf);
  // log1p and expm1 keep their accuracy near 0, where log(1 + x) and exp(x) - 1 lose it.
  EXPECT_EQ(log1p(Jet1<1>::Variable(1e-17, 0)).a, 1e-17);
  EXPECT_EQ(expm1(Jet1<1>::Variable(1e-17, 0)).a, 1e-17);
}

TEST(JetFunctions, SmoothMaxAndMinStayWithinTheirErrorBounds) {
  const double eps = 0.2;
  for (const double a : {-1.0, -0.1, 0.0, 0.05, 0.7}) {
    for (const double b : {-0.5, 0.0, 0.05, 2.0}) {
      const double smax = SmoothMax(a, b, eps), smin = SmoothMin(a, b, eps);
      const double d = std::abs(a - b);
      EXPECT_GT(smax, std::max(a, b));
      EXPECT_LE(smax - std::max(a, b),
                (d > 0.0 ? std::min(eps / 2, eps * eps / (4 * d)) : eps / 2) + 1e-15);
      EXPECT_LT(smin, std::min(a, b));
      EXPECT_NEAR(smin, -SmoothMax(-a, -b, eps), 1e-15);
      EXPECT_NEAR(SmoothMax(a, b, 0.0), std::max(a, b), 1e-15);
      // Derivatives in (0, 1), summing to 1.
      const Jet2<2> j = SmoothMax(Jet2<2>::Variable(a, 0), Jet2<2>::Variable(b, 1), eps);
      EXPECT_GT(j.g[0], 0.0);
      EXPECT_LT(j.g[0], 1.0);
      EXPECT_NEAR(j.g[0] + j.g[1], 1.0, 1e-15);
    }
  }
  EXPECT_NEAR(SmoothMax(0.3, 0.3, eps), 0.3 + eps / 2, 1e-15);
  // A smooth max(x, 0) of a jet against a constant, and an integer constant.
  const Jet1<1> x = Jet1<1>::Variable(-0.4, 0);
  EXPECT_EQ(SmoothMax(x, 0.0, eps).a, SmoothMax(-0.4, 0.0, eps));
  EXPECT_EQ(SmoothMin(1, x, eps).g[0], SmoothMin(1.0, x, eps).g[0]);
}

}  // namespace
}  // namespace ocpb
