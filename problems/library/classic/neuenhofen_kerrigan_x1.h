// Neuenhofen and Kerrigan's example X1: a singular arc over the whole horizon, with a closed-form
// optimum (OCPBench problem "neuenhofen-kerrigan-x1").
#pragma once

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    J = int_0^(pi/2) (y^2 + cos(t) u) dt
/// subject to  y' = y^2 / 2 + u,  y(0) = 0,  y(pi/2) free,  -1.5 <= u <= 1.
///
/// M. P. Neuenhofen and E. C. Kerrigan, "An integral penalty-barrier direct transcription method
/// for optimal control", IEEE CDC 2020, example X1 (PSOPT example `x1`). H = y^2 + cos(t) u +
/// p (y^2/2 + u) is linear in u, and the optimum is singular on the whole horizon: p = -cos t
/// makes H_u = 0, and the bounds are inactive. Closed form: y*(t) = -sin t / (2 - cos t),
/// u*(t) = 1/2 - 3 / (2 (cos t - 2)^2), J* = -0.256996962561 (the PSOPT example checks it by
/// quadrature; OCPBench's midpoint quadrature of the closed form with 2e5 steps gives
/// -0.25699696256). Collocation schemes are known to let u ring here (the NLP's reduced Hessian
/// in u is singular); the discrete objective may lie below J*.
///
/// Hamiltonian method: not applicable (H linear in u, singular everywhere).
class NeuenhofenKerriganX1 final : public AutoDiffOcp<NeuenhofenKerriganX1, 1, 1, 0, 0> {
 public:
  static constexpr double kReferenceCost = -0.256996962561;
  static std::vector<ParameterSpec> ParameterSpecs() { return {}; }
  explicit NeuenhofenKerriganX1(const Parameters& params);

  std::string name() const override { return "neuenhofen-kerrigan-x1"; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 1>& y, const VecT<T, 1>& u, VecT<T, 1>* f) const {
    (*f)[0] = 0.5 * y[0] * y[0] + u[0];
  }
  template <class T>
  T EvalRunningCost(double t, const VecT<T, 1>& y, const VecT<T, 1>& u) const {
    return y[0] * y[0] + std::cos(t) * u[0];
  }
  /// The closed-form optimal state and control.
  static double OptimalState(double t) { return -std::sin(t) / (2.0 - std::cos(t)); }
  static double OptimalControl(double t) {
    const double d = std::cos(t) - 2.0;
    return 0.5 - 1.5 / (d * d);
  }
};

/// The registry entry "neuenhofen-kerrigan-x1".
ProblemInfo NeuenhofenKerriganX1ProblemInfo();

}  // namespace ocpb
