// The Lotka-Volterra fishing problem of Sager, relaxed (OCPBench problem
// "lotka-volterra-fishing").
#pragma once

#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    J = int_0^12 (x0 - 1)^2 + (x1 - 1)^2 dt
/// subject to  x0' = x0 - x0 x1 - c0 x0 w,
///             x1' = -x1 + x0 x1 - c1 x1 w,     c0 = 0.4, c1 = 0.2,
///             x(0) = (0.5, 0.7),  w in [0, 1]   (the relaxation of w in {0, 1}).
///
/// S. Sager, "Numerical methods for mixed-integer optimal control problems", PhD thesis,
/// Heidelberg 2005, and the mintOC library (mintoc.de, "Lotka Volterra fishing problem"): the
/// relaxed optimum is 1.34408 (PSOPT example `lotka` uses it as the reference). The relaxed
/// control is bang-bang-singular: w = 0, then w = 1, then a singular arc until about t = 4.8 and
/// w = 0 to the end. mintOC writes the cost as a third state x2(12) with x2' = L; here it is the
/// Lagrange term (the same optimum).
///
/// Hamiltonian method: H is linear in w (singular arc); its minimizer over [0, 1] is bang-bang
/// with an undetermined value where the switching function vanishes, so no exact minimizer is
/// provided (not applicable).
class LotkaVolterraFishing final : public AutoDiffOcp<LotkaVolterraFishing, 2, 1, 0, 0> {
 public:
  static constexpr double kPreyCatch = 0.4;      // c0
  static constexpr double kPredatorCatch = 0.2;  // c1
  static constexpr double kReferenceCost = 1.34408;
  static std::vector<ParameterSpec> ParameterSpecs() { return {}; }
  explicit LotkaVolterraFishing(const Parameters& params);

  std::string name() const override { return "lotka-volterra-fishing"; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 2>& x, const VecT<T, 1>& w, VecT<T, 2>* f) const {
    (*f)[0] = x[0] - x[0] * x[1] - kPreyCatch * x[0] * w[0];
    (*f)[1] = -x[1] + x[0] * x[1] - kPredatorCatch * x[1] * w[0];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 2>& x, const VecT<T, 1>&) const {
    return (x[0] - 1.0) * (x[0] - 1.0) + (x[1] - 1.0) * (x[1] - 1.0);
  }
};

/// The registry entry "lotka-volterra-fishing".
ProblemInfo LotkaVolterraFishingProblemInfo();

}  // namespace ocpb
