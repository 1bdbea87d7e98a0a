#include "core/stage_rk_ocp.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

namespace ocpb {

StageRkOcp::StageRkOcp(const Ocp& ocp, const TimeGrid& grid, RkTableau tableau, TerminalMode mode)
    : ocp_(ocp), grid_(grid), tableau_(std::move(tableau)), mode_(mode) {
  if (const std::string why = tableau_.Check(); !why.empty()) {
    throw std::invalid_argument("StageRkOcp: " + why);
  }
}

double StageRkOcp::StageTime(int k, int i) const {
  return grid_.t(k) + tableau_.c[static_cast<size_t>(i)] * grid_.h(k);
}

double StageRkOcp::StageWeight(int k, int i) const {
  return grid_.h(k) * tableau_.b[static_cast<size_t>(i)];
}

double StageRkOcp::Simulate(const Mat& U, Mat* X, Mat* Y, double* running) const {
  const int nx = ocp_.nx(), s = stages(), N = intervals();
  if (U.rows() != ocp_.nu() || U.cols() != s * N) {
    throw std::invalid_argument("StageRkOcp::Simulate: U must be nu x sN");
  }
  if (X) X->resize(nx, N + 1);
  if (Y) Y->resize(nx, s * N);
  Mat K(nx, s);
  Vec x = ocp_.x0(), y(nx);
  if (X) X->col(0) = x;
  double sum = 0.0;
  for (int k = 0; k < N; ++k) {
    const double h = grid_.h(k);
    double ell = 0.0;
    for (int i = 0; i < s; ++i) {
      y = x;
      for (int j = 0; j < i; ++j) {
        if (tableau_.A(i, j) != 0.0) y += (h * tableau_.A(i, j)) * K.col(j);
      }
      const int col = k * s + i;
      const double t = StageTime(k, i);
      ocp_.Dynamics(t, y, U.col(col), K.col(i));
      ell += tableau_.b[static_cast<size_t>(i)] * ocp_.RunningCost(t, y, U.col(col));
      if (Y) Y->col(col) = y;
    }
    for (int i = 0; i < s; ++i) x += (h * tableau_.b[static_cast<size_t>(i)]) * K.col(i);
    sum += h * ell;
    if (X) X->col(k + 1) = x;
  }
  if (running) *running = sum;
  const double J = sum + ocp_.TerminalObjective(x, mode_);
  return std::isfinite(J) && x.allFinite() ? J : std::numeric_limits<double>::quiet_NaN();
}

void StageRkOcp::Adjoint(
    const Mat& U, const Mat& X, Mat* Lambda, Mat* Y, Mat* P, Mat* G, Vec* dJdh) const {
  const int nx = ocp_.nx(), nu = ocp_.nu(), s = stages(), N = intervals();
  if (U.rows() != nu || U.cols() != s * N || X.rows() != nx || X.cols() != N + 1) {
    throw std::invalid_argument("StageRkOcp::Adjoint: U must be nu x sN and X nx x (N+1)");
  }
  Lambda->resize(nx, N + 1);
  Y->resize(nx, s * N);
  P->resize(nx, s * N);
  G->resize(nu, s * N);
  double phi = 0.0, L = 0.0;
  Vec lam(nx);
  ocp_.TerminalObjectiveGradient(X.col(N), mode_, &phi, lam);
  Lambda->col(N) = lam;
  Mat K(nx, s), bar_y(nx, s);
  std::vector<Mat> fx(static_cast<size_t>(s), Mat(nx, nx)), fu(static_cast<size_t>(s), Mat(nx, nu));
  Mat Lx(nx, s), Lu(nu, s);
  Vec bar_k(nx), Ls(s);
  if (dJdh) dJdh->resize(N);
  for (int k = N - 1; k >= 0; --k) {
    const double h = grid_.h(k);
    // The stages again, with their derivatives.
    for (int i = 0; i < s; ++i) {
      const int col = k * s + i;
      auto y = Y->col(col);
      y = X.col(k);
      for (int j = 0; j < i; ++j) {
        if (tableau_.A(i, j) != 0.0) y += (h * tableau_.A(i, j)) * K.col(j);
      }
      const double t = StageTime(k, i);
      ocp_.DynamicsJacobian(t, y, U.col(col), K.col(i), fx[i], fu[i]);
      ocp_.RunningCostGradient(t, y, U.col(col), &L, Lx.col(i), Lu.col(i));
      Ls[i] = L;
    }
    // Reverse through the stages: the cotangent of K_i is h b_i lambda_{k,i}.
    for (int i = s - 1; i >= 0; --i) {
      const double w = h * tableau_.b[static_cast<size_t>(i)];
      bar_k = w * lam;
      for (int l = i + 1; l < s; ++l) {
        if (tableau_.A(l, i) != 0.0) bar_k += (h * tableau_.A(l, i)) * bar_y.col(l);
      }
      auto p = P->col(k * s + i);
      p = bar_k / w;
      // bar_y_i = h b_i H_x(stage i), dJ/du_{k,i} = h b_i H_u(stage i).
      bar_y.col(i) = w * (fx[i].transpose() * p + Lx.col(i));
      G->col(k * s + i) = w * (fu[i].transpose() * p + Lu.col(i));
    }
    if (dJdh) {
      // lam is still lambda_{k+1}; bar_y_i = h b_i H_x(stage i).
      double d = 0.0;
      for (int i = 0; i < s; ++i) {
        d += tableau_.b[static_cast<size_t>(i)] * (lam.dot(K.col(i)) + Ls[i]) +
             bar_y.col(i).dot(Y->col(k * s + i) - X.col(k)) / h;
      }
      (*dJdh)[k] = d;
    }
    for (int i = 0; i < s; ++i) lam += bar_y.col(i);
    Lambda->col(k) = lam;
  }
}

}  // namespace ocpb
