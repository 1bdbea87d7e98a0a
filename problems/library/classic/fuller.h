// Fuller's problem on a finite horizon (OCPBench problem "fuller"): the optimal control switches
// infinitely often (chattering), the classic test of how a method meets it.
#pragma once

#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    J = int_0^1 x1^2 dt
/// subject to  x1' = x2,  x2' = u,  u in [-1, 1],
///             x(0) = (0.01, 0),  x(1) = (0.01, 0)  (terminal constraints),
/// posed in units of 0.01 for x (y = 100 x: y1' = y2, y2' = 100 u, y(0) = y(1) = (1, 0)), so that
/// OCPBench's J = int y1^2 dt = 1e4 times the source's: at J ~ 1.5e-5 Ipopt's default tol 1e-8
/// stopped Hermite-Simpson at N = 800 7% above the optimum, its controls nowhere at their bounds.
///
/// The relaxed form of mintOC's "Fuller's problem" (there x2' = 1 - 2 w with w in {0, 1}; u = 1 - 2
/// w with w relaxed to [0, 1] is the same problem). H = x1^2 + p1 x2 + p2 u is linear in u:
/// u* = -sign(p2), and the optimal control, bang-bang, switches infinitely often towards the
/// junctions with the singular arc x = 0 (Fuller 1963; Zelikin and Borisov 1994): no grid
/// resolves it, so every direct method's error here is the grid's.
///
/// Reference (the source's units; OCPBench's J is 1e4 times it): J = 1.52804e-5, computed by
/// OCPBench (Ipopt, tol 1e-12, hard form, in OCPBench's units): Hermite-Simpson at N = 800 and
/// 1600, 0.15280383 and 0.15280362; the trapezoid at N = 1600, 0.15280411; LGR at N = 1600
/// (Ipopt's acceptable level), 0.15280353: good to about 3e-6 relative (the chattering arcs
/// converge slowly and not monotonically). mintOC (Sager et al., mintoc.de, "Fuller's problem")
/// publishes 1.5296058259296967e-5 for the relaxed problem solved with Optimica and Ipopt on a
/// grid the page does not state: 1.0e-3 above, about what the trapezoid gives at N = 100
/// (0.15298303 here).
class Fuller final : public AutoDiffOcp<Fuller, 2, 1, 2, 0> {
 public:
  /// In OCPBench's units (1e4 times the source's).
  static constexpr double kReferenceCost = 1.52804e-1;
  static constexpr double kMintocCost = 1.5296058259296967e-1;
  /// Parameters: C (terminal penalty weight, 1e3).
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit Fuller(const Parameters& params);

  std::string name() const override { return "fuller"; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 2>& x, const VecT<T, 1>& u, VecT<T, 2>* f) const {
    (*f)[0] = x[1];
    (*f)[1] = 100.0 * u[0];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 2>& x, const VecT<T, 1>&) const {
    return x[0] * x[0];
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 2>& x, VecT<T, 2>* psi) const {
    (*psi)[0] = x[0] - 1.0;
    (*psi)[1] = x[1];
  }
};

/// The registry entry "fuller".
ProblemInfo FullerProblemInfo();

}  // namespace ocpb
