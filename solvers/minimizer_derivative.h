// The (generalized) Jacobian of the pointwise Hamiltonian minimizer u*(t, x, p).
#pragma once

#include <vector>

#include "core/ocp.h"

namespace ocpb {

/// Computes du*/dx and du*/dp (nu x nx each) of
///
///   u*(t, x, p) = argmin_{u in U} H(t, x, u, p),   H = p^T f(t, x, u) + L(t, x, u),
///
/// the closed form Ocp::MinimizeHamiltonian, from the problem's own derivatives, by the implicit
/// function theorem applied to the first-order conditions of the minimization over U.
///
/// Interior u* (H_u(t, x, u*, p) = 0, H_uu positive definite):
///   du*/dx = -H_uu^{-1} H_ux,   du*/dp = -H_uu^{-1} f_u^T,
/// with H_uu, H_ux the blocks of Ocp::PointHessian (sigma = 1, lambda = p) and f_u from
/// Ocp::DynamicsJacobian.
///
/// u* on the boundary of U (U a product of boxes and balls, ControlSet): the active constraints
/// a_j(u) = 0 are kept active and the KKT system of the minimization is differentiated,
///
///   [ H_uu + sum_b mu_b I_b   A^T ] [ du ]     [ H_ux dx + f_u^T dp ]
///   [ A                       0   ] [ dl ] = - [ 0                  ],
///
/// where A has one row e_i^T per box component at a bound (so du_i = 0: the derivative of a
/// clipped component is 0) and one row n_b^T = (u_b - c_b)^T / r_b per ball block on its sphere,
/// whose multiplier mu_b = max(0, -n_b^T H_u,b / r_b) adds the sphere's curvature. When H is
/// isotropic in u_b (H_uu,bb = c I, the common case L = (c/2)|u|^2) this is exactly the Jacobian
/// of the projection onto the ball, (r_b / |v_b - c_b|) (I - n_b n_b^T), applied to the derivative
/// of the unconstrained minimizer v_b.
///
/// Semismoothness: u* is only piecewise smooth. At a switching point (a component exactly at a
/// bound with H_u,i = 0, a ball with mu_b = 0) the constraint is treated as active; the result is
/// then one element of the generalized (B-)Jacobian, the limit from the active side, which is what
/// a semismooth Newton method needs (Qi and Sun, "A nonsmooth version of Newton's method", Math.
/// Programming 58, 1993; Ulbrich, "Semismooth Newton Methods for Variational Inequalities and
/// Constrained Optimization Problems in Function Spaces", SIAM 2011). A component counts as being
/// at a bound when it lies within `kActiveTolerance` (relative) of it; MinimizeHamiltonian returns
/// clipped values exactly, so the tolerance only absorbs roundoff.
///
/// Requires H strictly convex in u on the free directions (the reduced KKT matrix nonsingular);
/// otherwise Compute() returns false (u* is then not a differentiable function of (x, p), for
/// example bang-bang controls of an H linear in u).
class MinimizerDerivative {
 public:
  /// Relative distance to a bound (or to a ball's sphere) under which a constraint is active.
  static constexpr double kActiveTolerance = 1e-12;

  explicit MinimizerDerivative(const Ocp& ocp);

  /// Given u = u*(t, x, p), H_u = L_u + f_u^T p at u, f_u (nx x nu) and the PointHessian `hess`
  /// ((nx+nu) x (nx+nu), sigma = 1, lambda = p) at (t, x, u), fills du_dx and du_dp (nu x nx).
  /// Returns false when the reduced KKT matrix is singular.
  bool Compute(
      ConstVecRef u, ConstVecRef Hu, ConstMatRef fu, ConstMatRef hess, MatRef du_dx, MatRef du_dp);

  /// Everything from scratch at (t, x, p): calls MinimizeHamiltonian, DynamicsJacobian,
  /// RunningCostGradient and PointHessian, then Compute(). Fills u (nu) as well. For tests and
  /// callers that do not have the pieces already.
  bool ComputeAt(double t, ConstVecRef x, ConstVecRef p, VecRef u, MatRef du_dx, MatRef du_dp);

  /// The number of active constraint rows of the last Compute() (box components at a bound plus
  /// balls on their sphere).
  int num_active() const { return num_active_; }
  /// Per control component, whether it was fixed by an active box bound in the last Compute().
  const std::vector<bool>& box_active() const { return box_active_; }

 private:
  const Ocp& ocp_;
  int nx_, nu_;
  int num_active_ = 0;
  std::vector<bool> box_active_;
  // M (nu x nu) and the active constraint rows A (at most nu rows of nu), see Compute.
  std::vector<double> m_, a_;
  // The KKT matrix and its LU (at most 2 nu x 2 nu, column-major), Z (nu x nu), a solve's column.
  std::vector<double> kkt_, inverse_, work_;
  std::vector<int> pivot_;
  // Scratch for ComputeAt.
  Vec f_, Lx_, Lu_, Hu_;
  Mat fx_, fu_, hess_;
};

}  // namespace ocpb
