// A linear-quadratic regulator with a known Riccati solution (OCPBench problem "lqr").
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    J = 1/2 int_0^5 (|x|^2 + u^2) dt             (with the 1/2)
/// subject to  x' = A x + B u,  A = [0 1; -1 0],  B = [0; 1],  x(0) = (0, 1),
///             x(5) free, u unbounded, no path constraints.
///
/// Reference: J* = 1/2 x0^T P(0) x0 = 0.6739990459, with P the solution of the Riccati equation
///   -P' = A^T P + P A - P B B^T P + I,  P(5) = 0
/// (reference-problem notes, section 2.5: Riccati ODE at rtol 1e-13; the problem is
/// CTProblems.jl lqr_ricatti). The optimal feedback is u* = -B^T P(t) x and the costate
/// (H = p^T f + L) is p(t) = P(t) x(t).
///
/// Hamiltonian minimizer: H = p^T (A x + B u) + (|x|^2 + u^2)/2 gives u* = -B^T p = -p2. Fits the
/// Hamiltonian method as stated.
class Lqr final : public AutoDiffOcp<Lqr, 2, 1> {
 public:
  static constexpr double kReferenceCost = 0.6739990459;
  /// No parameters.
  static std::vector<ParameterSpec> ParameterSpecs() { return {}; }
  Lqr();

  std::string name() const override { return "lqr"; }
  static Eigen::Matrix2d A();
  static Eigen::Vector2d B();

  template <class T>
  void EvalDynamics(double, const VecT<T, 2>& x, const VecT<T, 1>& u, VecT<T, 2>* f) const {
    (*f)[0] = x[1];
    (*f)[1] = -x[0] + u[0];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 2>& x, const VecT<T, 1>& u) const {
    return 0.5 * (x[0] * x[0] + x[1] * x[1] + u[0] * u[0]);
  }

  bool HasHamiltonianMinimizer() const override { return true; }
  void MinimizeHamiltonian(double t, ConstVecRef x, ConstVecRef p, VecRef u) const override;

  /// The optimum in closed form. The maximum principle with u* = -B^T p makes (x, p) solve the
  /// linear Hamiltonian system z' = M z, M = [A, -B B^T; -I, -A^T] (p' = -H_x = -x - A^T p),
  /// with x(0) = x0 and p(5) = 0; so z(t) = exp(t M) z(0), and p(0) follows from
  /// [exp(5 M)]_{21} x0 + [exp(5 M)]_{22} p(0) = 0. Matrix exponentials by Eigen's
  /// MatrixFunctions (Pade with scaling and squaring); agrees with the Riccati ODE's
  /// p = P(t) x(t) and gives 1/2 x0^T p(0) = J* (tests/problems/reference_costate_test.cc).
  static Eigen::Matrix4d HamiltonianMatrix();
  /// (x*(t), p*(t)) for t in [0, 5].
  static Eigen::Vector4d OptimalStateAndCostate(double t);
  static Eigen::Vector2d OptimalState(double t) { return OptimalStateAndCostate(t).head<2>(); }
  static Eigen::Vector2d OptimalCostate(double t) { return OptimalStateAndCostate(t).tail<2>(); }
};

/// The registry entry "lqr".
ProblemInfo LqrProblemInfo();

}  // namespace ocpb
