#include "solvers/euler_costate_fit.h"

#include <cmath>
#include <stdexcept>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/QR>

#include "core/control_set.h"

namespace ocpb {
namespace {

// The components of u strictly inside U (see FitEulerCostates).
std::vector<int> FreeComponents(const ControlSet& set, ConstVecRef u) {
  std::vector<int> free;
  if (set.blocks().empty()) {
    for (int i = 0; i < u.size(); ++i) free.push_back(i);
    return free;
  }
  constexpr double kMargin = 1e-6;
  for (const ControlSet::Block& b : set.blocks()) {
    if (b.kind == ControlSet::Kind::kBox) {
      for (int i = 0; i < b.size; ++i) {
        const double lo = b.lower[i], hi = b.upper[i], v = u[b.offset + i];
        const double margin = kMargin * (std::isfinite(hi - lo) ? hi - lo : 1.0);
        if (v > lo + margin && v < hi - margin) free.push_back(b.offset + i);
      }
    } else {
      const auto ub = u.segment(b.offset, b.size);
      const double r = b.center.size() > 0 ? (ub - b.center).norm() : ub.norm();
      if (r < (1.0 - kMargin) * b.radius) {
        for (int i = 0; i < b.size; ++i) free.push_back(b.offset + i);
      }
    }
  }
  return free;
}

}  // namespace

Mat FitEulerCostates(
    const Ocp& ocp, const TimeGrid& grid, TerminalMode mode, const Mat& U, const Mat& X) {
  const int nx = ocp.nx(), nu = ocp.nu(), N = grid.intervals();
  if (U.rows() != nu || U.cols() != N || X.rows() != nx || X.cols() != N + 1) {
    throw std::invalid_argument("FitEulerCostates: U must be nu x N and X nx x (N+1)");
  }
  // p_k = M_k q + c_k: M_N = I, c_N = 0; M_k = (I + h fx^T) M_{k+1}, c_k = (I + h fx^T) c_{k+1}
  // + h L_x at (t_k, x_k, u_k).
  std::vector<Mat> M(N + 1);
  std::vector<Vec> c(N + 1);
  M[N] = Mat::Identity(nx, nx);
  c[N] = Vec::Zero(nx);
  Vec f(nx), Lx(nx), Lu(nu);
  Mat fx(nx, nx), fu(nx, nu), hess(nx + nu, nx + nu);
  double L = 0.0;
  for (int k = N - 1; k >= 0; --k) {
    const double t = grid.t(k), h = grid.h(k);
    ocp.DynamicsJacobian(t, X.col(k), U.col(k), f, fx, fu);
    ocp.RunningCostGradient(t, X.col(k), U.col(k), &L, Lx, Lu);
    M[k] = M[k + 1] + h * fx.transpose() * M[k + 1];
    c[k] = c[k + 1] + h * (fx.transpose() * c[k + 1] + Lx);
  }
  Vec q0(nx);
  double phi = 0.0;
  ocp.TerminalObjectiveGradient(X.col(N), mode, &phi, q0);

  // Rows sqrt(h_k) (H_uu)_F^-1 [G_k q + g_k] of the free components, H_u = G q + g.
  std::vector<double> rows;  // [A | b] row-major
  const Vec no_mu = Vec::Zero(ocp.num_path());
  for (int k = 0; k < N; ++k) {
    const double t = grid.t(k), h = grid.h(k);
    const std::vector<int> free = FreeComponents(ocp.control_set(), U.col(k));
    if (free.empty()) continue;
    ocp.DynamicsJacobian(t, X.col(k), U.col(k), f, fx, fu);
    ocp.RunningCostGradient(t, X.col(k), U.col(k), &L, Lx, Lu);
    const Vec p0 = M[k + 1] * q0 + c[k + 1];
    ocp.PointHessian(t, X.col(k), U.col(k), 1.0, p0, no_mu, hess);
    const int m = static_cast<int>(free.size());
    Mat Huu(m, m), G(m, nx);
    Vec g(m);
    for (int a = 0; a < m; ++a) {
      for (int b = 0; b < m; ++b) Huu(a, b) = hess(nx + free[a], nx + free[b]);
      G.row(a) = fu.col(free[a]).transpose() * M[k + 1];
      g[a] = Lu[free[a]] + fu.col(free[a]).dot(c[k + 1]);
    }
    const Eigen::LLT<Mat> llt(Huu);
    if (llt.info() == Eigen::Success && Huu.allFinite()) {
      G = llt.solve(G);
      g = llt.solve(g);
    }
    const double w = std::sqrt(h);
    for (int a = 0; a < m; ++a) {
      for (int j = 0; j < nx; ++j) rows.push_back(w * G(a, j));
      rows.push_back(-w * g[a]);
    }
  }
  Vec q = q0;
  const int count = static_cast<int>(rows.size()) / (nx + 1);
  if (count > 0) {
    Mat A(count + nx, nx);
    Vec b(count + nx);
    for (int i = 0; i < count; ++i) {
      for (int j = 0; j < nx; ++j) A(i, j) = rows[static_cast<size_t>(i) * (nx + 1) + j];
      b[i] = rows[static_cast<size_t>(i) * (nx + 1) + nx];
    }
    const double delta = 1e-8 * A.topRows(count).colwise().norm().maxCoeff();
    A.bottomRows(nx) = delta * Mat::Identity(nx, nx);
    b.tail(nx) = delta * q0;
    if (A.allFinite() && b.allFinite() && delta > 0.0) {
      const Vec fitted = A.householderQr().solve(b);
      if (fitted.allFinite()) q = fitted;
    }
  }
  Mat P(nx, N + 1);
  for (int k = 0; k <= N; ++k) P.col(k) = M[k] * q + c[k];
  return P;
}

}  // namespace ocpb
