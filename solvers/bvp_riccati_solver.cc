#include "solvers/bvp_riccati_solver.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace ocpb {
namespace {

// True when every entry is finite (x * 0 is NaN for a NaN or an infinity).
template <class M>
bool FiniteBlock(const M& m) {
  return (m.array() * 0.0).sum() == 0.0;
}

}  // namespace

bool BvpRiccatiSolver::SmallLu::Compute(ConstMatRef a) {
  const int n = static_cast<int>(a.rows());
  lu_ = a;
  pivot_.resize(n);
  double largest = 0.0;
  for (int j = 0; j < n; ++j) {
    int p = j;
    double best = std::abs(lu_(j, j));
    for (int i = j + 1; i < n; ++i) {
      if (std::abs(lu_(i, j)) > best) {
        best = std::abs(lu_(i, j));
        p = i;
      }
    }
    if (!std::isfinite(best)) return false;
    pivot_[j] = p;
    if (p != j) lu_.row(p).swap(lu_.row(j));
    largest = std::max(largest, best);
    if (!(best > 0.0)) return false;
    const double inv = 1.0 / lu_(j, j);
    for (int i = j + 1; i < n; ++i) lu_(i, j) *= inv;
    for (int c = j + 1; c < n; ++c) {
      const double v = lu_(j, c);
      if (v == 0.0) continue;
      for (int i = j + 1; i < n; ++i) lu_(i, c) -= lu_(i, j) * v;
    }
  }
  for (int j = 0; j < n; ++j) {
    if (!(std::abs(lu_(j, j)) > 1e-13 * largest)) return false;
  }
  return true;
}

void BvpRiccatiSolver::SmallLu::SolveVector(VecRef x) const {
  const int n = static_cast<int>(lu_.rows());
  for (int j = 0; j < n; ++j) {
    if (pivot_[j] != j) std::swap(x[j], x[pivot_[j]]);
  }
  for (int j = 0; j < n; ++j) {  // L (unit diagonal), column by column
    const double v = x[j];
    if (v == 0.0) continue;
    for (int i = j + 1; i < n; ++i) x[i] -= lu_(i, j) * v;
  }
  for (int j = n - 1; j >= 0; --j) {  // U
    x[j] /= lu_(j, j);
    const double v = x[j];
    if (v == 0.0) continue;
    for (int i = 0; i < j; ++i) x[i] -= lu_(i, j) * v;
  }
}

void BvpRiccatiSolver::SmallLu::SolveColumns(MatRef x) const {
  for (int c = 0; c < x.cols(); ++c) SolveVector(x.col(c));
}

BvpRiccatiSolver::BvpRiccatiSolver(const PmpResidual& pmp)
    : pmp_(pmp),
      nx_(pmp.ocp().nx()),
      nnu_(pmp.num_multipliers()),
      N_(pmp.intervals()),
      core_(pmp.size() - (pmp.free_final_time() ? 1 : 0)),
      free_time_(pmp.free_final_time()),
      euler_(pmp.scheme() == PmpResidual::Scheme::kEuler) {
  const int nx = nx_;
  terminal_.resize(nx + nnu_, 2 * nx + nnu_);
  K_.resize(2 * nx, 2 * nx);
  RpT_.resize(2 * nx, nnu_);
  rhs_.resize(2 * nx);
  lu_.resize(N_);
  S_.assign(N_ + 1, Mat(nx, nx));
  T_.assign(N_ + 1, Mat(nx, nnu_));
  Y_.assign(N_, Mat(2 * nx, nx));
  V_.assign(N_, Mat(2 * nx, nnu_));
  Rp_.assign(N_, Mat(2 * nx, nx));
  if (euler_) G_.assign(N_, Mat(nx, nx));
  W_.assign(N_ + 1, Mat(nx, nnu_));
  s_.assign(N_ + 1, Vec(nx));
  y_.assign(N_, Vec(2 * nx));
  a_.assign(N_ + 1, Vec(nx));
  if (free_time_) {
    time_column_.resize(core_);
    time_row_.resize(core_);
    w_.resize(core_);
  }
  core_d_.resize(core_);
}

bool BvpRiccatiSolver::Factorize() {
  const int nx = nx_, N = N_;
  // Terminal rows: Tx x_N + Tp p_N + Tnu nu = b_t, so p_N = S_N x_N + T_N nu + Tp^-1 b_t.
  pmp_.TerminalBlock(terminal_);
  if (!terminal_.allFinite()) return false;
  if (!terminal_lu_.Compute(terminal_.block(0, nx, nx, nx))) return false;
  S_[N] = -terminal_.topLeftCorner(nx, nx);
  terminal_lu_.SolveColumns(S_[N]);
  if (nnu_ > 0) {
    T_[N] = -terminal_.block(0, 2 * nx, nx, nnu_);
    terminal_lu_.SolveColumns(T_[N]);
  }
  psi_x_ = terminal_.bottomLeftCorner(nnu_, nx);

  for (int k = N - 1; k >= 0; --k) {
    const auto block_ = pmp_.IntervalBlock(k);
    if (!FiniteBlock(block_)) return false;
    // K = [R_x + R_p S_{k+1} | L_p] acting on (x_{k+1}, p_k).
    Rp_[k] = block_.rightCols(nx);
    if (euler_) {
      // Euler: R_x = (I; 0), L_p = (0; I), so K = [M 0; G I] with M = I + R_p,top S_{k+1},
      // G = R_p,bottom S_{k+1}: one nx x nx LU.
      K_.topLeftCorner(nx, nx).setIdentity();
      K_.topLeftCorner(nx, nx) += Rp_[k].topRows(nx).lazyProduct(S_[k + 1]);
      G_[k] = Rp_[k].bottomRows(nx).lazyProduct(S_[k + 1]);
      if (!lu_[k].Compute(K_.topLeftCorner(nx, nx))) return false;
    } else {
      K_.leftCols(nx) = block_.middleCols(2 * nx, nx);
      K_.leftCols(nx) += Rp_[k].lazyProduct(S_[k + 1]);
      K_.rightCols(nx) = block_.middleCols(nx, nx);
      if (!lu_[k].Compute(K_)) return false;
    }
    Y_[k] = block_.leftCols(nx);
    SolveK(k, Y_[k]);
    S_[k] = -Y_[k].bottomRows(nx);
    if (nnu_ > 0) {
      V_[k] = Rp_[k].lazyProduct(T_[k + 1]);
      SolveK(k, V_[k]);
      T_[k] = -V_[k].bottomRows(nx);
    }
    if (!FiniteBlock(S_[k])) return false;
  }
  // x_{k+1} = y_x - Y_x x_k - V_x nu from x_0 (which the initial rows fix): W_k = dx_k / dnu.
  if (nnu_ > 0) {
    W_[0].setZero();
    for (int k = 0; k < N; ++k) {
      W_[k + 1] = -V_[k].topRows(nx);
      W_[k + 1] -= Y_[k].topRows(nx).lazyProduct(W_[k]);
    }
    if (!nu_lu_.Compute(psi_x_.lazyProduct(W_[N]))) return false;
  }
  if (free_time_) {
    pmp_.TimeColumn(time_column_);
    pmp_.TimeRow(time_row_);
    SolveCore(time_column_, w_);
    border_ = -time_row_.dot(w_);
    const double scale = time_row_.cwiseAbs().maxCoeff() * w_.cwiseAbs().maxCoeff();
    if (!std::isfinite(border_) || !(std::abs(border_) > 1e-14 * scale)) return false;
  }
  return true;
}

void BvpRiccatiSolver::SolveK(int k, MatRef x) const {
  if (!euler_) {
    lu_[k].SolveColumns(x);
    return;
  }
  // [M 0; G I] (u; v) = (r; q): u = M^-1 r, v = q - G u.
  const int nx = nx_;
  lu_[k].SolveColumns(x.topRows(nx));
  x.bottomRows(nx) -= G_[k].lazyProduct(x.topRows(nx));
}

void BvpRiccatiSolver::SolveCore(ConstVecRef b, VecRef d) {
  const int nx = nx_, N = N_;
  s_[N] = b.segment(pmp_.IntervalRow(N), nx);
  terminal_lu_.SolveVector(s_[N]);
  for (int k = N - 1; k >= 0; --k) {
    y_[k] = b.segment(pmp_.IntervalRow(k), 2 * nx);
    y_[k] -= Rp_[k].lazyProduct(s_[k + 1]);
    SolveK(k, y_[k]);
    s_[k] = y_[k].tail(nx);
  }
  a_[0] = b.head(nx);
  for (int k = 0; k < N; ++k) {
    a_[k + 1] = y_[k].head(nx);
    a_[k + 1] -= Y_[k].topRows(nx).lazyProduct(a_[k]);
  }
  Vec dnu(nnu_);
  if (nnu_ > 0) {
    dnu = b.segment(pmp_.IntervalRow(N) + nx, nnu_);
    dnu -= psi_x_.lazyProduct(a_[N]);
    nu_lu_.SolveVector(dnu);
    d.segment(pmp_.NodeColumn(N + 1), nnu_) = dnu;
  }
  for (int k = 0; k <= N; ++k) {
    auto x = d.segment(pmp_.NodeColumn(k), nx);
    auto p = d.segment(pmp_.NodeColumn(k) + nx, nx);
    x = a_[k];
    if (nnu_ > 0) x += W_[k].lazyProduct(dnu);
    p = s_[k];
    p += S_[k].lazyProduct(x);
    if (nnu_ > 0) p += T_[k].lazyProduct(dnu);
  }
}

void BvpRiccatiSolver::ApplyInverse(ConstVecRef b, VecRef d) {
  if (!free_time_) {
    SolveCore(b, d);
    return;
  }
  // [J0 c; r^T 0] (d0, dT) = (b0, bT): d0 = J0^-1 b0 - w dT, dT = (bT - r . J0^-1 b0) / border.
  SolveCore(b.head(core_), core_d_);
  const double dT = (b[core_] - time_row_.dot(core_d_)) / border_;
  d.head(core_) = core_d_ - w_ * dT;
  d[core_] = dT;
}

void BvpRiccatiSolver::Multiply(ConstVecRef d, Vec& r) const {
  const int nx = nx_;
  r.resize(d.size());
  r.head(nx) = d.head(nx);  // the initial rows: the identity on x_0
  for (int k = 0; k < N_; ++k) {
    r.segment(pmp_.IntervalRow(k), 2 * nx).noalias() =
        pmp_.IntervalBlock(k) * d.segment(pmp_.NodeColumn(k), 4 * nx);
  }
  // (x_N, p_N, nu) are contiguous in z.
  r.segment(pmp_.IntervalRow(N_), nx + nnu_).noalias() =
      terminal_ * d.segment(pmp_.NodeColumn(N_), 2 * nx + nnu_);
  if (free_time_) {
    r.head(core_) += time_column_ * d[core_];
    r[core_] = time_row_.dot(d.head(core_));
  }
}

bool BvpRiccatiSolver::Solve(const Vec& b, Vec* d) {
  d->resize(b.size());
  ApplyInverse(b, *d);
  const double scale = kRelativeResidual * std::max(b.cwiseAbs().maxCoeff(), 1e-300);
  for (int refinement = 0;; ++refinement) {
    if (!d->allFinite()) return false;
    Multiply(*d, residual_);
    residual_ -= b;
    if (residual_.cwiseAbs().maxCoeff() <= scale) return true;
    if (refinement == 1) return false;
    correction_.resize(b.size());
    ApplyInverse(residual_, correction_);
    *d -= correction_;
  }
}

}  // namespace ocpb
