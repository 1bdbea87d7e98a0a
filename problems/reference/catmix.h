// The catalyst mixing problem of COPS (OCPBench problem "catmix").
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    J = -1 + x1(1) + x2(1)  [+ eps int_0^1 u^2 dt]  (Mayer; eps = 0 is COPS' problem)
/// subject to  x1' = u (10 x2 - x1),
///             x2' = u (x1 - 10 x2) - (1 - u) x2,
///             x(0) = (1, 0),  x(1) free,  0 <= u <= 1  (U = [0, 1]), no path constraints.
///
/// Maximizes the yield of a tubular reactor mixing two catalysts (Gunn & Thomas 1965; E. Dolan,
/// J. Moré, T. Munson, "Benchmarking optimization software with COPS 3.0", ANL/MCS-TM-273, 2004,
/// problem `catmix`, smoothing alpha = 0). The optimal control is bang-singular-bang: u = 1, then a
/// singular arc, then u = 0.
///
/// Reference: COPS 3.0 reports J = -0.0480556 at nh = 100 for ITS discretization: 3-point Gauss
/// (Gauss-Legendre) collocation on each of nh intervals, controls at the collocation points. That
/// is an optimum of the discrete NLP, not of the continuous problem; compare with it only at the
/// same scheme and nh (tests/problems/reference_catmix_test.cc builds that scheme). PSOPT reports
/// -0.0480532 with another scheme.
///
/// Hamiltonian: H = eps u^2 + u s - p2 x2 with the switching function
///   s = p1 (10 x2 - x1) + p2 (x1 - 9 x2).
/// Minimizer: eps > 0: u* = clip(-s / (2 eps), 0, 1); eps = 0: H is linear in u and
/// u* = 0 if s >= 0, 1 if s < 0 (bang-bang; any u in [0, 1] minimizes when s = 0).
/// With eps = 0 the singular arc makes the Hamiltonian method chatter, so
/// HamiltonianReformulation() returns this problem with eps = options.regularization or the
/// parameter "hamiltonian_eps" (default 1e-4); its controls are judged on the eps = 0 problem.
/// With eps > 0 already (parameter "eps") the problem fits as stated and the reformulation is
/// nullptr.
class Catmix final : public AutoDiffOcp<Catmix, 2, 1> {
 public:
  static constexpr double kCopsReferenceCost = -0.0480556;
  static constexpr int kCopsIntervals = 100;
  /// Parameters: eps (>= 0, default 0) and hamiltonian_eps (> 0, default 1e-4).
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit Catmix(const Parameters& params);
  Catmix(double eps, double hamiltonian_eps);

  std::string name() const override { return "catmix"; }
  double eps() const { return eps_; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 2>& x, const VecT<T, 1>& u, VecT<T, 2>* f) const {
    (*f)[0] = u[0] * (10.0 * x[1] - x[0]);
    (*f)[1] = u[0] * (x[0] - 10.0 * x[1]) - (1.0 - u[0]) * x[1];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 2>&, const VecT<T, 1>& u) const {
    return eps_ * u[0] * u[0];
  }
  template <class T>
  T EvalTerminalCost(const VecT<T, 2>& x) const {
    return -1.0 + x[0] + x[1];
  }

  bool HasHamiltonianMinimizer() const override { return true; }
  void MinimizeHamiltonian(double t, ConstVecRef x, ConstVecRef p, VecRef u) const override;
  std::unique_ptr<Ocp> HamiltonianReformulation(
      const HamiltonianReformulationOptions& options) const override;

  /// The switching function s above.
  static double SwitchingFunction(ConstVecRef x, ConstVecRef p);

 private:
  double eps_;
  double hamiltonian_eps_;
};

/// The registry entry "catmix".
ProblemInfo CatmixProblemInfo();

}  // namespace ocpb
