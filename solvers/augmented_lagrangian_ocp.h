// The augmented Lagrangian of a problem's terminal equalities and path inequalities: the
// problem the family's descent minimizes inside its outer multiplier loop.
#pragma once

#include <memory>

#include "core/time_grid.h"
#include "solvers/convex_point_minimizer.h"
#include "solvers/forwarding_ocp.h"

namespace ocpb {

/// For a problem P (terminal constraints psi(x(tf)) = 0, path constraints c(t, x, u) <= 0),
/// multipliers nu (npsi), mu (nc x N, one per constraint and grid interval) and penalties
/// rho, rho_c > 0, the problem with
///
///   Phi_A(x) = phi(x) + sum_i [nu_i psi_i(x) + (rho / 2) psi_i(x)^2],
///   L_A(t, x, u) = L(t, x, u) + sum_i (1 / (2 rho_c)) [max(0, mu_i,k + rho_c c_i)^2 - mu_i,k^2],
///
/// k the grid interval of t (Hestenes and Powell's augmented Lagrangian for the equalities, and
/// Rockafellar's for the inequalities: Bertsekas, "Constrained Optimization and Lagrange
/// Multiplier Methods", 1982, Sec. 2.1 and 3.1; Conn, Gould and Toint, "A globally convergent
/// augmented Lagrangian algorithm", SIAM J. Numer. Anal. 28, 1991). P's penalty weights w_i are
/// not used: they are sized for the penalty form (bryson-denham's 1e4), and rho w_i made the
/// outer loop's first subproblems as ill-conditioned as the penalty form itself.
///
/// It has num_path() == 0 and P's terminal constraints (so a DiscreteOcp in TerminalMode::kHard
/// minimizes Phi_A: TerminalObjective = TerminalCost there). Derivatives are exact, from P's
/// (the path term's d/dz is max(0, mu + rho_c c) c_z; its Hessian adds rho_c c_z c_z^T where
/// mu + rho_c c > 0, and P's c_zz through PointHessian's mu). The first-order multiplier updates
/// that make the method converge are
///   nu <- nu + rho psi(x_N),    mu_i,k <- max(0, mu_i,k + rho_c c_i(t_k, x_k, u_k)),
/// (TerminalUpdate, PathUpdate): at a stationary point of the AL with these, the costate
/// satisfies p_N = grad phi + psi_x^T nu_new, the multipliers of the hard-form NLP.
///
/// The Hamiltonian minimizer: P's when the path term is absent or the constraints do not depend
/// on u at the point (c_u = 0: state constraints leave H's u-part unchanged); otherwise the
/// ConvexPointMinimizer on H_A (exact for the convex H_A of a convex problem). Not thread-safe
/// (the minimizer keeps scratch). `inner` and `grid` must outlive this object.
class AugmentedLagrangianOcp final : public ForwardingOcp {
 public:
  /// Multipliers start at zero, penalties at 1. Throws std::invalid_argument when P has no
  /// Hamiltonian minimizer.
  AugmentedLagrangianOcp(const Ocp& inner, const TimeGrid& grid);

  /// Sets nu (npsi) and rho > 0; throws std::invalid_argument on bad sizes or values.
  void SetTerminal(const Vec& nu, double rho);
  /// Sets mu (nc x N, >= 0) and rho_c > 0; throws std::invalid_argument on bad sizes or values.
  void SetPath(const Mat& mu, double rho);
  const Vec& terminal_multipliers() const { return nu_; }
  const Mat& path_multipliers() const { return mu_; }
  double rho() const { return rho_; }
  double path_rho() const { return rho_c_; }
  /// nu + rho psi(x_N).
  Vec TerminalUpdate(ConstVecRef xN) const;
  /// max(0, mu_k + rho_c c(t_k, x_k, u_k)) for the grid's intervals, given states X (nx x N+1)
  /// and controls U (nu x N).
  Mat PathUpdate(const Mat& X, const Mat& U) const;
  /// max_{i,k} max(c_i(t_k, x_k, u_k), 0) and max_{i,k} |min(-c_i, mu_i,k)| (the violation and
  /// the complementarity of the path constraints at (X, U)).
  void PathMeasures(const Mat& X, const Mat& U, double* violation, double* complementarity) const;

  std::string name() const override { return inner().name() + "+al"; }

  double RunningCost(double t, ConstVecRef x, ConstVecRef u) const override;
  void RunningCostGradient(
      double t, ConstVecRef x, ConstVecRef u, double* L, VecRef Lx, VecRef Lu) const override;
  double TerminalCost(ConstVecRef x) const override;
  void TerminalCostGradient(ConstVecRef x, double* phi, VecRef phix) const override;
  void TerminalHessian(ConstVecRef x, double sigma, ConstVecRef nu, MatRef hess) const override;
  void PathConstraints(double, ConstVecRef, ConstVecRef, VecRef) const override {}
  void PathConstraintsJacobian(
      double, ConstVecRef, ConstVecRef, VecRef, MatRef, MatRef) const override {}
  void PointHessian(double t,
                    ConstVecRef x,
                    ConstVecRef u,
                    double sigma,
                    ConstVecRef lambda,
                    ConstVecRef mu,
                    MatRef hess) const override;
  bool HasHamiltonianMinimizer() const override { return true; }
  void MinimizeHamiltonian(double t, ConstVecRef x, ConstVecRef p, VecRef u) const override;
  void MinimizeAndCompareHamiltonian(double t,
                                     ConstVecRef x,
                                     ConstVecRef p,
                                     ConstVecRef u,
                                     VecRef u_star,
                                     double* h_star,
                                     double* h_now,
                                     VecRef f) const override;
  /// P's bound without path terms (they can be negative: -mu^2 / (2 rho_c)); none with them.
  std::optional<double> RunningCostLowerBound() const override;

 private:
  // The multipliers' interval for time t (the Euler grid's left node pairing).
  int Interval(double t) const { return grid_.Locate(t); }
  bool HasPathTerm() const { return nc_ > 0; }

  const TimeGrid& grid_;
  int nc_;
  Vec nu_;
  Mat mu_;
  double rho_ = 1.0, rho_c_ = 1.0;
  mutable std::unique_ptr<ConvexPointMinimizer> minimizer_;
};

}  // namespace ocpb
