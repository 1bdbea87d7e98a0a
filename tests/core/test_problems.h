// Small problems used only by the core tests.
#pragma once

#include "core/autodiff_ocp.h"

namespace ocpb::testing {

/// A deliberately nonlinear problem exercising every elementary function of core/jet.h:
///   x1' = x2 sin(u1) + exp(-x3),  x2' = x1 x3 / (1 + x2^2) + u2,  x3' = sqrt(1 + x1^2) - log(2 + u1^2)
///   L = x1^2 u2^2 + cos(x2) u1 + pow(1 + x3^2, 1.5),  phi = x1 x2 + atan(x3),
///   psi = (x1 - 1, x2 x3),  c = x1 + u1^2 - 3.
class NonlinearTestOcp final : public AutoDiffOcp<NonlinearTestOcp, 3, 2, 2, 1> {
 public:
  NonlinearTestOcp() {
    SetDimensions(3, 2, 2, 1);
    SetHorizon(0.0, 1.0);
    Vec x0(3);
    x0 << 0.3, -0.2, 0.5;
    SetInitialState(x0);
    Vec w(2);
    w << 10.0, 3.0;
    SetTerminalWeights(w);
  }
  std::string name() const override { return "nonlinear-test"; }

  template <class T>
  void EvalDynamics(double t, const VecT<T, 3>& x, const VecT<T, 2>& u, VecT<T, 3>* f) const {
    (*f)[0] = x[1] * sin(u[0]) + exp(-x[2]) + t;
    (*f)[1] = x[0] * x[2] / (1.0 + x[1] * x[1]) + u[1];
    (*f)[2] = sqrt(1.0 + x[0] * x[0]) - log(2.0 + u[0] * u[0]);
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 3>& x, const VecT<T, 2>& u) const {
    return x[0] * x[0] * u[1] * u[1] + cos(x[1]) * u[0] + pow(1.0 + x[2] * x[2], 1.5);
  }
  template <class T>
  T EvalTerminalCost(const VecT<T, 3>& x) const {
    return x[0] * x[1] + atan(x[2]);
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 3>& x, VecT<T, 2>* psi) const {
    (*psi)[0] = x[0] - 1.0;
    (*psi)[1] = x[1] * x[2];
  }
  template <class T>
  void EvalPathConstraints(double, const VecT<T, 3>& x, const VecT<T, 2>& u, VecT<T, 1>* c) const {
    (*c)[0] = x[0] + u[0] * u[0] - 3.0;
  }
};

}  // namespace ocpb::testing
