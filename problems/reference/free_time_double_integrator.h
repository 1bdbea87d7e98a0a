// The double integrator with a free final time and a time cost (OCPBench problem
// "double-integrator-free-time").
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    J = int_0^T (1 + u^2/2) dt        over u and the final time T (free),
/// subject to  x1' = x2, x2' = u,  x(0) = (-1, 0),  psi = x(T) = 0.
///
/// For a fixed T the rest-to-rest move over distance 1 costs 1/2 int u^2 = 6 / T^3 (u = 6/T^2
/// (1 - 2t/T)), so J(T) = T + 6 / T^3 and dJ/dT = 1 - 18 / T^4: T* = 18^(1/4) = 2.0597671, J* =
/// 4 T*/3 = 2.7463561. With H = p^T f + L: u* = -p2, p1 = -12 / T^3, p2(t) = 12 t / T^3 - 6 / T^2,
/// and H = 1 - p2^2/2 + p1 x2 is 0 along the optimum (the free-time condition H(T) = 0 holds with
/// p2(T)^2 = 2). The problem is autonomous, as Ocp's free final time requires.
///
/// The one free-final-time problem here with a smooth closed-form minimizer (quadratic Newton
/// convergence, no time scaling): the reference for PmpResidual's H(T) = 0 row. Penalty form:
/// weight C on |x(T)|^2. Parameters: C (1e3), tf (the nominal T where methods start, 1), and the
/// bounds tf_min (0.1) and tf_max (100) of T.
class FreeTimeDoubleIntegrator final : public AutoDiffOcp<FreeTimeDoubleIntegrator, 2, 1, 2, 0> {
 public:
  static double OptimalTime() { return std::pow(18.0, 0.25); }
  static double OptimalCost() { return 4.0 * OptimalTime() / 3.0; }
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit FreeTimeDoubleIntegrator(const Parameters& params);

  std::string name() const override { return "double-integrator-free-time"; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 2>& x, const VecT<T, 1>& u, VecT<T, 2>* f) const {
    (*f)[0] = x[1];
    (*f)[1] = u[0];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 2>&, const VecT<T, 1>& u) const {
    return 1.0 + 0.5 * u[0] * u[0];
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 2>& x, VecT<T, 2>* psi) const {
    (*psi)[0] = x[0];
    (*psi)[1] = x[1];
  }

  bool HasHamiltonianMinimizer() const override { return true; }
  /// u* = -p2 (H = 1 + p1 x2 + p2 u + u^2/2).
  void MinimizeHamiltonian(double t, ConstVecRef x, ConstVecRef p, VecRef u) const override;
  /// u = 1 (accelerate towards the target): at u = 0 nothing moves and the row H(T) = 0 of the
  /// indirect method has a zero derivative (f = 0, H_x = 0 at rest).
  Vec NominalControl() const override { return Vec::Ones(1); }
};

/// The registry entry "double-integrator-free-time".
ProblemInfo FreeTimeDoubleIntegratorProblemInfo();

}  // namespace ocpb
