// Minimum-energy double integrator from rest to the line x1 - 2 x2 = 1 at t = 1 (OCPBench
// problem "min-energy-target-line").
#pragma once

#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    J = int_0^1 u^2 / 2 dt
/// subject to  x1' = x2,  x2' = u,  x(0) = (0, 0),  psi = x1(1) - 2 x2(1) - 1 = 0.
///
/// A. Locatelli, "Optimal Control of a Double Integrator", Springer 2017, chapter 6 (PSOPT
/// example `mineng_target_set`): the final state lies on a line; the costate at tf is
/// orthogonal to it. Closed form u* = -(3/7)(1 + t), x(1) = (-2/7, -9/14), J* = 3/14.
///
/// Hamiltonian minimizer: H = u^2/2 + p1 x2 + p2 u gives u* = -p2.
class MinEnergyTargetLine final : public AutoDiffOcp<MinEnergyTargetLine, 2, 1, 1, 0> {
 public:
  static constexpr double kReferenceCost = 3.0 / 14.0;
  /// Parameters: C (terminal penalty weight, 1e3).
  static std::vector<ParameterSpec> ParameterSpecs() {
    return {{"C", {1000.0}, "terminal penalty weight (penalty form)", 0.0, 1e300, true}};
  }
  explicit MinEnergyTargetLine(const Parameters& params) {
    SetHorizon(0.0, 1.0);
    SetInitialState(Eigen::Vector2d(0.0, 0.0));
    SetTerminalWeights(Vec::Constant(1, params.Scalar("C")));
  }

  std::string name() const override { return "min-energy-target-line"; }

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
    (*psi)[0] = x[0] - 2.0 * x[1] - 1.0;
  }

  bool HasHamiltonianMinimizer() const override { return true; }
  void MinimizeHamiltonian(double, ConstVecRef, ConstVecRef p, VecRef u) const override {
    u[0] = -p[1];
  }
};

/// The registry entry "min-energy-target-line".
ProblemInfo MinEnergyTargetLineProblemInfo();

}  // namespace ocpb
