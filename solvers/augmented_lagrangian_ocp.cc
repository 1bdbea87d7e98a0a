#include "solvers/augmented_lagrangian_ocp.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ocpb {

AugmentedLagrangianOcp::AugmentedLagrangianOcp(const Ocp& inner, const TimeGrid& grid)
    : ForwardingOcp(inner, false),
      grid_(grid),
      nc_(inner.num_path()),
      nu_(Vec::Zero(inner.num_terminal())),
      mu_(Mat::Zero(inner.num_path(), grid.intervals())) {
  if (!inner.HasHamiltonianMinimizer()) {
    throw std::invalid_argument("AugmentedLagrangianOcp: problem '" + inner.name() +
                                "' has no Hamiltonian minimizer");
  }
}

void AugmentedLagrangianOcp::SetTerminal(const Vec& nu, double rho) {
  if (nu.size() != num_terminal() || !nu.allFinite() || !(rho > 0.0) || !std::isfinite(rho)) {
    throw std::invalid_argument("AugmentedLagrangianOcp: nu must be finite of size npsi, rho > 0");
  }
  nu_ = nu;
  rho_ = rho;
}

void AugmentedLagrangianOcp::SetPath(const Mat& mu, double rho) {
  if (mu.rows() != nc_ || mu.cols() != grid_.intervals() || !mu.allFinite() ||
      (mu.size() > 0 && mu.minCoeff() < 0.0) || !(rho > 0.0) || !std::isfinite(rho)) {
    throw std::invalid_argument(
        "AugmentedLagrangianOcp: mu must be finite, >= 0, nc x N; rho_c > 0");
  }
  mu_ = mu;
  rho_c_ = rho;
}

Vec AugmentedLagrangianOcp::TerminalUpdate(ConstVecRef xN) const {
  Vec psi(num_terminal());
  inner().TerminalConstraints(xN, psi);
  return nu_ + rho_ * psi;
}

Mat AugmentedLagrangianOcp::PathUpdate(const Mat& X, const Mat& U) const {
  Mat next(nc_, grid_.intervals());
  Vec c(nc_);
  for (int k = 0; k < grid_.intervals(); ++k) {
    inner().PathConstraints(grid_.t(k), X.col(k), U.col(k), c);
    next.col(k) = (mu_.col(k) + rho_c_ * c).cwiseMax(0.0);
  }
  return next;
}

void AugmentedLagrangianOcp::PathMeasures(const Mat& X,
                                          const Mat& U,
                                          double* violation,
                                          double* complementarity) const {
  double v = 0.0, comp = 0.0;
  Vec c(nc_);
  for (int k = 0; k < grid_.intervals(); ++k) {
    inner().PathConstraints(grid_.t(k), X.col(k), U.col(k), c);
    for (int i = 0; i < nc_; ++i) {
      v = std::max(v, c[i]);
      comp = std::max(comp, std::abs(std::min(-c[i], mu_(i, k))));
    }
  }
  *violation = v;
  *complementarity = comp;
}

double AugmentedLagrangianOcp::RunningCost(double t, ConstVecRef x, ConstVecRef u) const {
  double value = inner().RunningCost(t, x, u);
  if (!HasPathTerm()) return value;
  Vec c(nc_);
  inner().PathConstraints(t, x, u, c);
  const int k = Interval(t);
  for (int i = 0; i < nc_; ++i) {
    const double m = mu_(i, k), a = std::max(0.0, m + rho_c_ * c[i]);
    value += (a * a - m * m) / (2.0 * rho_c_);
  }
  return value;
}

void AugmentedLagrangianOcp::RunningCostGradient(
    double t, ConstVecRef x, ConstVecRef u, double* L, VecRef Lx, VecRef Lu) const {
  inner().RunningCostGradient(t, x, u, L, Lx, Lu);
  if (!HasPathTerm()) return;
  Vec c(nc_);
  Mat cx(nc_, nx()), cu(nc_, nu());
  inner().PathConstraintsJacobian(t, x, u, c, cx, cu);
  const int k = Interval(t);
  for (int i = 0; i < nc_; ++i) {
    const double m = mu_(i, k), a = std::max(0.0, m + rho_c_ * c[i]);
    *L += (a * a - m * m) / (2.0 * rho_c_);
    if (a == 0.0) continue;
    Lx += a * cx.row(i).transpose();
    Lu += a * cu.row(i).transpose();
  }
}

double AugmentedLagrangianOcp::TerminalCost(ConstVecRef x) const {
  double value = inner().TerminalCost(x);
  if (num_terminal() == 0) return value;
  Vec psi(num_terminal());
  inner().TerminalConstraints(x, psi);
  for (int i = 0; i < num_terminal(); ++i) {
    value += nu_[i] * psi[i] + 0.5 * rho_ * psi[i] * psi[i];
  }
  return value;
}

void AugmentedLagrangianOcp::TerminalCostGradient(ConstVecRef x, double* phi, VecRef phix) const {
  inner().TerminalCostGradient(x, phi, phix);
  if (num_terminal() == 0) return;
  Vec psi(num_terminal());
  Mat psix(num_terminal(), nx());
  inner().TerminalConstraintsJacobian(x, psi, psix);
  for (int i = 0; i < num_terminal(); ++i) {
    *phi += nu_[i] * psi[i] + 0.5 * rho_ * psi[i] * psi[i];
  }
  phix += psix.transpose() * (nu_ + rho_ * psi);
}

void AugmentedLagrangianOcp::TerminalHessian(ConstVecRef x,
                                             double sigma,
                                             ConstVecRef nu,
                                             MatRef hess) const {
  // sigma Phi_A'' + nu^T psi'' = sigma phi'' + (sigma (nu_A + rho psi) + nu)^T psi''
  //                              + sigma rho psi_x^T psi_x.
  const int npsi = num_terminal();
  if (npsi == 0) {
    inner().TerminalHessian(x, sigma, nu, hess);
    return;
  }
  Vec psi(npsi);
  Mat psix(npsi, nx());
  inner().TerminalConstraintsJacobian(x, psi, psix);
  const Vec weights = sigma * (nu_ + rho_ * psi) + nu;
  inner().TerminalHessian(x, sigma, weights, hess);
  hess += (sigma * rho_) * psix.transpose() * psix;
}

void AugmentedLagrangianOcp::PointHessian(double t,
                                          ConstVecRef x,
                                          ConstVecRef u,
                                          double sigma,
                                          ConstVecRef lambda,
                                          ConstVecRef /*mu*/,
                                          MatRef hess) const {
  if (!HasPathTerm()) {
    inner().PointHessian(t, x, u, sigma, lambda, Vec(), hess);
    return;
  }
  Vec c(nc_);
  Mat cx(nc_, nx()), cu(nc_, nu());
  inner().PathConstraintsJacobian(t, x, u, c, cx, cu);
  const int k = Interval(t);
  Vec a(nc_);
  for (int i = 0; i < nc_; ++i) a[i] = std::max(0.0, mu_(i, k) + rho_c_ * c[i]);
  // sigma * (1/(2 rho_c)) max(0, mu + rho_c c)^2 has the Hessian
  // sigma (rho_c c_z c_z^T + a c_zz) where a > 0: the c_zz part is P's Hessian with mu = sigma a.
  inner().PointHessian(t, x, u, sigma, lambda, sigma * a, hess);
  Vec cz(nx() + nu());
  for (int i = 0; i < nc_; ++i) {
    if (a[i] <= 0.0) continue;
    cz.head(nx()) = cx.row(i).transpose();
    cz.tail(nu()) = cu.row(i).transpose();
    hess += (sigma * rho_c_) * cz * cz.transpose();
  }
}

void AugmentedLagrangianOcp::MinimizeHamiltonian(double t,
                                                 ConstVecRef x,
                                                 ConstVecRef p,
                                                 VecRef u) const {
  inner().MinimizeHamiltonian(t, x, p, u);
  if (!HasPathTerm()) return;
  Vec c(nc_);
  Mat cx(nc_, nx()), cu(nc_, nu());
  inner().PathConstraintsJacobian(t, x, u, c, cx, cu);
  if (cu.cwiseAbs().maxCoeff() == 0.0) return;  // state constraints: H's u-part is P's
  if (!minimizer_) minimizer_ = std::make_unique<ConvexPointMinimizer>(*this);
  const Vec start = u;
  minimizer_->Minimize(t, x, p, start, std::numeric_limits<double>::infinity(), start, u);
}

void AugmentedLagrangianOcp::MinimizeAndCompareHamiltonian(double t,
                                                           ConstVecRef x,
                                                           ConstVecRef p,
                                                           ConstVecRef u,
                                                           VecRef u_star,
                                                           double* h_star,
                                                           double* h_now,
                                                           VecRef f) const {
  if (!HasPathTerm()) {  // H is P's: its (possibly fused) implementation
    inner().MinimizeAndCompareHamiltonian(t, x, p, u, u_star, h_star, h_now, f);
    return;
  }
  Ocp::MinimizeAndCompareHamiltonian(t, x, p, u, u_star, h_star, h_now, f);
}

std::optional<double> AugmentedLagrangianOcp::RunningCostLowerBound() const {
  if (HasPathTerm()) return std::nullopt;
  return inner().RunningCostLowerBound();
}

}  // namespace ocpb
