// The Van der Pol oscillator steered to rest (OCPBench problem "vanderpol").
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    J = 1/2 int_0^2 (x1^2 + x2^2 + u^2) dt         (with the 1/2)
/// subject to  x1' = x2,
///             x2' = eps om (1 - x1^2) x2 - om^2 x1 + u,  om = eps = 1,
///             x(0) = (1, 0),  x(2) free, u unbounded, no path constraints.
///
/// Reference: J* = 1.0478069082 (reference-problem notes, section 2.9: shooting on the optimality
/// conditions, p(0) = (1.717177, 0.011261)); the problem is Bocop's / OptimalControlProblems.jl
/// `vanderpol`, for which Bocop's examples list gives 1.05 (midpoint rule, 100 steps).
///
/// Hamiltonian minimizer: H = p^T f + L is u^2/2 + p2 u + (terms without u), so u* = -p2. Fits
/// the Hamiltonian method as stated.
class VanDerPol final : public AutoDiffOcp<VanDerPol, 2, 1> {
 public:
  static constexpr double kReferenceCost = 1.0478069082;
  static std::vector<ParameterSpec> ParameterSpecs() { return {}; }
  VanDerPol();

  std::string name() const override { return "vanderpol"; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 2>& x, const VecT<T, 1>& u, VecT<T, 2>* f) const {
    (*f)[0] = x[1];
    (*f)[1] = kEps * kOmega * (1.0 - x[0] * x[0]) * x[1] - kOmega * kOmega * x[0] + u[0];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 2>& x, const VecT<T, 1>& u) const {
    return 0.5 * (x[0] * x[0] + x[1] * x[1] + u[0] * u[0]);
  }

  bool HasHamiltonianMinimizer() const override { return true; }
  void MinimizeHamiltonian(double t, ConstVecRef x, ConstVecRef p, VecRef u) const override;

 private:
  static constexpr double kEps = 1.0;
  static constexpr double kOmega = 1.0;
};

/// The registry entry "vanderpol".
ProblemInfo VanDerPolProblemInfo();

}  // namespace ocpb
