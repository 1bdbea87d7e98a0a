// The exterior-penalty form of a problem with path constraints (what the Hamiltonian method
// solves in place of it; see Ocp::HamiltonianReformulation).
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "core/ocp.h"

namespace ocpb {

/// Given a problem P with path constraints c(t, x, u) <= 0, the problem P_rho
///
///   minimize    int_{t0}^{tf} [ L(t, x, u) + rho sum_i max(0, c_i(t, x, u))^2 ] dt + phi(x(tf))
///   subject to  x' = f(t, x, u),  x(t0) = x0,  u(t) in U,  (psi(x(tf)) = 0 or its penalty),
///
/// with no path constraints (num_path() == 0). This is the quadratic exterior penalty
/// (Nocedal & Wright, "Numerical Optimization", 2nd ed., Springer 2006, Sec. 17.1; for optimal
/// control, fit code B of the project's reference-problem notes): every admissible control of P is
/// admissible for P_rho with the same cost, so min P_rho <= min P, and the gap closes as
/// rho -> infinity. Dynamics, U, x0, horizon and the terminal part are P's.
///
/// Derivatives are exact and come from P's: with c+ = max(0, c),
///   d/dz  rho sum c+_i^2 = 2 rho sum_i c+_i c_i,z,
///   d2/dz2 rho sum c+_i^2 = 2 rho sum_{i: c_i > 0} (c_i,z c_i,z^T + c_i c_i,zz),
/// where the c_i,zz term comes from P.PointHessian with mu = 2 rho sigma c+ (z = (x, u)).
///
/// The Hamiltonian minimizer: `minimizer` when given (it must be exact for the penalized
/// H = p^T f + L + rho sum c+_i^2); otherwise P's own MinimizeHamiltonian, which is exact only
/// when c does not depend on u (state constraints leave the u-part of H unchanged).
class PathPenaltyOcp final : public Ocp {
 public:
  using Minimizer = std::function<void(double t, ConstVecRef x, ConstVecRef p, VecRef u)>;

  /// Throws std::invalid_argument when `base` is null or rho is not finite and > 0.
  PathPenaltyOcp(std::unique_ptr<const Ocp> base, double rho, Minimizer minimizer = nullptr);

  /// P's name with "+penalty" appended.
  std::string name() const override { return base_->name() + "+penalty"; }
  const Ocp& base() const { return *base_; }
  double rho() const { return rho_; }

  void Dynamics(double t, ConstVecRef x, ConstVecRef u, VecRef f) const override {
    base_->Dynamics(t, x, u, f);
  }
  double RunningCost(double t, ConstVecRef x, ConstVecRef u) const override;
  double TerminalCost(ConstVecRef x) const override { return base_->TerminalCost(x); }
  void TerminalConstraints(ConstVecRef x, VecRef psi) const override {
    base_->TerminalConstraints(x, psi);
  }
  void PathConstraints(double, ConstVecRef, ConstVecRef, VecRef) const override {}

  void DynamicsJacobian(
      double t, ConstVecRef x, ConstVecRef u, VecRef f, MatRef fx, MatRef fu) const override {
    base_->DynamicsJacobian(t, x, u, f, fx, fu);
  }
  void RunningCostGradient(
      double t, ConstVecRef x, ConstVecRef u, double* L, VecRef Lx, VecRef Lu) const override;
  void TerminalCostGradient(ConstVecRef x, double* phi, VecRef phix) const override {
    base_->TerminalCostGradient(x, phi, phix);
  }
  void TerminalConstraintsJacobian(ConstVecRef x, VecRef psi, MatRef psix) const override {
    base_->TerminalConstraintsJacobian(x, psi, psix);
  }
  void PathConstraintsJacobian(
      double, ConstVecRef, ConstVecRef, VecRef, MatRef, MatRef) const override {}

  void PointHessian(double t,
                    ConstVecRef x,
                    ConstVecRef u,
                    double sigma,
                    ConstVecRef lambda,
                    ConstVecRef mu,
                    MatRef hess) const override;
  void TerminalHessian(ConstVecRef x, double sigma, ConstVecRef nu, MatRef hess) const override {
    base_->TerminalHessian(x, sigma, nu, hess);
  }

  bool HasHamiltonianMinimizer() const override {
    return minimizer_ ? true : base_->HasHamiltonianMinimizer();
  }
  void MinimizeHamiltonian(double t, ConstVecRef x, ConstVecRef p, VecRef u) const override;

 private:
  std::unique_ptr<const Ocp> base_;
  double rho_;
  Minimizer minimizer_;
};

}  // namespace ocpb
