// The F-8 aircraft minimum-time problem of Kaya and Noakes, relaxed by outer convexification
// as in mintOC (OCPBench problem "f8-aircraft").
#pragma once

#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    J = T                         (T free; L = 1)
/// subject to  x' = (1 - w) f(x, -xi) + w f(x, xi),  w in [0, 1],  xi = 0.05236,
///             x(0) = (0.4655, 0, 0),  psi = x(T) = 0,
/// with the Garrard model of the F-8 (angle of attack x0, pitch angle x1, pitch rate x2, tail
/// deflection v):
///   f0 = -0.877 x0 + x2 - 0.088 x0 x2 + 0.47 x0^2 - 0.019 x1^2 - x0^2 x2 + 3.846 x0^3
///        - 0.215 v + 0.28 x0^2 v + 0.47 x0 v^2 + 0.63 v^3,
///   f1 = x2,
///   f2 = -4.208 x0 - 0.396 x2 - 0.47 x0^2 - 3.564 x0^3
///        - 20.967 v + 6.265 x0^2 v + 46 x0 v^2 + 61.4 v^3.
/// The deflection takes only the values +-xi; w in [0, 1] weights the two modes (outer
/// convexification), the relaxation whose optimum is bang-bang: w in {0, 1} a.e.
/// Reference: mintOC (mintoc.de, "F-8 aircraft"; C. Y. Kaya and J. L. Noakes, J. Optim. Theory
/// Appl. 117, 2003; S. Sager, PhD thesis 2005): T* = 3.78086, three switches, starting with
/// w = 1 (PSOPT example `f8` reproduces it). The problem is nonconvex with several documented
/// local minima (T = 6.035, 5.742, 5.729, 4.400): a method may stop at one of them.
///
/// Hamiltonian method: not applicable (free final time).
class F8Aircraft final : public AutoDiffOcp<F8Aircraft, 3, 1, 3, 0> {
 public:
  static constexpr double kDeflection = 0.05236;  // xi
  static constexpr double kReferenceTime = 3.78086;
  /// Parameters: C (1e3), tf (nominal final time, 4), tf_min (1), tf_max (8).
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit F8Aircraft(const Parameters& params);

  std::string name() const override { return "f8-aircraft"; }

  template <class T, class V>
  static void Garrard(const VecT<T, 3>& x, const V& v, VecT<T, 3>* f) {
    const T& x0 = x[0];
    const T& x1 = x[1];
    const T& x2 = x[2];
    (*f)[0] = -0.877 * x0 + x2 - 0.088 * x0 * x2 + 0.47 * x0 * x0 - 0.019 * x1 * x1 - x0 * x0 * x2 +
              3.846 * x0 * x0 * x0 - 0.215 * v + 0.28 * x0 * x0 * v + 0.47 * x0 * v * v +
              0.63 * v * v * v;
    (*f)[1] = x2;
    (*f)[2] = -4.208 * x0 - 0.396 * x2 - 0.47 * x0 * x0 - 3.564 * x0 * x0 * x0 - 20.967 * v +
              6.265 * x0 * x0 * v + 46.0 * x0 * v * v + 61.4 * v * v * v;
  }
  template <class T>
  void EvalDynamics(double, const VecT<T, 3>& x, const VecT<T, 1>& w, VecT<T, 3>* f) const {
    VecT<T, 3> down, up;
    Garrard(x, -kDeflection, &down);
    Garrard(x, kDeflection, &up);
    for (int i = 0; i < 3; ++i) (*f)[i] = down[i] + w[0] * (up[i] - down[i]);
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 3>&, const VecT<T, 1>&) const {
    return T(1.0);
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 3>& x, VecT<T, 3>* psi) const {
    for (int i = 0; i < 3; ++i) (*psi)[i] = x[i];
  }
};

/// The registry entry "f8-aircraft".
ProblemInfo F8AircraftProblemInfo();

}  // namespace ocpb
