// Betts' Alp rider (OCPBench problem "alp-rider").
#pragma once

#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    J = int_0^20 100 |y|^2 + 0.01 |u|^2 dt
/// subject to  y1' = -10 y1 + u1 + u2,
///             y2' = -2 y2 + u1 + 2 u2,
///             y3' = -3 y3 + 5 y4 + u1 - u2,
///             y4' = 5 y3 - 3 y4 + u1 + 3 u2,
///             y(0) = (2, 1, 2, 1),  psi = y(20) - (2, 3, 1, -2) = 0,
///             |y|^2 >= 3 p(t, 3, 12) + 3 p(t, 6, 10) + 3 p(t, 10, 6) + 8 p(t, 15, 4) + 0.01,
///             p(t, a, b) = exp(-b (t - a)^2)            (path constraint c <= 0, time-varying),
/// u unbounded. J. T. Betts, "Practical Methods for Optimal Control and Estimation Using
/// Nonlinear Programming", 2nd ed., SIAM 2010, example 10.1 (section 4.11.7), J* = 2030.85609;
/// PSOPT's example `alpine` poses the same problem (with inactive box bounds |y_i| <= 4,
/// |u_i| <= 500 that are left out here). The state is forced over four bumps of the constraint
/// while the cost pulls |y|^2 towards it: the constraint is active on four arcs, and the stiff
/// first state (rate 10) gives boundary layers at both ends.
///
/// Hamiltonian method: not applicable (the path constraint depends on the state alone).
class AlpRider final : public AutoDiffOcp<AlpRider, 4, 2, 4, 1> {
 public:
  static constexpr double kHorizon = 20.0;
  static constexpr double kReferenceCost = 2030.85609;
  /// Parameters: C (terminal penalty weight, 1e3).
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit AlpRider(const Parameters& params);

  std::string name() const override { return "alp-rider"; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 4>& y, const VecT<T, 2>& u, VecT<T, 4>* f) const {
    (*f)[0] = -10.0 * y[0] + u[0] + u[1];
    (*f)[1] = -2.0 * y[1] + u[0] + 2.0 * u[1];
    (*f)[2] = -3.0 * y[2] + 5.0 * y[3] + u[0] - u[1];
    (*f)[3] = 5.0 * y[2] - 3.0 * y[3] + u[0] + 3.0 * u[1];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 4>& y, const VecT<T, 2>& u) const {
    return 100.0 * (y[0] * y[0] + y[1] * y[1] + y[2] * y[2] + y[3] * y[3]) +
           0.01 * (u[0] * u[0] + u[1] * u[1]);
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 4>& y, VecT<T, 4>* psi) const {
    (*psi)[0] = y[0] - 2.0;
    (*psi)[1] = y[1] - 3.0;
    (*psi)[2] = y[2] - 1.0;
    (*psi)[3] = y[3] + 2.0;
  }
  template <class T>
  void EvalPathConstraints(double t, const VecT<T, 4>& y, const VecT<T, 2>&, VecT<T, 1>* c) const {
    (*c)[0] = Floor(t) - (y[0] * y[0] + y[1] * y[1] + y[2] * y[2] + y[3] * y[3]);
  }

  /// The lower bound of |y|^2 at time t.
  static double Floor(double t);
};

/// The registry entry "alp-rider".
ProblemInfo AlpRiderProblemInfo();

}  // namespace ocpb
