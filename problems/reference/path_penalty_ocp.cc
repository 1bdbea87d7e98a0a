#include "problems/reference/path_penalty_ocp.h"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace ocpb {

PathPenaltyOcp::PathPenaltyOcp(std::unique_ptr<const Ocp> base, double rho, Minimizer minimizer)
    : base_(std::move(base)), rho_(rho), minimizer_(std::move(minimizer)) {
  if (!base_) throw std::invalid_argument("PathPenaltyOcp: the base problem must not be null");
  if (!std::isfinite(rho_) || rho_ <= 0.0) {
    throw std::invalid_argument("PathPenaltyOcp: the penalty weight rho must be finite and > 0");
  }
  SetDimensions(base_->nx(), base_->nu(), base_->num_terminal(), 0);
  SetHorizon(base_->t0(), base_->tf());
  SetInitialState(base_->x0());
  SetTerminalWeights(base_->terminal_weights());
  SetControlSet(base_->control_set());
}

double PathPenaltyOcp::RunningCost(double t, ConstVecRef x, ConstVecRef u) const {
  double value = base_->RunningCost(t, x, u);
  const int nc = base_->num_path();
  if (nc == 0) return value;
  Vec c(nc);
  base_->PathConstraints(t, x, u, c);
  for (int i = 0; i < nc; ++i) {
    if (c[i] > 0.0) value += rho_ * c[i] * c[i];
  }
  return value;
}

void PathPenaltyOcp::RunningCostGradient(
    double t, ConstVecRef x, ConstVecRef u, double* L, VecRef Lx, VecRef Lu) const {
  base_->RunningCostGradient(t, x, u, L, Lx, Lu);
  const int nc = base_->num_path();
  if (nc == 0) return;
  Vec c(nc);
  Mat cx(nc, nx()), cu(nc, nu());
  base_->PathConstraintsJacobian(t, x, u, c, cx, cu);
  for (int i = 0; i < nc; ++i) {
    if (c[i] <= 0.0) continue;
    *L += rho_ * c[i] * c[i];
    Lx += (2.0 * rho_ * c[i]) * cx.row(i).transpose();
    Lu += (2.0 * rho_ * c[i]) * cu.row(i).transpose();
  }
}

void PathPenaltyOcp::PointHessian(double t,
                                  ConstVecRef x,
                                  ConstVecRef u,
                                  double sigma,
                                  ConstVecRef lambda,
                                  ConstVecRef /*mu*/,
                                  MatRef hess) const {
  const int nc = base_->num_path();
  if (nc == 0 || sigma == 0.0) {
    base_->PointHessian(t, x, u, sigma, lambda, Vec::Zero(nc), hess);
    return;
  }
  Vec c(nc);
  Mat cx(nc, nx()), cu(nc, nu());
  base_->PathConstraintsJacobian(t, x, u, c, cx, cu);
  // sigma * rho * sum c+_i^2 has the Hessian sigma * 2 rho sum_{c_i > 0} (c_z c_z^T + c_i c_zz):
  // the second part is P's Hessian of mu^T c with mu = 2 rho sigma c+.
  const Vec mu = (2.0 * rho_ * sigma) * c.cwiseMax(0.0);
  base_->PointHessian(t, x, u, sigma, lambda, mu, hess);
  Vec cz(nx() + nu());
  for (int i = 0; i < nc; ++i) {
    if (c[i] <= 0.0) continue;
    cz.head(nx()) = cx.row(i).transpose();
    cz.tail(nu()) = cu.row(i).transpose();
    hess += (2.0 * rho_ * sigma) * cz * cz.transpose();
  }
}

void PathPenaltyOcp::MinimizeHamiltonian(double t, ConstVecRef x, ConstVecRef p, VecRef u) const {
  if (minimizer_) {
    minimizer_(t, x, p, u);
  } else {
    base_->MinimizeHamiltonian(t, x, p, u);
  }
}

}  // namespace ocpb
