// The Bryson-Denham problem: a double integrator with a state bound (OCPBench problem
// "bryson-denham").
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    J = 1/2 int_0^1 u^2 dt                       (with the 1/2)
/// subject to  x1' = x2,  x2' = u,  x(0) = (0, 1),
///             psi = x(1) - (0, -1) = 0                      (terminal; penalty C |psi|^2 in
///                                                            penalty form),
///             c = x1 - l <= 0                               (path constraint, l = 1/9),
///             u unbounded.
///
/// Reference (l <= 1/6): J* = 4 / (9 l), so J* = 4 for l = 1/9 (A. E. Bryson, W. F. Denham,
/// S. E. Dreyfus, AIAA J. 1(11), 1963; Bryson & Ho, "Applied Optimal Control", 1975, Sec. 3.11;
/// CTProblems.jl double_integrator_energy_state_constraint). Analytic solution, with a boundary
/// arc on [3l, 1 - 3l]:
///   [0, 3l]:      x1 = l (1 - (1 - t/(3l))^3),  x2 = (1 - t/(3l))^2,  u = -2/(3l) (1 - t/(3l)),
///   [3l, 1-3l]:   x1 = l, x2 = 0, u = 0,
///   [1-3l, 1]:    the mirror image x1(t) = x1(1-t), x2(t) = -x2(1-t), u(t) = u(1-t).
/// Costates (H = p^T f + L, direct adjoining of c): p2 = -u everywhere, p1 = 2/(9 l^2) on the
/// first arc, 0 on the boundary arc, -2/(9 l^2) on the last (p1 jumps at the junctions).
///
/// Hamiltonian minimizer: H = p1 x2 + p2 u + u^2/2 gives u* = -p2 (U = R). The path constraint
/// does not fit the Hamiltonian method; HamiltonianReformulation() returns the exterior penalty
/// form (PathPenaltyOcp) with L = u^2/2 + rho max(0, x1 - l)^2, rho = options.path_penalty or the
/// parameter "rho" (default 1e5). c does not depend on u, so u* = -p2 is still exact.
/// What the penalties cost (optimum judged on this problem; Ipopt, Hermite-Simpson, N = 400,
/// hard terminal form): rho = 1e3: J = 3.236, 1e4: 3.864, 1e5: 3.973, 1e6: 3.995 (the gap shrinks
/// like rho^-0.7). In penalty terminal form the weight C adds its own gap (C = 1e3: about -3%,
/// C = 1e4: about -0.8% with rho = 1e5, Euler N = 100); hence the defaults C = 1e4, rho = 1e5.
class BrysonDenham final : public AutoDiffOcp<BrysonDenham, 2, 1, 2, 1> {
 public:
  static constexpr double kDefaultBound = 1.0 / 9.0;
  /// Parameters: C (terminal penalty weight, > 0, default 1e4) and rho (the Hamiltonian
  /// reformulation's path penalty weight, > 0, default 1e5).
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit BrysonDenham(const Parameters& params, double l = kDefaultBound);

  std::string name() const override { return "bryson-denham"; }
  double bound() const { return l_; }

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
    (*psi)[0] = x[0];
    (*psi)[1] = x[1] + 1.0;
  }
  template <class T>
  void EvalPathConstraints(double, const VecT<T, 2>& x, const VecT<T, 1>&, VecT<T, 1>* c) const {
    (*c)[0] = x[0] - l_;
  }

  bool HasHamiltonianMinimizer() const override { return true; }
  void MinimizeHamiltonian(double t, ConstVecRef x, ConstVecRef p, VecRef u) const override;
  std::unique_ptr<Ocp> HamiltonianReformulation(
      const HamiltonianReformulationOptions& options) const override;

  /// The analytic optimum above (valid for 0 < l <= 1/6).
  static double OptimalCost(double l = kDefaultBound) { return 4.0 / (9.0 * l); }
  static Eigen::Vector2d OptimalState(double t, double l = kDefaultBound);
  static double OptimalControl(double t, double l = kDefaultBound);
  static Eigen::Vector2d OptimalCostate(double t, double l = kDefaultBound);

 private:
  double l_;
  double rho_;
};

/// The registry entry "bryson-denham".
ProblemInfo BrysonDenhamProblemInfo();

}  // namespace ocpb
