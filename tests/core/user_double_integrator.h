// A double integrator with two terminal constraints written as a user would (AutoDiffOcp), with
// the mistakes of issue 24 selectable: a second, disagreeing statement of the dimensions, and
// terminal weights left at their default.
#pragma once

#include <string>

#include "core/autodiff_ocp.h"

namespace ocpb::testing {

/// minimize int_0^1 u^2 dt, x' = (x2, u), x(0) = 0, psi = (x1(1) - 1, x2(1)) = 0 (J* = 12 in
/// the hard form). `declared_npsi` is what the constructor tells SetDimensions (< 0: it does
/// not call it); `weight` > 0 is passed to SetTerminalWeights for both constraints (<= 0: never
/// called, the default w = 1 stays); `x0_first` sets x0 = (0.5, 0.5) before SetDimensions.
class UserDoubleIntegrator final : public AutoDiffOcp<UserDoubleIntegrator, 2, 1, 2, 0> {
 public:
  explicit UserDoubleIntegrator(int declared_npsi = -1,
                                double weight = 0.0,
                                bool x0_first = false) {
    if (x0_first) SetInitialState(Vec::Constant(2, 0.5));
    if (declared_npsi >= 0) SetDimensions(2, 1, declared_npsi, 0);
    SetHorizon(0.0, 1.0);
    if (!x0_first) SetInitialState(Vec::Zero(2));
    if (weight > 0.0) SetTerminalWeights(Vec::Constant(2, weight));
  }
  std::string name() const override { return "user-double-integrator"; }
  template <class T>
  void EvalDynamics(double, const VecT<T, 2>& x, const VecT<T, 1>& u, VecT<T, 2>* f) const {
    (*f)[0] = x[1];
    (*f)[1] = u[0];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 2>&, const VecT<T, 1>& u) const {
    return u[0] * u[0];
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 2>& x, VecT<T, 2>* psi) const {
    (*psi)[0] = x[0] - 1.0;
    (*psi)[1] = x[1];
  }
};

}  // namespace ocpb::testing
