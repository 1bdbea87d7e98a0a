// The functions of core/jet.h beyond the first set, through the path every solver uses:
// AutoDiffOcp's Jet1 / Jet2 passes over dynamics, running cost, terminal cost, terminal and path
// constraints, checked by CheckOcpDerivatives against central differences (first derivatives and
// the Hessians of the Lagrangian).
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/autodiff_ocp.h"
#include "core/derivative_check.h"

namespace ocpb {
namespace {

// Each function as G(p, q): the binary ones as they are, a unary phi as phi(p) + phi(q), so
// that G takes the (jet, jet), (jet, double) and (double, jet) forms alike.
#define OCPB_UNARY_AS_BINARY(NAME, FN)        \
  struct NAME {                               \
    static constexpr const char* kName = #FN; \
    template <class P, class Q>               \
    static auto G(const P& p, const Q& q) {   \
      return FN(p) + FN(q);                   \
    }                                         \
  };
OCPB_UNARY_AS_BINARY(SinhG, sinh)
OCPB_UNARY_AS_BINARY(CoshG, cosh)
OCPB_UNARY_AS_BINARY(TanhG, tanh)
OCPB_UNARY_AS_BINARY(AsinG, asin)
OCPB_UNARY_AS_BINARY(AcosG, acos)
OCPB_UNARY_AS_BINARY(Log1pG, log1p)
OCPB_UNARY_AS_BINARY(Expm1G, expm1)
#undef OCPB_UNARY_AS_BINARY
struct Atan2G {
  static constexpr const char* kName = "atan2";
  template <class P, class Q>
  static auto G(const P& p, const Q& q) {
    return atan2(p, q);
  }
};
struct HypotG {
  static constexpr const char* kName = "hypot";
  template <class P, class Q>
  static auto G(const P& p, const Q& q) {
    return hypot(p, q);
  }
};
struct SmoothMaxG {
  static constexpr const char* kName = "SmoothMax";
  template <class P, class Q>
  static auto G(const P& p, const Q& q) {
    return SmoothMax(p, q, 0.25);
  }
};
struct SmoothMinG {
  static constexpr const char* kName = "SmoothMin";
  template <class P, class Q>
  static auto G(const P& p, const Q& q) {
    return SmoothMin(p, q, 0.25);
  }
};

// A problem whose every piece uses G: nx = 2, nu = 2, one terminal and one path constraint.
// For |x_i|, |u_j| <= 1 every argument of G is in (-0.8, 0.8) (inside the domains of asin,
// acos, log1p); the signs of a and b are those of x0 and u1, so the points below put (a, b) in
// each quadrant and on both sides of the negative axis of atan2(a, b).
template <class F>
class FunctionOcp final : public AutoDiffOcp<FunctionOcp<F>, 2, 2, 1, 1> {
 public:
  FunctionOcp() { this->SetHorizon(0.0, 1.0); }
  std::string name() const override { return std::string("function-") + F::kName; }
  template <class T>
  static T A(const VecT<T, 2>& x, const VecT<T, 2>& u) {
    return 0.6 * x[0] * (1.0 + 0.25 * u[0] * x[1]);
  }
  template <class T>
  static T B(const VecT<T, 2>& x, const VecT<T, 2>& u) {
    return 0.6 * u[1] * (1.0 - 0.25 * x[0] * u[0]);
  }
  template <class T>
  void EvalDynamics(double, const VecT<T, 2>& x, const VecT<T, 2>& u, VecT<T, 2>* f) const {
    (*f)[0] = F::G(A(x, u), B(x, u));
    (*f)[1] = F::G(B(x, u), -0.45) * x[1] + u[0];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 2>& x, const VecT<T, 2>& u) const {
    return F::G(0.3, A(x, u)) + 0.5 * u[0] * u[0];
  }
  template <class T>
  T EvalTerminalCost(const VecT<T, 2>& x) const {
    return F::G(0.7 * x[0], 0.6 * x[1] - 0.1 * x[0] * x[1]);
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 2>& x, VecT<T, 1>* psi) const {
    (*psi)[0] = F::G(0.6 * x[0] * x[1], -0.4);
  }
  template <class T>
  void EvalPathConstraints(double, const VecT<T, 2>& x, const VecT<T, 2>& u, VecT<T, 1>* c) const {
    (*c)[0] = F::G(-0.5, 0.5 * B(x, u) + 0.2 * x[1]);
  }
};

struct CheckPoint {
  double x0, x1, u0, u1;
};
const std::vector<CheckPoint> kCheckPoints = {
    {0.4, -0.8, 0.9, -0.3},    // a > 0, b < 0
    {-0.7, 0.5, -0.6, 0.8},    // a < 0, b > 0
    {-0.9, -0.2, 0.3, -0.95},  // a < 0, b < 0
    {0.2, 0.6, -0.8, 0.1},     // a > 0, b > 0
    {1e-3, 0.3, 0.5, -0.9},    // just above the negative b axis
    {-1e-3, 0.3, 0.5, -0.9},   // just below it
};

DerivativeCheck CheckAt(const Ocp& ocp, const CheckPoint& p) {
  Vec x(2), u(2), lambda(2), mu(1), nu(1);
  x << p.x0, p.x1;
  u << p.u0, p.u1;
  lambda << 1.3, -0.8;
  mu << 0.6;
  nu << -1.7;
  return CheckOcpDerivatives(ocp, 0.25, x, u, lambda, mu, nu);
}

template <class F>
class AutoDiffFunctions : public ::testing::Test {};
using FunctionTypes = ::testing::Types<Atan2G,
                                       HypotG,
                                       SinhG,
                                       CoshG,
                                       TanhG,
                                       AsinG,
                                       AcosG,
                                       Log1pG,
                                       Expm1G,
                                       SmoothMaxG,
                                       SmoothMinG>;
TYPED_TEST_SUITE(AutoDiffFunctions, FunctionTypes);

TYPED_TEST(AutoDiffFunctions, EveryDerivativeOfTheOcpMatchesFiniteDifferences) {
  const FunctionOcp<TypeParam> ocp;
  for (const CheckPoint& p : kCheckPoints) {
    const DerivativeCheck check = CheckAt(ocp, p);
    EXPECT_LT(check.max_error, 1e-7) << TypeParam::kName << " at x = (" << p.x0 << ", " << p.x1
                                     << "), u = (" << p.u0 << ", " << p.u1 << ")\n"
                                     << check.log;
  }
}

// The check fails when a function's derivative is wrong: tanh with a wrong first derivative
// (1 - tanh^2 scaled by 1.01) or with the wrong sign of its second (+2 tanh tanh').
template <bool kWrongFirst>
struct WrongTanhG {
  static constexpr const char* kName = kWrongFirst ? "tanh, wrong first" : "tanh, wrong second";
  template <class T>
  static T WrongTanh(const T& s) {
    if constexpr (JetType<T>) {
      const double t = std::tanh(s.a), d1 = 1.0 - t * t;
      return kWrongFirst ? s.Chain(t, 1.01 * d1, -2.0 * t * d1) : s.Chain(t, d1, 2.0 * t * d1);
    } else {
      return std::tanh(s);
    }
  }
  template <class P, class Q>
  static auto G(const P& p, const Q& q) {
    return WrongTanh(p) + WrongTanh(q);
  }
};

// The error CheckOcpDerivatives logged on the line that starts with `name`.
double LoggedError(const std::string& log, const std::string& name) {
  const size_t line = log.find(name);
  if (line == std::string::npos) return NAN;
  return std::stod(log.substr(log.find(": ", line) + 2));
}

TEST(AutoDiffFunctionsCheck, CatchesAWrongFirstOrSecondDerivative) {
  const FunctionOcp<WrongTanhG<true>> wrong_first;
  const FunctionOcp<WrongTanhG<false>> wrong_second;
  const DerivativeCheck first = CheckAt(wrong_first, kCheckPoints[0]);
  const DerivativeCheck second = CheckAt(wrong_second, kCheckPoints[0]);
  EXPECT_GT(LoggedError(first.log, "f_(x,u)"), 1e-4) << first.log;
  // The second: its first derivatives are right, its Hessians are not.
  EXPECT_LT(LoggedError(second.log, "f_(x,u)"), 1e-7) << second.log;
  EXPECT_GT(LoggedError(second.log, "hessian_(x,u)"), 1e-2) << second.log;
  EXPECT_GT(LoggedError(second.log, "terminal hessian"), 1e-2) << second.log;
}

}  // namespace
}  // namespace ocpb
