// Hager's problem: a scalar linear-quadratic problem with a closed-form solution (OCPBench
// problem "hager").
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    J = 1/2 int_0^1 (u^2 + 2 x^2) dt              (with the 1/2)
/// subject to  x' = x/2 + u,  x(0) = 1,  x(1) free, u unbounded.
///
/// Closed form (W. W. Hager, "Runge-Kutta methods in optimal control and the transformed adjoint
/// system", Numer. Math. 87, 2000; the citation is as the project notes give it):
///   x*(t) = (2 e^{3t} + e^3) / (e^{3t/2} (2 + e^3)),
///   u*(t) = 2 (e^{3t} - e^3) / (e^{3t/2} (2 + e^3)),
///   p*(t) = -u*(t)                                          (H = p^T f + L),
///   J*    = 0.8641644977691                                 (closed-form quadrature and
///                                                            Riccati agree to 1e-14).
/// Smooth, with known x*, u*, p*: the problem for order-of-accuracy tests.
///
/// Hamiltonian minimizer: H = p (x/2 + u) + u^2/2 + x^2 gives u* = -p. Fits as stated.
class Hager final : public AutoDiffOcp<Hager, 1, 1> {
 public:
  static constexpr double kReferenceCost = 0.8641644977691;
  static std::vector<ParameterSpec> ParameterSpecs() { return {}; }
  Hager();

  std::string name() const override { return "hager"; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 1>& x, const VecT<T, 1>& u, VecT<T, 1>* f) const {
    (*f)[0] = 0.5 * x[0] + u[0];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 1>& x, const VecT<T, 1>& u) const {
    return 0.5 * u[0] * u[0] + x[0] * x[0];
  }

  bool HasHamiltonianMinimizer() const override { return true; }
  void MinimizeHamiltonian(double t, ConstVecRef x, ConstVecRef p, VecRef u) const override;

  /// The closed-form solution above.
  static double OptimalState(double t);
  static double OptimalControl(double t);
  static double OptimalCostate(double t) { return -OptimalControl(t); }
};

/// The registry entry "hager".
ProblemInfo HagerProblemInfo();

}  // namespace ocpb
