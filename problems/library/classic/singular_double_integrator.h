// Locatelli's singular-arc double integrator with a free final time (OCPBench problem
// "singular-double-integrator").
#pragma once

#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    J = int_0^T (1 + x2^2) / 2 dt      over u and the final time T (free),
/// subject to  x1' = x2,  x2' = u,  |u| <= 1,  x(0) = (2, 0),  psi = x(T) - (5, 0) = 0.
///
/// A. Locatelli, "Optimal Control of a Double Integrator", Springer 2017, problem 11.2-1a (PSOPT
/// example `singular_di`). H = (1 + x2^2)/2 + p1 x2 + p2 u is linear in u; the optimum is
/// bang-singular-bang: u = +1 on [0, 1], the singular arc u = 0 with x2 = 1 on [1, 3], u = -1 on
/// [3, 4], so T* = 4 and J* = 2/3 + 2 + 2/3 = 10/3 (the free-time condition H = 0 holds on the
/// singular arc: (1 + 1)/2 + p1 = 0, p1 = -1).
///
/// Hamiltonian method: not applicable (free final time).
class SingularDoubleIntegrator final : public AutoDiffOcp<SingularDoubleIntegrator, 2, 1, 2, 0> {
 public:
  static constexpr double kReferenceCost = 10.0 / 3.0;
  static constexpr double kOptimalTime = 4.0;
  /// Parameters: C (1e3), tf (nominal final time, 5), tf_min (2), tf_max (8).
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit SingularDoubleIntegrator(const Parameters& params);

  std::string name() const override { return "singular-double-integrator"; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 2>& x, const VecT<T, 1>& u, VecT<T, 2>* f) const {
    (*f)[0] = x[1];
    (*f)[1] = u[0];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 2>& x, const VecT<T, 1>&) const {
    return 0.5 * (1.0 + x[1] * x[1]);
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 2>& x, VecT<T, 2>* psi) const {
    (*psi)[0] = x[0] - 5.0;
    (*psi)[1] = x[1];
  }
  /// u = 0.5: at u = 0 nothing moves.
  Vec NominalControl() const override { return Vec::Constant(1, 0.5); }
};

/// The registry entry "singular-double-integrator".
ProblemInfo SingularDoubleIntegratorProblemInfo();

}  // namespace ocpb
