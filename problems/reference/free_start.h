// A problem whose initial state is partly free, with an initial cost and an active bound on
// x(t0) (OCPBench problem "free-start"): the reference for Ocp::SetInitialStateBounds and
// Ocp::InitialCost.
#pragma once

#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    J = w/2 (x1(0) - a)^2 + x2(T) + q/2 (x1(T) - b)^2     (no running cost)
/// subject to  x1' = u,  x2' = u^2 / 2,  t in [0, T], T = 1,
///             x1(0) in [lo, hi] free,  x2(0) = 0 fixed,  u unbounded.
///
/// x2 carries the control energy, so J is phi0(x(0)) + 1/2 int u^2 + phi(x(T)): a Mayer problem
/// with an initial cost. Analytic optimum (derived here; the transversality conditions of a free
/// initial state, p(0) = -dphi0/dx(0) where x1(0) is inside its bounds, as in Bryson & Ho,
/// "Applied Optimal Control", 1975, Sec. 2.7): u is constant, so for given ends the energy is
/// (x1(T) - x1(0))^2 / (2T); the best x1(T) for a given x1(0) leaves
///   J(x1(0)) = w/2 (x1(0) - a)^2 + k/2 (x1(0) - b)^2,   k = q / (1 + q T),
/// minimized at x1(0)* = clip((w a + k b) / (w + k), lo, hi), with x1(T)* = (x1(0)* + q T b) /
/// (1 + q T) and u* = (x1(T)* - x1(0)*) / T. Defaults w = 1, a = 0, q = 4, b = 2, lo = -1,
/// hi = 0.5: the unconstrained x1(0) = 8/9 is cut to the bound 0.5 (active), J* = 1.025.
/// Costates (H = p^T f, Mayer): p1 = q (x1(T)* - b), p2 = 1, constant.
///
/// H = p1 u + p2 u^2/2 has the closed-form minimizer u* = -p1 / p2 (p2 = 1 on every costate of
/// the problem), so indirect-newton solves it with the transversality rows of a free initial
/// state (solvers/pmp_residual.h), and so does the Hamiltonian family on forward Euler (x1(0) a
/// variable of its descent, solvers/descent_passes.h). Not for the paper's `hamiltonian` or single
/// shooting (they start every trajectory from a fixed x0: not_applicable).
class FreeStart final : public AutoDiffOcp<FreeStart, 2, 1> {
 public:
  /// Parameters: w, a (initial cost), q, b (terminal cost), lo, hi (bounds of x1(0); need
  /// lo <= 0 <= hi, x0 = (0, 0) being where methods start).
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit FreeStart(const Parameters& params);

  std::string name() const override { return "free-start"; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 2>&, const VecT<T, 1>& u, VecT<T, 2>* f) const {
    (*f)[0] = u[0];
    (*f)[1] = 0.5 * u[0] * u[0];
  }
  bool HasHamiltonianMinimizer() const override { return true; }
  /// u* = -p1 / p2, the minimizer of H where p2 > 0 (p2' = 0 and p2(T) = 1: every costate of
  /// the problem has p2 = 1); NaN where p2 <= 0, where H has no minimum.
  void MinimizeHamiltonian(double t, ConstVecRef x, ConstVecRef p, VecRef u) const override;

  template <class T>
  T EvalInitialCost(const VecT<T, 2>& x0) const {
    const T d = x0[0] - a_;
    return 0.5 * w_ * d * d;
  }
  template <class T>
  T EvalTerminalCost(const VecT<T, 2>& x) const {
    const T d = x[0] - b_;
    return x[1] + 0.5 * q_ * d * d;
  }

  /// The analytic optimum above: x1(0)*, x1(T)*, J*.
  struct Optimum {
    double x1_start = 0.0, x1_end = 0.0, J = 0.0;
  };
  Optimum AnalyticOptimum() const;
  /// The optimal costate (constant): (q (x1(T)* - b), 1).
  Vec OptimalCostate() const;

 private:
  double w_, a_, q_, b_, lo_, hi_;
};

/// The registry entry "free-start".
ProblemInfo FreeStartProblemInfo();

}  // namespace ocpb
