// Forward-mode automatic differentiation with fixed-size derivative vectors.
//
// Jet1<N> carries a value a and its gradient g = da/dz for z in R^N.
// Jet2<N> also carries the Hessian H = d^2a/dz^2 (second-order forward mode).
//
// Every elementary function is written once, through the chain rule for a scalar
// function phi applied to a jet x:
//   value  phi(a)
//   grad   phi'(a) g
//   Hess   phi'(a) H + phi''(a) g g^T
// and products through the Leibniz rule; a function of two jets (atan2, hypot) through Chain2,
// the same rule with the partial derivatives of phi(x, y). A problem that is written once as a
// template on its scalar type is thereby differentiated twice without tapes.
// N is small here (nx + nu), so the O(N^2) cost per operation of Jet2 is cheap.
#pragma once

#include <cmath>
#include <type_traits>

#include <Eigen/Core>

namespace ocpb {

template <int N>
struct Jet1 {
  using Grad = Eigen::Matrix<double, N, 1>;
  double a = 0.0;
  Grad g = Grad::Zero();

  Jet1() = default;
  Jet1(double value) : a(value) {}  // NOLINT: constants convert implicitly
  Jet1(double value, const Grad& grad) : a(value), g(grad) {}
  static Jet1 Variable(double value, int index) {
    Jet1 j(value);
    j.g[index] = 1.0;
    return j;
  }
  // Applies a scalar function with derivatives d1 = phi'(a), d2 = phi''(a) (d2 unused).
  Jet1 Chain(double value, double d1, double /*d2*/) const { return Jet1(value, d1 * g); }
  // Applies phi(a, y.a) with first partials dx, dy (second partials unused).
  Jet1 Chain2(const Jet1& y,
              double value,
              double dx,
              double dy,
              double /*dxx*/,
              double /*dxy*/,
              double /*dyy*/) const {
    return Jet1(value, dx * g + dy * y.g);
  }
};

template <int N>
struct Jet2 {
  using Grad = Eigen::Matrix<double, N, 1>;
  using Hess = Eigen::Matrix<double, N, N>;
  double a = 0.0;
  Grad g = Grad::Zero();
  Hess h = Hess::Zero();

  Jet2() = default;
  Jet2(double value) : a(value) {}  // NOLINT: constants convert implicitly
  Jet2(double value, const Grad& grad, const Hess& hess) : a(value), g(grad), h(hess) {}
  static Jet2 Variable(double value, int index) {
    Jet2 j(value);
    j.g[index] = 1.0;
    return j;
  }
  Jet2 Chain(double value, double d1, double d2) const {
    return Jet2(value, d1 * g, d1 * h + d2 * g * g.transpose());
  }
  // Applies phi(a, y.a) with first partials dx, dy and second partials dxx, dxy, dyy:
  //   Hess = dx H + dy H_y + dxx g g^T + dyy g_y g_y^T + dxy (g g_y^T + g_y g^T).
  Jet2 Chain2(
      const Jet2& y, double value, double dx, double dy, double dxx, double dxy, double dyy) const {
    const Hess cross = dxy * g * y.g.transpose();
    return Jet2(value,
                dx * g + dy * y.g,
                dx * h + dy * y.h + dxx * g * g.transpose() + dyy * y.g * y.g.transpose() + cross +
                    cross.transpose());
  }
};

template <typename T>
struct IsJet : std::false_type {};
template <int N>
struct IsJet<Jet1<N>> : std::true_type {};
template <int N>
struct IsJet<Jet2<N>> : std::true_type {};
template <typename T>
concept JetType = IsJet<T>::value;

/// The value part of a double or a jet.
inline double ValueOf(double x) { return x; }
template <JetType J>
double ValueOf(const J& x) {
  return x.a;
}

// ---- arithmetic -------------------------------------------------------------
template <int N>
Jet1<N> operator+(const Jet1<N>& x, const Jet1<N>& y) {
  return Jet1<N>(x.a + y.a, x.g + y.g);
}
template <int N>
Jet2<N> operator+(const Jet2<N>& x, const Jet2<N>& y) {
  return Jet2<N>(x.a + y.a, x.g + y.g, x.h + y.h);
}
template <int N>
Jet1<N> operator-(const Jet1<N>& x, const Jet1<N>& y) {
  return Jet1<N>(x.a - y.a, x.g - y.g);
}
template <int N>
Jet2<N> operator-(const Jet2<N>& x, const Jet2<N>& y) {
  return Jet2<N>(x.a - y.a, x.g - y.g, x.h - y.h);
}
template <int N>
Jet1<N> operator-(const Jet1<N>& x) {
  return Jet1<N>(-x.a, -x.g);
}
template <int N>
Jet2<N> operator-(const Jet2<N>& x) {
  return Jet2<N>(-x.a, -x.g, -x.h);
}
template <int N>
Jet1<N> operator*(const Jet1<N>& x, const Jet1<N>& y) {
  return Jet1<N>(x.a * y.a, y.a * x.g + x.a * y.g);
}
template <int N>
Jet2<N> operator*(const Jet2<N>& x, const Jet2<N>& y) {
  const auto cross = x.g * y.g.transpose();
  return Jet2<N>(
      x.a * y.a, y.a * x.g + x.a * y.g, y.a * x.h + x.a * y.h + cross + cross.transpose());
}
template <JetType J>
J Reciprocal(const J& x) {
  const double r = 1.0 / x.a;
  return x.Chain(r, -r * r, 2.0 * r * r * r);
}
template <JetType J>
J operator/(const J& x, const J& y) {
  return x * Reciprocal(y);
}

// Mixed jet/double arithmetic. These operators deduce the jet as JetT<N>, not as a J constrained
// by JetType: clang 14 substitutes a deduced J = int into an operator's signature before checking
// the constraint and then rejects `int <= enum` (or `i += enum`) in any file of namespace ocpb that
// includes this header.
template <template <int> class JetT, int N>
JetT<N> operator+(const JetT<N>& x, double c) requires JetType<JetT<N>> {
  JetT<N> r = x;
  r.a += c;
  return r;
}
template <template <int> class JetT, int N>
JetT<N> operator+(double c, const JetT<N>& x) requires JetType<JetT<N>> {
  return x + c;
}
template <template <int> class JetT, int N>
JetT<N> operator-(const JetT<N>& x, double c) requires JetType<JetT<N>> {
  return x + (-c);
}
template <template <int> class JetT, int N>
JetT<N> operator-(double c, const JetT<N>& x) requires JetType<JetT<N>> {
  return (-x) + c;
}
template <template <int> class JetT, int N>
JetT<N> operator*(const JetT<N>& x, double c) requires JetType<JetT<N>> {
  return x.Chain(x.a * c, c, 0.0);
}
template <template <int> class JetT, int N>
JetT<N> operator*(double c, const JetT<N>& x) requires JetType<JetT<N>> {
  return x * c;
}
template <template <int> class JetT, int N>
JetT<N> operator/(const JetT<N>& x, double c) requires JetType<JetT<N>> {
  return x * (1.0 / c);
}
template <template <int> class JetT, int N>
JetT<N> operator/(double c, const JetT<N>& x) requires JetType<JetT<N>> {
  return c * Reciprocal(x);
}
template <JetType J>
J& operator+=(J& x, const J& y) {
  return x = x + y;
}
template <JetType J>
J& operator-=(J& x, const J& y) {
  return x = x - y;
}
template <JetType J>
J& operator*=(J& x, const J& y) {
  return x = x * y;
}
template <template <int> class JetT, int N>
JetT<N>& operator+=(JetT<N>& x, double c) requires JetType<JetT<N>> {
  return x = x + c;
}
template <template <int> class JetT, int N>
JetT<N>& operator*=(JetT<N>& x, double c) requires JetType<JetT<N>> {
  return x = x * c;
}

// Comparisons look at values only (branches are taken on the value); the mixed ones deduce
// JetT<N> as above.
template <JetType J>
bool operator<(const J& x, const J& y) {
  return x.a < y.a;
}
template <JetType J>
bool operator>(const J& x, const J& y) {
  return x.a > y.a;
}
template <template <int> class JetT, int N>
bool operator<(const JetT<N>& x, double c) requires JetType<JetT<N>> {
  return x.a < c;
}
template <template <int> class JetT, int N>
bool operator>(const JetT<N>& x, double c) requires JetType<JetT<N>> {
  return x.a > c;
}
template <template <int> class JetT, int N>
bool operator<=(const JetT<N>& x, double c) requires JetType<JetT<N>> {
  return x.a <= c;
}
template <template <int> class JetT, int N>
bool operator>=(const JetT<N>& x, double c) requires JetType<JetT<N>> {
  return x.a >= c;
}

// ---- elementary functions ---------------------------------------------------
// Plain-double versions in this namespace, so that a problem written as a template
// calls `exp(x)` unqualified for both doubles and jets.
inline double exp(double x) { return std::exp(x); }
inline double log(double x) { return std::log(x); }
inline double sqrt(double x) { return std::sqrt(x); }
inline double sin(double x) { return std::sin(x); }
inline double cos(double x) { return std::cos(x); }
inline double tan(double x) { return std::tan(x); }
inline double atan(double x) { return std::atan(x); }
inline double pow(double x, double p) { return std::pow(x, p); }
inline double abs(double x) { return std::abs(x); }
inline double sinh(double x) { return std::sinh(x); }
inline double cosh(double x) { return std::cosh(x); }
inline double tanh(double x) { return std::tanh(x); }
inline double asin(double x) { return std::asin(x); }
inline double acos(double x) { return std::acos(x); }
inline double log1p(double x) { return std::log1p(x); }
inline double expm1(double x) { return std::expm1(x); }
inline double atan2(double y, double x) { return std::atan2(y, x); }
inline double hypot(double x, double y) { return std::hypot(x, y); }

template <JetType J>
J exp(const J& x) {
  const double e = std::exp(x.a);
  return x.Chain(e, e, e);
}
template <JetType J>
J log(const J& x) {
  return x.Chain(std::log(x.a), 1.0 / x.a, -1.0 / (x.a * x.a));
}
template <JetType J>
J sqrt(const J& x) {
  const double s = std::sqrt(x.a);
  return x.Chain(s, 0.5 / s, -0.25 / (s * x.a));
}
template <JetType J>
J sin(const J& x) {
  const double s = std::sin(x.a), c = std::cos(x.a);
  return x.Chain(s, c, -s);
}
template <JetType J>
J cos(const J& x) {
  const double s = std::sin(x.a), c = std::cos(x.a);
  return x.Chain(c, -s, -c);
}
template <JetType J>
J tan(const J& x) {
  const double t = std::tan(x.a), sec2 = 1.0 + t * t;
  return x.Chain(t, sec2, 2.0 * t * sec2);
}
template <JetType J>
J atan(const J& x) {
  const double d = 1.0 / (1.0 + x.a * x.a);
  return x.Chain(std::atan(x.a), d, -2.0 * x.a * d * d);
}
/// x^p for a constant exponent p.
template <JetType J>
J pow(const J& x, double p) {
  const double v = std::pow(x.a, p);
  const double d1 = p * std::pow(x.a, p - 1.0);
  const double d2 = p * (p - 1.0) * std::pow(x.a, p - 2.0);
  return x.Chain(v, d1, d2);
}
/// c^x for a constant base c > 0.
template <JetType J>
J pow(double c, const J& x) {
  const double lc = std::log(c), v = std::pow(c, x.a);
  return x.Chain(v, lc * v, lc * lc * v);
}
/// |x|: the derivative at 0 is taken as 0 (a problem that crosses 0 must smooth it).
template <JetType J>
J abs(const J& x) {
  return x.a >= 0.0 ? x : -x;
}
template <JetType J>
J sinh(const J& x) {
  const double s = std::sinh(x.a), c = std::cosh(x.a);
  return x.Chain(s, c, s);
}
template <JetType J>
J cosh(const J& x) {
  const double s = std::sinh(x.a), c = std::cosh(x.a);
  return x.Chain(c, s, c);
}
/// tanh' = 1 / cosh^2 (not 1 - tanh^2, which cancels to 0 for |x| > 19), tanh'' = -2 tanh tanh'.
template <JetType J>
J tanh(const J& x) {
  const double t = std::tanh(x.a), sech = 1.0 / std::cosh(x.a), d1 = sech * sech;
  return x.Chain(t, d1, -2.0 * t * d1);
}
/// asin' = 1 / sqrt(1 - x^2), asin'' = x / (1 - x^2)^(3/2), with 1 - x^2 as (1 - x)(1 + x) for
/// accuracy near +-1. As sqrt at 0: at x = +-1 the derivatives are infinite; outside [-1, 1]
/// the value and the derivatives are NaN.
template <JetType J>
J asin(const J& x) {
  const double d1 = 1.0 / std::sqrt((1.0 - x.a) * (1.0 + x.a));
  return x.Chain(std::asin(x.a), d1, x.a * d1 * d1 * d1);
}
/// acos = pi/2 - asin: the derivatives of asin negated (same edges).
template <JetType J>
J acos(const J& x) {
  const double d1 = 1.0 / std::sqrt((1.0 - x.a) * (1.0 + x.a));
  return x.Chain(std::acos(x.a), -d1, -x.a * d1 * d1 * d1);
}
/// log(1 + x), accurate for small |x|; as log at 0: at x = -1 the value is -inf, below it NaN.
template <JetType J>
J log1p(const J& x) {
  const double d1 = 1.0 / (1.0 + x.a);
  return x.Chain(std::log1p(x.a), d1, -d1 * d1);
}
/// exp(x) - 1, accurate for small |x|.
template <JetType J>
J expm1(const J& x) {
  const double e = std::exp(x.a);
  return x.Chain(std::expm1(x.a), e, e);
}

namespace jet_detail {
/// A function phi(p, q) of two arguments at one point: its value and partial derivatives.
struct BinaryPartials {
  double value, dp, dq, dpp, dpq, dqq;
};
/// atan2(y, x) = the angle of (x, y) in (-pi, pi]; partials in the order (y, x):
///   d/dy = x/r^2, d/dx = -y/r^2, d2/dy2 = -2xy/r^4, d2/dydx = (y^2 - x^2)/r^4, d2/dx2 = 2xy/r^4,
/// written with (x, y)/r to avoid overflow. At the origin, where the angle has no limit, the
/// derivatives are taken as 0 (the convention of abs at 0).
inline BinaryPartials Atan2Partials(double y, double x) {
  BinaryPartials p{std::atan2(y, x), 0.0, 0.0, 0.0, 0.0, 0.0};
  const double r = std::hypot(x, y);
  if (r == 0.0) return p;
  const double cx = x / r, cy = y / r, r2 = r * r;
  p.dp = cx / r;
  p.dq = -cy / r;
  p.dpp = -2.0 * cx * cy / r2;
  p.dpq = (cy * cy - cx * cx) / r2;
  p.dqq = 2.0 * cx * cy / r2;
  return p;
}
/// hypot(x, y) = r = sqrt(x^2 + y^2) without overflow; partials in the order (x, y):
///   x/r, y/r, y^2/r^3, -xy/r^3, x^2/r^3.
/// At the origin the gradient is taken as 0 (a subgradient of the norm, the convention of abs at
/// 0) and so is the (unbounded) Hessian.
inline BinaryPartials HypotPartials(double x, double y) {
  const double r = std::hypot(x, y);
  BinaryPartials p{r, 0.0, 0.0, 0.0, 0.0, 0.0};
  if (r == 0.0) return p;
  const double cx = x / r, cy = y / r;
  p.dp = cx;
  p.dq = cy;
  p.dpp = cy * cy / r;
  p.dpq = -cx * cy / r;
  p.dqq = cx * cx / r;
  return p;
}
}  // namespace jet_detail

/// atan2(y, x): the angle of the point (x, y), in (-pi, pi], continuous except across the
/// negative x axis, where the value jumps by 2 pi but the derivatives are continuous. Derivatives
/// at (0, 0) are 0 (see jet_detail::Atan2Partials). Jet-jet, jet-double and double-jet forms.
template <JetType J>
J atan2(const J& y, const J& x) {
  const jet_detail::BinaryPartials p = jet_detail::Atan2Partials(y.a, x.a);
  return y.Chain2(x, p.value, p.dp, p.dq, p.dpp, p.dpq, p.dqq);
}
template <template <int> class JetT, int N>
JetT<N> atan2(const JetT<N>& y, double x) requires JetType<JetT<N>> {
  const jet_detail::BinaryPartials p = jet_detail::Atan2Partials(y.a, x);
  return y.Chain(p.value, p.dp, p.dpp);
}
template <template <int> class JetT, int N>
JetT<N> atan2(double y, const JetT<N>& x) requires JetType<JetT<N>> {
  const jet_detail::BinaryPartials p = jet_detail::Atan2Partials(y, x.a);
  return x.Chain(p.value, p.dq, p.dqq);
}
/// hypot(x, y) = sqrt(x^2 + y^2) without overflow or underflow. At (0, 0) the gradient and the
/// Hessian are 0 (see jet_detail::HypotPartials); away from it hypot(x, eps) with a constant
/// eps > 0 is a smooth |x| (error at most eps, C-infinity).
template <JetType J>
J hypot(const J& x, const J& y) {
  const jet_detail::BinaryPartials p = jet_detail::HypotPartials(x.a, y.a);
  return x.Chain2(y, p.value, p.dp, p.dq, p.dpp, p.dpq, p.dqq);
}
template <template <int> class JetT, int N>
JetT<N> hypot(const JetT<N>& x, double y) requires JetType<JetT<N>> {
  const jet_detail::BinaryPartials p = jet_detail::HypotPartials(x.a, y);
  return x.Chain(p.value, p.dp, p.dpp);
}
template <template <int> class JetT, int N>
JetT<N> hypot(double x, const JetT<N>& y) requires JetType<JetT<N>> {
  const jet_detail::BinaryPartials p = jet_detail::HypotPartials(x, y.a);
  return y.Chain(p.value, p.dq, p.dqq);
}

template <JetType J>
J square(const J& x) {
  return x * x;
}
inline double square(double x) { return x * x; }

// ---- smooth approximations ------------------------------------------------------
/// A double or a jet (or a number that converts to double).
template <typename T>
concept ScalarOrJet = std::is_arithmetic_v<T> || JetType<T>;

/// A smooth max(a, b) for eps > 0: (a + b + hypot(a - b, eps)) / 2. C-infinity, always above
/// max(a, b), by eps / 2 where a = b and by less than eps^2 / (4 |a - b|) away from it; its
/// derivatives with respect to a and b lie in (0, 1) and sum to 1. eps = 0 gives max(a, b)
/// exactly (derivative 1/2 each where a = b). Any mix of doubles and jets: SmoothMax(x, 0.0, eps)
/// is a smooth max(x, 0), as for a penalty or a saturation that Newton's method can cross.
template <ScalarOrJet A, ScalarOrJet B>
auto SmoothMax(const A& a, const B& b, double eps) {
  return 0.5 * (a + b + hypot(a - b, eps));
}
/// A smooth min(a, b) for eps > 0: (a + b - hypot(a - b, eps)) / 2 = -SmoothMax(-a, -b, eps),
/// always below min(a, b), with the same error bounds.
template <ScalarOrJet A, ScalarOrJet B>
auto SmoothMin(const A& a, const B& b, double eps) {
  return 0.5 * (a + b - hypot(a - b, eps));
}

/// A jet of a function of two jets whose value, gradient and Hessian are known
/// numerically (for example a channel map s(q)): the chain rule for phi(x, y).
template <JetType J>
J ApplyBinary(const J& x,
              const J& y,
              double value,
              const Eigen::Vector2d& grad,
              const Eigen::Matrix2d& hess) {
  J r;
  r.a = value;
  r.g = grad[0] * x.g + grad[1] * y.g;
  if constexpr (requires { r.h; }) {
    r.h = grad[0] * x.h + grad[1] * y.h + hess(0, 0) * x.g * x.g.transpose() +
          hess(1, 1) * y.g * y.g.transpose() +
          hess(0, 1) * (x.g * y.g.transpose() + y.g * x.g.transpose());
  }
  return r;
}
inline double ApplyBinary(double /*x*/,
                          double /*y*/,
                          double value,
                          const Eigen::Vector2d& /*grad*/,
                          const Eigen::Matrix2d& /*hess*/) {
  return value;
}

}  // namespace ocpb

// Let Eigen hold jets in its fixed-size matrices.
namespace Eigen {
template <int N>
struct NumTraits<ocpb::Jet1<N>> : NumTraits<double> {
  using Real = ocpb::Jet1<N>;
  using NonInteger = ocpb::Jet1<N>;
  using Nested = ocpb::Jet1<N>;
  enum { IsComplex = 0, RequireInitialization = 1, ReadCost = 1, AddCost = 2, MulCost = 4 };
};
template <int N>
struct NumTraits<ocpb::Jet2<N>> : NumTraits<double> {
  using Real = ocpb::Jet2<N>;
  using NonInteger = ocpb::Jet2<N>;
  using Nested = ocpb::Jet2<N>;
  enum { IsComplex = 0, RequireInitialization = 1, ReadCost = 1, AddCost = 2, MulCost = 4 };
};
}  // namespace Eigen
