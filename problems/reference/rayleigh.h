// The Rayleigh problem with a mixed control-state constraint (OCPBench problem "rayleigh").
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    J = int_0^4.5 (x1^2 + u^2) dt                  (WITHOUT a 1/2: Betts' convention)
/// subject to  x1' = x2,
///             x2' = -x1 + x2 (1.4 - 0.14 x2^2) + 4 u,
///             x(0) = (-5, -5),  x(4.5) free, u unbounded,
///             c = u + x1/6 <= 0                               (mixed path constraint).
///
/// Reference: J* = 44.8044433 (J. T. Betts, "Practical Methods for Optimal Control and Estimation
/// Using Nonlinear Programming", 2nd ed., SIAM 2010, example 10.113, after Maurer & Augustin; the
/// project notes' PMP boundary-value solve gives 44.80444491).
///
/// Hamiltonian minimizer of the problem as stated (U = R; c is not part of U):
/// H = x1^2 + u^2 + p1 x2 + p2 (... + 4u) gives u* = -2 p2.
///
/// The mixed constraint does not fit the Hamiltonian method; HamiltonianReformulation() returns
/// the exterior penalty form (PathPenaltyOcp)
///   L_rho = x1^2 + u^2 + rho max(0, u + x1/6)^2,  rho = options.path_penalty or parameter "rho"
///   (default 1e3),
/// whose H is convex and piecewise quadratic in u, with the exact minimizer
///   u0 = -2 p2;  u* = u0 if u0 + x1/6 <= 0, else u* = (-2 p2 - rho x1/6) / (1 + rho)
/// (on the second branch 2u + 4 p2 + 2 rho (u + x1/6) = 0, and u* + x1/6 = (u0 + x1/6)/(1 + rho)
/// > 0, so the branches are consistent). As rho -> infinity, u* -> min(-2 p2, -x1/6), the
/// pointwise minimizer of the constrained problem. What the penalty costs (optimum judged on this
/// problem; Ipopt, Hermite-Simpson, N = 400): rho = 1e2: J = 43.55 (-2.8%), 1e3: 44.67 (-0.3%),
/// 1e4: 44.79 (-0.03%). Larger rho makes the problem stiff for the Hamiltonian descent (the
/// penalty couples u to x1 with gain rho/6), hence the default 1e3.
class Rayleigh final : public AutoDiffOcp<Rayleigh, 2, 1, 0, 1> {
 public:
  static constexpr double kReferenceCost = 44.8044433;
  /// Parameter rho: the Hamiltonian reformulation's penalty weight (> 0, default 1e3).
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit Rayleigh(const Parameters& params);

  std::string name() const override { return "rayleigh"; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 2>& x, const VecT<T, 1>& u, VecT<T, 2>* f) const {
    (*f)[0] = x[1];
    (*f)[1] = -x[0] + x[1] * (1.4 - 0.14 * x[1] * x[1]) + 4.0 * u[0];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 2>& x, const VecT<T, 1>& u) const {
    return x[0] * x[0] + u[0] * u[0];
  }
  template <class T>
  void EvalPathConstraints(double, const VecT<T, 2>& x, const VecT<T, 1>& u, VecT<T, 1>* c) const {
    (*c)[0] = u[0] + x[0] / 6.0;
  }

  bool HasHamiltonianMinimizer() const override { return true; }
  void MinimizeHamiltonian(double t, ConstVecRef x, ConstVecRef p, VecRef u) const override;
  std::unique_ptr<Ocp> HamiltonianReformulation(
      const HamiltonianReformulationOptions& options) const override;

  /// The exact minimizer over u of the penalized H above.
  static double PenalizedMinimizer(double rho, double x1, double p2);

 private:
  double rho_;
};

/// The registry entry "rayleigh".
ProblemInfo RayleighProblemInfo();

}  // namespace ocpb
