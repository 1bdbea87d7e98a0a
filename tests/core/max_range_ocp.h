// A Mayer problem written without a running cost: the maximum range of a unit-speed heading
// control with a prescribed final cross-range.
#pragma once

#include <cmath>
#include <string>

#include "core/autodiff_ocp.h"

namespace ocpb::testing {

/// minimize -x(1), x' = cos(theta), y' = sin(theta), x(0) = y(0) = 0, psi = y(1) - h = 0, the
/// control theta unbounded. f does not depend on the state, so the costate p = (-1, p_y) is
/// constant (p(1) = phi_x + psi_x^T nu), and H = p^T f minimal in theta for every t gives one
/// constant heading with tan(theta) = -p_y; y(1) = sin(theta) = h. Hence theta* = asin(h),
/// J* = -sqrt(1 - h^2) (-0.8 for h = 0.6) and p* = (-1, -h / sqrt(1 - h^2)) = (-1, -0.75).
/// A constant control is integrated exactly by every scheme, so each transcription's discrete
/// optimum is the continuous one.
class MaxRangeOcp final : public AutoDiffOcp<MaxRangeOcp, 2, 1, 1, 0> {
 public:
  explicit MaxRangeOcp(double h = 0.6) : h_(h) {
    SetHorizon(0.0, 1.0);
    SetInitialState(Vec::Zero(2));
    SetTerminalWeights(Vec::Constant(1, 100.0));
  }
  std::string name() const override { return "max-range"; }
  double OptimalCost() const { return -std::sqrt(1.0 - h_ * h_); }
  double OptimalHeading() const { return std::asin(h_); }
  double OptimalCostateY() const { return -h_ / std::sqrt(1.0 - h_ * h_); }

  template <class T>
  void EvalDynamics(double, const VecT<T, 2>&, const VecT<T, 1>& u, VecT<T, 2>* f) const {
    (*f)[0] = cos(u[0]);
    (*f)[1] = sin(u[0]);
  }
  // No EvalRunningCost: L = 0.
  template <class T>
  T EvalTerminalCost(const VecT<T, 2>& x) const {
    return -x[0];
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 2>& x, VecT<T, 1>* psi) const {
    (*psi)[0] = x[1] - h_;
  }

 private:
  double h_;
};

}  // namespace ocpb::testing
