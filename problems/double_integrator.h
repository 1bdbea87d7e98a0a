// The minimum-energy double integrator (OCPBench problems "double-integrator" and
// "double-integrator-bounded").
#pragma once

#include <memory>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"

namespace ocpb {

/// minimize    J = 1/2 int_0^1 u^2 dt
/// subject to  x1' = x2, x2' = u,  x(0) = (-1, 0),  psi = x(1) - (0, 0) = 0,  |u| <= umax.
///
/// Unbounded (umax = inf): u*(t) = 6 - 12 t, x1*(t) = -1 + 3t^2 - 2t^3, p*(t) = (-12, 12t - 6)
/// (H = p^T f + L), J* = 6. Bounded, umax = 5: J* = 6.0450277563 with
/// u*(t) = clip(6.4549722 - 12.9099445 t, -5, 5) (reference-problems notes, section 2.1-2.2;
/// CTProblems.jl double_integrator_energy[_control_constraint]).
/// Hamiltonian minimizer: u* = clip(-p2, -umax, umax). In penalty form the terminal cost is
/// C (x1(1)^2 + x2(1)^2) with C = parameter "C".
class DoubleIntegrator final : public AutoDiffOcp<DoubleIntegrator, 2, 1, 2, 0> {
 public:
  /// Parameters: umax (> 0, default inf is given as 1e300), C (penalty weight), x0, xf.
  static std::vector<ParameterSpec> ParameterSpecs(double default_umax);
  DoubleIntegrator(const Parameters& params, std::string name);

  std::string name() const override { return name_; }

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
    (*psi)[0] = x[0] - xf_[0];
    (*psi)[1] = x[1] - xf_[1];
  }

  bool HasHamiltonianMinimizer() const override { return true; }
  void MinimizeHamiltonian(double t, ConstVecRef x, ConstVecRef p, VecRef u) const override;

 private:
  std::string name_;
  double umax_;
  Eigen::Vector2d xf_;
};

}  // namespace ocpb
