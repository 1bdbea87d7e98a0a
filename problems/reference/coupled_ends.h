// A problem whose two ends are coupled by a boundary constraint (OCPBench problem
// "coupled-ends"): the reference for Ocp::SetBoundaryConstraints.
#pragma once

#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    J = 1/2 x(0)^2 + 1/2 int_0^1 u^2 dt + 1/2 (x(1) - 3)^2
/// subject to  x' = u,  x(0) free in [-10, 10],
///             0 <= x(1) - x(0) <= d_max            (a boundary constraint, d_max = 0.8).
///
/// Analytic optimum (derived here): u is constant, u = d = x(1) - x(0), so
/// J(x(0), d) = 1/2 x(0)^2 + 1/2 d^2 + 1/2 (x(0) + d - 3)^2, whose free minimum d = x(0) = 1
/// breaks the constraint for d_max < 1; then d = d_max (the boundary constraint active) and
/// x(0) = (3 - d_max) / 2: for d_max = 0.8, x(0) = 1.1, x(1) = 1.9, u = 0.8, J* = 1.53.
/// Costate (H = p u + u^2/2): p = -u = -0.8, constant; with p(1) = phi_x(x(1)) + mu b_x(1) the
/// constraint's multiplier is mu = 0.3 (and p(0) = -phi0_x(x(0)) - mu b_x(0) = -1.1 + 0.3).
///
/// For the collocation NLPs only (the other methods do not take boundary constraints or a free
/// initial state: not_applicable).
class CoupledEnds final : public AutoDiffOcp<CoupledEnds, 1, 1> {
 public:
  /// Parameter: d_max (the upper bound of x(1) - x(0), in (0, 1) where the constraint is
  /// active; default 0.8).
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit CoupledEnds(const Parameters& params);

  std::string name() const override { return "coupled-ends"; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 1>&, const VecT<T, 1>& u, VecT<T, 1>* f) const {
    (*f)[0] = u[0];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 1>&, const VecT<T, 1>& u) const {
    return 0.5 * u[0] * u[0];
  }
  template <class T>
  T EvalInitialCost(const VecT<T, 1>& x0) const {
    return 0.5 * x0[0] * x0[0];
  }
  template <class T>
  T EvalTerminalCost(const VecT<T, 1>& x) const {
    return 0.5 * (x[0] - 3.0) * (x[0] - 3.0);
  }
  template <class T>
  void EvalBoundaryConstraints(const VecT<T, 1>& x0,
                               const VecT<T, 1>& xf,
                               VecT<T, Eigen::Dynamic>* b) const {
    (*b)[0] = xf[0] - x0[0];
  }

  /// The analytic optimum above.
  double OptimalCost() const;
  double OptimalInitialState() const { return 0.5 * (3.0 - d_max_); }
  double OptimalControl() const { return d_max_; }

 private:
  double d_max_;
};

/// The registry entry "coupled-ends".
ProblemInfo CoupledEndsProblemInfo();

}  // namespace ocpb
