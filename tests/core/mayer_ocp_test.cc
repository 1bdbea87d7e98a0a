// Mayer problems: AutoDiffOcp without EvalRunningCost has L = 0, and everything derived from L
// (its gradient, its share of PointHessian, RunningCostLowerBound) says so.
#include <cmath>
#include <optional>
#include <string>

#include <gtest/gtest.h>

#include "core/autodiff_ocp.h"
#include "core/derivative_check.h"
#include "tests/core/max_range_ocp.h"
#include "tests/core/slip_ocp.h"
#include "tests/core/test_problems.h"
#include "tests/core/user_double_integrator.h"

namespace ocpb {
namespace {

using testing::MaxRangeOcp;
using testing::UserDoubleIntegrator;

// A running cost declared one layer up, between AutoDiffOcp and the problem.
template <class Derived>
class QuadraticCostLayer : public AutoDiffOcp<Derived, 1, 1> {
 public:
  template <class T>
  T EvalRunningCost(double, const VecT<T, 1>&, const VecT<T, 1>& u) const {
    return u[0] * u[0];
  }
};
class LayeredOcp final : public QuadraticCostLayer<LayeredOcp> {
 public:
  std::string name() const override { return "layered"; }
  template <class T>
  void EvalDynamics(double, const VecT<T, 1>& x, const VecT<T, 1>& u, VecT<T, 1>* f) const {
    (*f)[0] = x[0] * u[0];
  }
};

// Every problem that declares EvalRunningCost, directly or in a base, keeps it.
static_assert(!MaxRangeOcp::DefinesRunningCost());
static_assert(UserDoubleIntegrator::DefinesRunningCost());
static_assert(testing::NonlinearTestOcp::DefinesRunningCost());
static_assert(testing::SlipOcp::DefinesRunningCost());
static_assert(LayeredOcp::DefinesRunningCost());

TEST(MayerProblem, ARunningCostDeclaredInABaseIsKept) {
  const LayeredOcp ocp;
  const Vec x = Vec::Constant(1, 2.0), u = Vec::Constant(1, -3.0);
  EXPECT_EQ(ocp.RunningCost(0.0, x, u), 9.0);
  Mat hess(2, 2);
  ocp.PointHessian(0.0, x, u, 1.0, Vec::Zero(1), Vec(), hess);
  EXPECT_EQ(hess(1, 1), 2.0);
}

TEST(MayerProblem, HasAZeroRunningCostWithZeroDerivatives) {
  const MaxRangeOcp ocp;
  Vec x(2), u(1), Lx = Vec::Constant(2, 7.0), Lu = Vec::Constant(1, 7.0);
  x << 0.3, -0.2;
  u << 0.9;
  EXPECT_EQ(ocp.RunningCost(0.5, x, u), 0.0);
  double L = 7.0;
  ocp.RunningCostGradient(0.5, x, u, &L, Lx, Lu);
  EXPECT_EQ(L, 0.0);
  EXPECT_TRUE(Lx.isZero(0.0));
  EXPECT_TRUE(Lu.isZero(0.0));
  EXPECT_EQ(ocp.RunningCostLowerBound(), std::optional<double>(0.0));
  // A problem with a running cost keeps Ocp's default (no bound).
  EXPECT_FALSE(UserDoubleIntegrator().RunningCostLowerBound().has_value());
}

TEST(MayerProblem, PointHessianIsTheDynamicsAloneWhateverSigma) {
  const MaxRangeOcp ocp;
  Vec x(2), u(1), lambda(2);
  x << 0.3, -0.2;
  u << 0.9;
  lambda << 0.0, 0.0;
  Mat hess = Mat::Constant(3, 3, 7.0);
  ocp.PointHessian(0.5, x, u, 1.0, lambda, Vec(), hess);
  EXPECT_TRUE(hess.isZero(0.0)) << hess;
  // lambda^T f'' only: d2/du2 (l1 cos u + l2 sin u) = -(l1 cos u + l2 sin u).
  lambda << 1.5, -0.5;
  for (const double sigma : {0.0, 1.0, 3.0}) {
    ocp.PointHessian(0.5, x, u, sigma, lambda, Vec(), hess);
    Mat want = Mat::Zero(3, 3);
    want(2, 2) = -(1.5 * std::cos(0.9) - 0.5 * std::sin(0.9));
    EXPECT_TRUE(hess.isApprox(want, 1e-15)) << hess;
  }
}

TEST(MayerProblem, DerivativesMatchFiniteDifferences) {
  const MaxRangeOcp ocp;
  Vec x(2), u(1), lambda(2), nu(1);
  x << 0.3, -0.2;
  u << 0.9;
  lambda << 1.5, -0.5;
  nu << 2.0;
  const DerivativeCheck check = CheckOcpDerivatives(ocp, 0.5, x, u, lambda, Vec(), nu);
  EXPECT_LT(check.max_error, 1e-7) << check.log;
}

}  // namespace
}  // namespace ocpb
