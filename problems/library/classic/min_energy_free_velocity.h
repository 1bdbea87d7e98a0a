// Minimum-energy double integrator to x1(1) = 1 with a free final velocity (OCPBench problem
// "min-energy-free-velocity").
#pragma once

#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    J = int_0^1 u^2 / 2 dt
/// subject to  x1' = x2,  x2' = u,  x(0) = (0, 0),  psi = x1(1) - 1 = 0,  x2(1) free.
///
/// A. Locatelli, "Optimal Control of a Double Integrator", Springer 2017, section 3.3 (PSOPT
/// example `mineng_free_vf`): with x2(1) free the transversality condition gives p2(1) = 0, so
/// u* = -p2 = 3 - 3t, x2(1) = 3/2 and J* = 3/2 (closed form).
///
/// Hamiltonian minimizer: H = u^2/2 + p1 x2 + p2 u gives u* = -p2.
class MinEnergyFreeVelocity final : public AutoDiffOcp<MinEnergyFreeVelocity, 2, 1, 1, 0> {
 public:
  static constexpr double kReferenceCost = 1.5;
  /// Parameters: C (terminal penalty weight, 1e3).
  static std::vector<ParameterSpec> ParameterSpecs() {
    return {{"C", {1000.0}, "terminal penalty weight (penalty form)", 0.0, 1e300, true}};
  }
  explicit MinEnergyFreeVelocity(const Parameters& params) {
    SetHorizon(0.0, 1.0);
    SetInitialState(Eigen::Vector2d(0.0, 0.0));
    SetTerminalWeights(Vec::Constant(1, params.Scalar("C")));
  }

  std::string name() const override { return "min-energy-free-velocity"; }

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
  void EvalTerminalConstraints(const VecT<T, 2>& x, VecT<T, 1>* psi) const {
    (*psi)[0] = x[0] - 1.0;
  }

  bool HasHamiltonianMinimizer() const override { return true; }
  void MinimizeHamiltonian(double, ConstVecRef, ConstVecRef p, VecRef u) const override {
    u[0] = -p[1];
  }
};

/// The registry entry "min-energy-free-velocity".
ProblemInfo MinEnergyFreeVelocityProblemInfo();

}  // namespace ocpb
