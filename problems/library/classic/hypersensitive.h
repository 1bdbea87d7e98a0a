// The hypersensitive problem of Rao and Mease, in Betts' form (OCPBench problem
// "hypersensitive").
#pragma once

#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    J = int_0^tf (y^2 + u^2) dt          (no 1/2: Betts' convention)
/// subject to  y' = -y^3 + u,  y(0) = 1,  psi = y(tf) - 1.5 = 0,  tf = 10000 (parameter).
///
/// J. T. Betts, "Practical Methods for Optimal Control and Estimation Using Nonlinear
/// Programming", 2nd ed., SIAM 2010, example 10.7 (after A. V. Rao and K. D. Mease), reports
/// J* = 6.7241. The optimum leaves y = 1 in a boundary layer of width O(1), rests at y = u = 0,
/// and climbs to 1.5 in a second layer at tf: for a long horizon the cost is the sum of two
/// infinite-horizon costs, which the Hamilton-Jacobi equation gives in closed form. With
/// V(y) = min int_0^inf (y^2 + u^2) from y to rest, 0 = y^2 - V'^2/4 - V' y^3, so
/// V'(y) = 2 (sqrt(y^6 + y^2) - y^3); reaching y from rest (time reversed) costs W with
/// W'(y) = 2 (sqrt(y^6 + y^2) + y^3). With F(w) = (w sqrt(w^2 + 1) + asinh(w)) / 4:
///   J_inf = V(1) + W(1.5) = 2 (F(1) - 1/4) + 2 (F(2.25) + 2.25^2 / 4) = 6.72411380988600,
/// which agrees with Betts' 6.7241; the finite-horizon optimum differs from it by O(exp(-tf))
/// (the linearization at rest decays at rate 1), far below double precision for tf >= 40.
/// Uniform grids resolve the layers only with a short horizon: `--set tf=40` keeps the same
/// reference.
///
/// Hamiltonian minimizer: H = y^2 + u^2 + p (-y^3 + u) gives u* = -p/2.
class Hypersensitive final : public AutoDiffOcp<Hypersensitive, 1, 1, 1, 0> {
 public:
  /// J_inf above.
  static double InfiniteHorizonCost();
  /// Parameters: tf (10000, >= 40 for the reference to hold), C (terminal penalty weight, 1e3).
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit Hypersensitive(const Parameters& params);

  std::string name() const override { return "hypersensitive"; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 1>& y, const VecT<T, 1>& u, VecT<T, 1>* f) const {
    (*f)[0] = -y[0] * y[0] * y[0] + u[0];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 1>& y, const VecT<T, 1>& u) const {
    return y[0] * y[0] + u[0] * u[0];
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 1>& y, VecT<T, 1>* psi) const {
    (*psi)[0] = y[0] - 1.5;
  }

  bool HasHamiltonianMinimizer() const override { return true; }
  void MinimizeHamiltonian(double, ConstVecRef, ConstVecRef p, VecRef u) const override {
    u[0] = -0.5 * p[0];
  }
};

/// The registry entry "hypersensitive".
ProblemInfo HypersensitiveProblemInfo();

}  // namespace ocpb
