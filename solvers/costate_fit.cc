#include "solvers/costate_fit.h"

#include <cmath>
#include <cstddef>
#include <stdexcept>

#include <Eigen/Cholesky>
#include <Eigen/QR>

namespace ocpb {

void FreeControlComponents(const ControlSet& set, ConstVecRef u, std::vector<int>* free) {
  free->clear();
  if (set.blocks().empty()) {
    for (int i = 0; i < u.size(); ++i) free->push_back(i);
    return;
  }
  constexpr double kMargin = 1e-6;
  for (const ControlSet::Block& b : set.blocks()) {
    if (b.kind == ControlSet::Kind::kBox) {
      for (int i = 0; i < b.size; ++i) {
        const double lo = b.lower[i], hi = b.upper[i], v = u[b.offset + i];
        const double margin = kMargin * (std::isfinite(hi - lo) ? hi - lo : 1.0);
        if (v > lo + margin && v < hi - margin) free->push_back(b.offset + i);
      }
    } else {
      const auto ub = u.segment(b.offset, b.size);
      const double r = b.center.size() > 0 ? (ub - b.center).norm() : ub.norm();
      if (r < (1.0 - kMargin) * b.radius) {
        for (int i = 0; i < b.size; ++i) free->push_back(b.offset + i);
      }
    }
  }
}

CostateFit FitTerminalCostate(const Ocp& ocp,
                              const CostateFitNodes& nodes,
                              const std::vector<Mat>& M,
                              const std::vector<Vec>& c,
                              const Vec& q0) {
  const int nx = ocp.nx(), nu = ocp.nu();
  const int count = static_cast<int>(nodes.t.size());
  if (!nodes.X || !nodes.U || nodes.weight.size() != nodes.t.size() || nodes.X->rows() != nx ||
      nodes.U->rows() != nu || nodes.X->cols() < count || nodes.U->cols() < count ||
      nodes.costate_offset < 0 || nodes.costate_offset + count > static_cast<int>(M.size()) ||
      M.size() != c.size() || q0.size() != nx) {
    throw std::invalid_argument("FitTerminalCostate: the nodes, M, c and q0 do not match");
  }
  const Mat& X = *nodes.X;
  const Mat& U = *nodes.U;
  std::vector<double> values;  // rows of [A | b], row-major
  Vec f(nx), Lx(nx), Lu(nu), p0(nx);
  Mat fx(nx, nx), fu(nx, nu), hess(nx + nu, nx + nu);
  const Vec no_mu = Vec::Zero(ocp.num_path());
  double L = 0.0;
  std::vector<int> free;
  // A Mayer cost along the controls: L = 0, L_x = 0, L_u = 0 and L_uu = 0 at every node (checked
  // until a node shows otherwise; the extra PointHessian only where L_x = L_u = 0).
  bool mayer = true;
  const Vec zero_p = Vec::Zero(nx);
  for (int i = 0; i < count; ++i) {
    const double t = nodes.t[static_cast<size_t>(i)];
    const int j = nodes.costate_offset + i;
    if (mayer) {
      ocp.RunningCostGradient(t, X.col(i), U.col(i), &L, Lx, Lu);
      mayer = L == 0.0 && (Lx.array() == 0.0).all() && (Lu.array() == 0.0).all();
      if (mayer) {
        ocp.PointHessian(t, X.col(i), U.col(i), 1.0, zero_p, no_mu, hess);
        mayer = (hess.bottomRightCorner(nu, nu).array() == 0.0).all();
      }
    }
    FreeControlComponents(ocp.control_set(), U.col(i), &free);
    if (free.empty()) continue;
    ocp.DynamicsJacobian(t, X.col(i), U.col(i), f, fx, fu);
    ocp.RunningCostGradient(t, X.col(i), U.col(i), &L, Lx, Lu);
    p0 = M[j] * q0 + c[j];
    ocp.PointHessian(t, X.col(i), U.col(i), 1.0, p0, no_mu, hess);
    const int m = static_cast<int>(free.size());
    Mat Huu(m, m), G(m, nx);
    Vec g(m);
    for (int a = 0; a < m; ++a) {
      for (int b = 0; b < m; ++b) Huu(a, b) = hess(nx + free[a], nx + free[b]);
      // H_u,a(q) = Lu_a + fu_a^T (M_j q + c_j) = G_a q + g_a.
      G.row(a) = fu.col(free[a]).transpose() * M[j];
      g[a] = Lu[free[a]] + fu.col(free[a]).dot(c[j]);
    }
    const Eigen::LLT<Mat> llt(Huu);
    if (llt.info() == Eigen::Success && Huu.allFinite()) {
      G = llt.solve(G);
      g = llt.solve(g);
    }
    const double w = std::sqrt(nodes.weight[static_cast<size_t>(i)]);
    for (int a = 0; a < m; ++a) {
      for (int k = 0; k < nx; ++k) values.push_back(w * G(a, k));
      values.push_back(-w * g[a]);
    }
  }
  CostateFit out;
  out.q = q0;
  out.degenerate = mayer && count > 0;
  out.rows = static_cast<int>(values.size()) / (nx + 1);
  const int rows = out.rows;
  if (rows == 0) return out;
  Mat A(rows + nx, nx);
  Vec b(rows + nx);
  for (int i = 0; i < rows; ++i) {
    for (int k = 0; k < nx; ++k) A(i, k) = values[static_cast<size_t>(i) * (nx + 1) + k];
    b[i] = values[static_cast<size_t>(i) * (nx + 1) + nx];
  }
  const double delta = 1e-8 * A.topRows(rows).colwise().norm().maxCoeff();
  A.bottomRows(nx) = delta * Mat::Identity(nx, nx);
  b.tail(nx) = delta * q0;
  if (!A.allFinite() || !b.allFinite() || !(delta > 0.0)) return out;
  const Vec q = A.householderQr().solve(b);
  if (q.allFinite()) out.q = q;
  return out;
}

}  // namespace ocpb
