// Bryson-Denham with its state bound declared as a bound (OCPBench problem
// "bryson-denham-bounds"): the reference for Ocp::SetStateBounds.
#pragma once

#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// The problem of "bryson-denham" (problems/reference/bryson_denham.h: J* = 4/(9 l) = 4 at
/// l = 1/9, the same analytic solution) with x1 <= l stated as a state bound, x in
/// [(-inf, -inf), (l, +inf)] on (0, 1], instead of the path row c = x1 - l <= 0. The
/// collocation transcriptions make it a bound of every state variable after x(0) (Ipopt sees a
/// variable bound, not a constraint row); the judge checks it on its fine re-simulation. The
/// bound is active on the interior arc [3l, 1 - 3l].
///
/// Not for the Hamiltonian family, indirect-newton, riccati-ip or single shooting (they do not
/// take state bounds: not_applicable); "bryson-denham" is the same problem for them.
class BrysonDenhamBounds final : public AutoDiffOcp<BrysonDenhamBounds, 2, 1, 2, 0> {
 public:
  /// Parameters: C (terminal penalty weight, > 0, default 1e4).
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit BrysonDenhamBounds(const Parameters& params);

  std::string name() const override { return "bryson-denham-bounds"; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 2>& x, const VecT<T, 1>& u, VecT<T, 2>* f) const {
    (*f)[0] = x[1];
    (*f)[1] = u[0];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 2>&, const VecT<T, 1>& u) const {
    return 0.5 * u[0] * u[0];
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 2>& x, VecT<T, 2>* psi) const {
    (*psi)[0] = x[0];
    (*psi)[1] = x[1] + 1.0;
  }
};

/// The registry entry "bryson-denham-bounds".
ProblemInfo BrysonDenhamBoundsProblemInfo();

}  // namespace ocpb
