#include "core/derivative_check.h"

#include <gtest/gtest.h>

#include "problems/registry.h"
#include "tests/core/test_problems.h"

namespace ocpb {
namespace {

TEST(AutoDiffOcp, NonlinearProblemDerivativesMatchFiniteDifferences) {
  const testing::NonlinearTestOcp ocp;
  Vec x(3), u(2), lambda(3), mu(1), nu(2);
  x << 0.4, -0.8, 1.2;
  u << 0.9, -0.3;
  lambda << 1.5, -0.7, 0.2;
  mu << 0.8;
  nu << -1.3, 2.1;
  const DerivativeCheck check = CheckOcpDerivatives(ocp, 0.37, x, u, lambda, mu, nu);
  EXPECT_LT(check.max_error, 1e-7) << check.log;
}

TEST(AutoDiffOcp, DoubleIntegratorDerivativesMatchFiniteDifferences) {
  const auto ocp = MakeProblem("double-integrator", {}, 0);
  Vec x(2), u(1), lambda(2), mu(0), nu(2);
  x << 0.3, -0.4;
  u << 1.7;
  lambda << 0.5, 2.0;
  nu << 1.0, -3.0;
  const DerivativeCheck check = CheckOcpDerivatives(*ocp, 0.5, x, u, lambda, mu, nu);
  EXPECT_LT(check.max_error, 1e-7) << check.log;
}

// The checker must be able to fail: a problem whose hand-written Jacobian is wrong is caught.
class WrongJacobianOcp final : public AutoDiffOcp<WrongJacobianOcp, 1, 1> {
 public:
  WrongJacobianOcp() {
    SetDimensions(1, 1, 0, 0);
    SetHorizon(0.0, 1.0);
  }
  std::string name() const override { return "wrong"; }
  template <class T>
  void EvalDynamics(double, const VecT<T, 1>& x, const VecT<T, 1>& u, VecT<T, 1>* f) const {
    (*f)[0] = x[0] * x[0] + u[0];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 1>&, const VecT<T, 1>& u) const {
    return u[0] * u[0];
  }
  void DynamicsJacobian(double t, ConstVecRef x, ConstVecRef u, VecRef f, MatRef fx,
                        MatRef fu) const override {
    Dynamics(t, x, u, f);
    fx(0, 0) = x[0];  // wrong on purpose: should be 2 x
    fu(0, 0) = 1.0;
  }
};

TEST(DerivativeCheck, DetectsAWrongJacobian) {
  const WrongJacobianOcp ocp;
  const DerivativeCheck check = CheckOcpDerivatives(ocp, 0.0, Vec::Constant(1, 2.0), Vec::Constant(1, 0.5),
                                                    Vec::Constant(1, 1.0), Vec(0), Vec(0));
  EXPECT_GT(check.max_error, 0.5) << check.log;
}

}  // namespace
}  // namespace ocpb
