// Betts' Van der Pol oscillator with a state bound (OCPBench problem
// "vanderpol-state-constrained").
#pragma once

#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    J = int_0^5 (y1^2 + y2^2 + u^2) dt          (no 1/2: Betts' convention)
/// subject to  y1' = y2,  y2' = (1 - y1^2) y2 - y1 + u,
///             y(0) = (1, 0),  y(5) free,  u unbounded,
///             y2 >= -0.4                                   (state bound, active on an arc).
///
/// J. T. Betts, "Practical Methods for Optimal Control and Estimation Using Nonlinear
/// Programming", 2nd ed., SIAM 2010, example 10.144 (section 4.14, example 4.11; 10.145 is the
/// same problem with (1 - y1^2) y2 as an algebraic variable): J* = 2.95369916. It differs from
/// the reference problem "vanderpol" (horizon 2, a 1/2, no bound).
///
/// Hamiltonian method: not applicable (state bound).
class VanDerPolStateConstrained final : public AutoDiffOcp<VanDerPolStateConstrained, 2, 1, 0, 0> {
 public:
  static constexpr double kReferenceCost = 2.95369916;
  static constexpr double kLowerVelocity = -0.4;
  static std::vector<ParameterSpec> ParameterSpecs() { return {}; }
  explicit VanDerPolStateConstrained(const Parameters& params);

  std::string name() const override { return "vanderpol-state-constrained"; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 2>& y, const VecT<T, 1>& u, VecT<T, 2>* f) const {
    (*f)[0] = y[1];
    (*f)[1] = (1.0 - y[0] * y[0]) * y[1] - y[0] + u[0];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 2>& y, const VecT<T, 1>& u) const {
    return y[0] * y[0] + y[1] * y[1] + u[0] * u[0];
  }
};

/// The registry entry "vanderpol-state-constrained".
ProblemInfo VanDerPolStateConstrainedProblemInfo();

}  // namespace ocpb
