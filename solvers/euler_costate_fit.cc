#include "solvers/euler_costate_fit.h"

#include <stdexcept>
#include <vector>

#include "solvers/costate_fit.h"

namespace ocpb {

Mat FitEulerCostates(const Ocp& ocp,
                     const TimeGrid& grid,
                     TerminalMode mode,
                     const Mat& U,
                     const Mat& X,
                     bool* adjoint_fallback) {
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
  Mat fx(nx, nx), fu(nx, nu);
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

  // The Euler pairing: node k is (t_k, x_k, u_k) with p_{k+1}, weight h_k.
  CostateFitNodes nodes;
  nodes.t.resize(static_cast<size_t>(N));
  nodes.weight.resize(static_cast<size_t>(N));
  for (int k = 0; k < N; ++k) {
    nodes.t[static_cast<size_t>(k)] = grid.t(k);
    nodes.weight[static_cast<size_t>(k)] = grid.h(k);
  }
  nodes.X = &X;
  nodes.U = &U;
  nodes.costate_offset = 1;
  const CostateFit fit = FitTerminalCostate(ocp, nodes, M, c, q0);
  Vec q = fit.q;
  // A Mayer cost: the adjoint sweep's own terminal costate (the penalty form's gradient).
  if (fit.degenerate) ocp.TerminalObjectiveGradient(X.col(N), TerminalMode::kPenalty, &phi, q);
  if (adjoint_fallback) *adjoint_fallback = fit.degenerate;
  Mat P(nx, N + 1);
  for (int k = 0; k <= N; ++k) P.col(k) = M[k] * q + c[k];
  return P;
}

}  // namespace ocpb
