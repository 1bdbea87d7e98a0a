#include "solvers/minimizer_derivative.h"

#include <algorithm>
#include <cmath>

namespace ocpb {

MinimizerDerivative::MinimizerDerivative(const Ocp& ocp)
    : ocp_(ocp), nx_(ocp.nx()), nu_(ocp.nu()), box_active_(ocp.nu(), false) {
  A_.resize(nu_, nu_);
  f_.resize(nx_);
  Lx_.resize(nx_);
  Lu_.resize(nu_);
  Hu_.resize(nu_);
  fx_.resize(nx_, nx_);
  fu_.resize(nx_, nu_);
  hess_.resize(nx_ + nu_, nx_ + nu_);
}

bool MinimizerDerivative::Compute(
    ConstVecRef u, ConstVecRef Hu, ConstMatRef fu, ConstMatRef hess, MatRef du_dx, MatRef du_dp) {
  const int nx = nx_, nu = nu_;
  // M = H_uu plus the curvature of active spheres; A = the active constraint rows.
  Mat& M = m_;
  M = hess.bottomRightCorner(nu, nu);
  A_.setZero();
  std::fill(box_active_.begin(), box_active_.end(), false);
  int na = 0;
  for (const ControlSet::Block& b : ocp_.control_set().blocks()) {
    if (b.kind == ControlSet::Kind::kBox) {
      for (int i = 0; i < b.size; ++i) {
        const int j = b.offset + i;
        const double lo = b.lower[i], up = b.upper[i];
        const bool at_lower =
            std::isfinite(lo) && u[j] <= lo + kActiveTolerance * std::max(1.0, std::abs(lo));
        const bool at_upper =
            std::isfinite(up) && u[j] >= up - kActiveTolerance * std::max(1.0, std::abs(up));
        if (at_lower || at_upper) {
          A_(na++, j) = 1.0;
          box_active_[j] = true;
        }
      }
    } else {
      const auto d = u.segment(b.offset, b.size) - b.center;
      const double nd = d.norm();
      if (b.radius > 0.0 && nd >= b.radius * (1.0 - kActiveTolerance)) {
        // n = d / |d|; H_u + mu (u - c) = 0 on the sphere, mu >= 0.
        const double mu = std::max(0.0, -d.dot(Hu.segment(b.offset, b.size)) / (nd * nd));
        M.block(b.offset, b.offset, b.size, b.size).diagonal().array() += mu;
        A_.block(na++, b.offset, 1, b.size) = d.transpose() / nd;
      }
    }
  }
  num_active_ = na;

  Mat& K = kkt_;
  K.setZero(nu + na, nu + na);
  K.topLeftCorner(nu, nu) = M;
  if (na > 0) {
    K.topRightCorner(nu, na) = A_.topRows(na).transpose();
    K.bottomLeftCorner(na, nu) = A_.topRows(na);
  }
  lu_.compute(K);
  if (!lu_.isInvertible()) return false;
  // (du_dx, du_dp) = -Z (H_ux, f_u^T), Z the top-left nu x nu block of K^-1 (the right-hand
  // sides vanish in the constraint rows): nu solves with P K Q = L U in plain loops (Eigen's
  // blocked triangular solves cost more than the arithmetic at these sizes).
  const int n = nu + na;
  const Mat& lu = lu_.matrixLU();
  const auto& p = lu_.permutationP().indices();
  const auto& q = lu_.permutationQ().indices();
  work_.resize(n);
  inverse_.resize(nu, nu);
  for (int c = 0; c < nu; ++c) {
    work_.setZero();
    work_[p[c]] = 1.0;
    for (int j = 0; j < n; ++j) {
      const double v = work_[j];
      if (v == 0.0) continue;
      for (int i = j + 1; i < n; ++i) work_[i] -= lu(i, j) * v;
    }
    for (int j = n - 1; j >= 0; --j) {
      work_[j] /= lu(j, j);
      const double v = work_[j];
      if (v == 0.0) continue;
      for (int i = 0; i < j; ++i) work_[i] -= lu(i, j) * v;
    }
    for (int i = 0; i < n; ++i) {
      if (q[i] < nu) inverse_(q[i], c) = work_[i];
    }
  }
  du_dx = -inverse_.lazyProduct(hess.bottomLeftCorner(nu, nx));
  du_dp = -inverse_.lazyProduct(fu.transpose());
  return du_dx.allFinite() && du_dp.allFinite();
}

bool MinimizerDerivative::ComputeAt(
    double t, ConstVecRef x, ConstVecRef p, VecRef u, MatRef du_dx, MatRef du_dp) {
  ocp_.MinimizeHamiltonian(t, x, p, u);
  ocp_.DynamicsJacobian(t, x, u, f_, fx_, fu_);
  double L = 0.0;
  ocp_.RunningCostGradient(t, x, u, &L, Lx_, Lu_);
  Hu_ = Lu_ + fu_.transpose() * p;
  const Vec no_mu = Vec::Zero(ocp_.num_path());
  ocp_.PointHessian(t, x, u, 1.0, p, no_mu, hess_);
  return Compute(u, Hu_, fu_, hess_, du_dx, du_dp);
}

}  // namespace ocpb
