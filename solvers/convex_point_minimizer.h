// A generic pointwise minimizer of a convex Hamiltonian (plus an optional proximal term) over U,
// for problems or wrappers that have no closed form.
#pragma once

#include "core/ocp.h"

namespace ocpb {

/// Options of ConvexPointMinimizer.
struct ConvexPointMinimizerOptions {
  /// Scaled projected Newton steps at most (>= 1).
  int max_iterations = 100;
  /// Stop when a step changes w by at most tolerance (1 + |w|_inf) in the max norm (> 0).
  double tolerance = 1e-13;
  /// Armijo constant of the backtracking along the projection arc, in (0, 1/2).
  double sufficient_decrease = 1e-4;

  bool IsValid(std::string* error) const;
};

/// w = argmin_{w in U} phi(w),  phi(w) = H(t, x, w, p) + |w - center|^2 / (2 eps),
/// H = p^T f + L of `ocp` (eps = +infinity: no proximal term), for H convex in w (the paper's
/// Assumption 1: f affine and L convex in u).
///
/// Method: scaled projected Newton with backtracking along the projection arc (Bertsekas,
/// "Projected Newton methods for optimization problems with simple constraints", SIAM J.
/// Control Optim. 20, 1982): from w_0 = P_U(center) (eps finite) or P_U(w_start),
///   w(tau) = P_U(w - tau S^{-1} grad phi(w)),  tau = 1, 1/2, ... until
///   phi(w(tau)) <= phi(w) + sufficient_decrease grad phi(w)^T (w(tau) - w),
/// with S diagonal: on box components the diagonal of H_uu + I/eps (Ocp::PointHessian), on a
/// ball block the largest diagonal entry of the block (a projection onto a ball is only the
/// minimizer of an isotropic quadratic). When H is quadratic in u with a diagonal H_uu (box) or
/// an isotropic one (ball), the first step is the exact minimizer (the paper's problems and the
/// reference problems with quadratic-in-u Hamiltonians); otherwise the iteration converges
/// linearly or better. Where S has a non-positive entry it is replaced by 1 / eps, or 1 without
/// a proximal term.
///
/// Costs per step: one Ocp::DynamicsJacobian, RunningCostGradient and PointHessian, plus the
/// backtracking's RunningCost evaluations. Not thread-safe (keeps scratch); one per thread.
class ConvexPointMinimizer {
 public:
  using Options = ConvexPointMinimizerOptions;

  /// Throws std::invalid_argument when !options.IsValid().
  explicit ConvexPointMinimizer(const Ocp& ocp, const Options& options = Options());

  /// Writes the minimizer to w and returns the number of steps taken, or -1 when
  /// max_iterations were taken without meeting the tolerance (w is then the last iterate, the
  /// best phi found). `w_start` is the start when eps is infinite (ignored otherwise).
  int Minimize(double t,
               ConstVecRef x,
               ConstVecRef p,
               ConstVecRef center,
               double eps,
               ConstVecRef w_start,
               VecRef w);

  /// phi(w) at (t, x, p, center, eps).
  double Objective(
      double t, ConstVecRef x, ConstVecRef p, ConstVecRef center, double eps, ConstVecRef w) const;

 private:
  const Ocp& ocp_;
  Options options_;
  Vec f_, Lx_, Lu_, grad_, scale_, trial_, mu_;
  Mat fx_, fu_, hess_;
};

}  // namespace ocpb
