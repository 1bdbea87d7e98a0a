// The free-time double integrator with its final time as a static parameter (OCPBench problem
// "double-integrator-time-parameter"): the reference for Ocp::SetStaticParameters.
#pragma once

#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// "double-integrator-free-time" (problems/reference/free_time_double_integrator.h: T* =
/// 18^(1/4) = 2.0597671, J* = 4 T*/3 = 2.7463561) on the fixed horizon s in [0, 1], with the
/// final time T a static parameter, the third state:
///
/// minimize    J = int_0^1 T (1 + u^2/2) ds
/// subject to  x1' = T x2,  x2' = T u,  T' = 0,  x(0) = (-1, 0),  T in [0.1, 100] (start 1),
///             psi = (x1(1), x2(1)) = 0.
///
/// The same optimum as the free-time form (t = T s); T enters the dynamics and the running cost,
/// so its derivatives (Jacobian column, Hessian cross terms) are exercised. u* is linear in s:
/// Hermite-Simpson and LGR are exact. Penalty form: weight C on |x(1)|^2. indirect-newton solves
/// it with T's adjoint: p3' = -H_T, p3(1) = 0 and the transversality row p3(0) = 0
/// (solvers/pmp_residual.h), which is dJ/dT = 0.
class TimeParameterDoubleIntegrator final
    : public AutoDiffOcp<TimeParameterDoubleIntegrator, 3, 1, 2, 0> {
 public:
  /// Parameters: C (terminal penalty weight, default 1e3).
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit TimeParameterDoubleIntegrator(const Parameters& params);

  std::string name() const override { return "double-integrator-time-parameter"; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 3>& x, const VecT<T, 1>& u, VecT<T, 3>* f) const {
    (*f)[0] = x[2] * x[1];
    (*f)[1] = x[2] * u[0];
    (*f)[2] = T(0.0);  // a static parameter: zero dynamics
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 3>& x, const VecT<T, 1>& u) const {
    return x[2] * (1.0 + 0.5 * u[0] * u[0]);
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 3>& x, VecT<T, 2>* psi) const {
    (*psi)[0] = x[0];
    (*psi)[1] = x[1];
  }
  bool HasHamiltonianMinimizer() const override { return true; }
  /// u* = -p2 (H = T (p1 x2 + p2 u + 1 + u^2/2), T > 0); NaN where T <= 0, where H has no
  /// minimum in u (T's bounds keep it >= 0.1 at every admissible point).
  void MinimizeHamiltonian(double t, ConstVecRef x, ConstVecRef p, VecRef u) const override;
  /// u = 1: at u = 0 nothing moves.
  Vec NominalControl() const override { return Vec::Ones(1); }
};

/// The registry entry "double-integrator-time-parameter".
ProblemInfo TimeParameterDoubleIntegratorProblemInfo();

}  // namespace ocpb
