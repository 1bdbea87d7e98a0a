#include "solvers/bvp_riccati_solver.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "solvers/all_finite.h"
#include "solvers/small_lu.h"

namespace ocpb {
namespace {

// C (r x c) += A (r x m) B (m x c), or -= with kSign = -1; column-major with leading dimensions
// lda, ldb, ldc. kR, kM, kC > 0 fix the sizes at compile time (the loops unroll).
template <int kR, int kM, int kC, int kSign = 1>
inline void RiccatiGemm(int r_runtime,
                        int m_runtime,
                        int c_runtime,
                        const double* __restrict A,
                        int lda,
                        const double* __restrict B,
                        int ldb,
                        double* __restrict C,
                        int ldc) {
  const int r = SmallDim<kR>(r_runtime), m = SmallDim<kM>(m_runtime), c = SmallDim<kC>(c_runtime);
  for (int j = 0; j < c; ++j) {
    double* cj = C + j * ldc;
    if constexpr (kR > 0) {
      // A column of C in registers (a local array the compiler need not reload).
      double acc[kR];
      for (int i = 0; i < kR; ++i) acc[i] = cj[i];
      for (int l = 0; l < m; ++l) {
        const double b = kSign * B[j * ldb + l];
        const double* al = A + l * lda;
        for (int i = 0; i < kR; ++i) acc[i] += al[i] * b;
      }
      for (int i = 0; i < kR; ++i) cj[i] = acc[i];
    } else {
      for (int l = 0; l < m; ++l) {
        const double b = kSign * B[j * ldb + l];
        const double* al = A + l * lda;
        for (int i = 0; i < r; ++i) cj[i] += al[i] * b;
      }
    }
  }
}

// The sweep for nx = kNx (kNx > 0: fixed at compile time; 0: pmp's nx at runtime). Matrices are
// stored column-major in flat arrays, one fixed-size slot per interval or node.
template <int kNx>
class RiccatiSweep final : public BvpRiccatiSolver::Sweep {
 public:
  static constexpr int kTwoNx = kNx > 0 ? 2 * kNx : 0;

  explicit RiccatiSweep(const PmpResidual& pmp)
      : pmp_(pmp),
        nx_(pmp.ocp().nx()),
        nnu_(pmp.num_multipliers()),
        N_(pmp.intervals()),
        core_(pmp.size() - (pmp.free_final_time() ? 1 : 0)),
        free_time_(pmp.free_final_time()),
        euler_(pmp.scheme() == PmpResidual::Scheme::kEuler),
        kb_(euler_ ? nx_ : 2 * nx_) {
    const size_t n = nx_, N = N_, nnu = nnu_, kb = kb_;
    terminal_.resize(nx_ + nnu_, 2 * nx_ + nnu_);
    lu_.resize(N * kb * kb);
    pivot_.resize(N * kb);
    if (euler_) G_.resize(N * n * n);
    Y_.resize(N * 2 * n * n);
    Rp_.resize(N * 2 * n * n);
    V_.resize(N * 2 * n * nnu);
    S_.resize((N + 1) * n * n);
    T_.resize((N + 1) * n * nnu);
    W_.resize((N + 1) * n * nnu);
    s_.resize((N + 1) * n);
    y_.resize(N * 2 * n);
    a_.resize((N + 1) * n);
    dnu_.resize(nnu);
    if (free_time_) {
      time_column_.resize(core_);
      time_row_.resize(core_);
      w_.resize(core_);
    }
    core_d_.resize(core_);
  }

  bool Factorize() override {
    const int n = SmallDim<kNx>(nx_), N = N_, nnu = nnu_, m = nx_ + nnu_;
    // Terminal rows: Tx x_N + Tp p_N + Tnu nu = b_t, so p_N = S_N x_N + T_N nu + Tp^-1 b_t.
    pmp_.TerminalBlock(terminal_);
    if (!terminal_.allFinite()) return false;
    const double* tb = terminal_.data();  // (n + nnu) x (2n + nnu), column-major
    if (!terminal_lu_.Compute(tb + n * m, n, m)) return false;
    double* SN = S(N);
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) SN[j * n + i] = -tb[j * m + i];
    }
    terminal_lu_.SolveColumns(SN, n, n);
    if (nnu > 0) {
      double* TN = T(N);
      for (int j = 0; j < nnu; ++j) {
        for (int i = 0; i < n; ++i) TN[j * n + i] = -tb[(2 * n + j) * m + i];
      }
      terminal_lu_.SolveColumns(TN, nnu, n);
    }
    psi_x_ = terminal_.bottomLeftCorner(nnu, n);

    const int width = 4 * n;  // row length of an interval block (row-major)
    for (int k = N - 1; k >= 0; --k) {
      // Not checked for finiteness here: a NaN or inf in the block reaches S_k (checked below)
      // or an LU pivot (checked), and Solve() checks d.
      const double* B = pmp_.IntervalBlock(k).data();
      double* Rp = RpOf(k);  // 2n x n
      for (int l = 0; l < n; ++l) {
        for (int i = 0; i < 2 * n; ++i) Rp[l * 2 * n + i] = B[i * width + 3 * n + l];
      }
      const double* S1 = S(k + 1);
      double* K = LuOf(k);
      double* Y = YOf(k);  // 2n x n: K^-1 L_x
      for (int j = 0; j < n; ++j) {
        for (int i = 0; i < 2 * n; ++i) Y[j * 2 * n + i] = B[i * width + j];
      }
      if (euler_) {
        // K = [M 0; G I], M = I + R_p,top S_{k+1}, G = R_p,bottom S_{k+1}.
        double* G = GOf(k);
        for (int j = 0; j < n; ++j) {
          for (int i = 0; i < n; ++i) {
            K[j * n + i] = i == j ? 1.0 : 0.0;
            G[j * n + i] = 0.0;
          }
        }
        RiccatiGemm<kNx, kNx, kNx>(n, n, n, Rp, 2 * n, S1, n, K, n);
        RiccatiGemm<kNx, kNx, kNx>(n, n, n, Rp + n, 2 * n, S1, n, G, n);
        if (!SmallLuFactor<kNx>(K, PivotOf(k), n)) return false;
      } else {
        // K = [R_x + R_p S_{k+1} | L_p] acting on (x_{k+1}, p_k).
        for (int j = 0; j < n; ++j) {
          for (int i = 0; i < 2 * n; ++i) {
            K[j * 2 * n + i] = B[i * width + 2 * n + j];
            K[(n + j) * 2 * n + i] = B[i * width + n + j];
          }
        }
        RiccatiGemm<kTwoNx, kNx, kNx>(2 * n, n, n, Rp, 2 * n, S1, n, K, 2 * n);
        if (!SmallLuFactor<kTwoNx>(K, PivotOf(k), 2 * n)) return false;
      }
      SolveK(k, Y, n);
      double* Sk = S(k);
      for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) Sk[j * n + i] = -Y[j * 2 * n + n + i];
      }
      if (nnu > 0) {
        double* V = VOf(k);  // 2n x nnu: K^-1 R_p T_{k+1}
        std::fill(V, V + 2 * n * nnu, 0.0);
        RiccatiGemm<kTwoNx, kNx, 0>(2 * n, n, nnu, Rp, 2 * n, T(k + 1), n, V, 2 * n);
        SolveK(k, V, nnu);
        double* Tk = T(k);
        for (int j = 0; j < nnu; ++j) {
          for (int i = 0; i < n; ++i) Tk[j * n + i] = -V[j * 2 * n + n + i];
        }
      }
      if (!AllFinite(Sk, n * n)) return false;
    }
    // x_{k+1} = y_x - Y_x x_k - V_x nu from x_0 (which the initial rows fix): W_k = dx_k / dnu.
    if (nnu > 0) {
      std::fill(W(0), W(0) + n * nnu, 0.0);
      for (int k = 0; k < N; ++k) {
        double* next = W(k + 1);
        const double* V = VOf(k);
        for (int j = 0; j < nnu; ++j) {
          for (int i = 0; i < n; ++i) next[j * n + i] = -V[j * 2 * n + i];
        }
        RiccatiGemm<kNx, kNx, 0, -1>(n, n, nnu, YOf(k), 2 * n, W(k), n, next, n);
      }
      Mat psi_w = psi_x_ * Eigen::Map<const Mat>(W(N), n, nnu);
      if (!nu_lu_.Compute(psi_w.data(), nnu, nnu)) return false;
    }
    if (free_time_) {
      pmp_.TimeColumn(time_column_);
      pmp_.TimeRow(time_row_);
      SolveCore(time_column_.data(), w_.data());
      border_ = -time_row_.dot(w_);
      const double scale = time_row_.cwiseAbs().maxCoeff() * w_.cwiseAbs().maxCoeff();
      if (!std::isfinite(border_) || !(std::abs(border_) > 1e-14 * scale)) return false;
    }
    return true;
  }

  bool Solve(const Vec& b, Vec* d) override {
    d->resize(b.size());
    ApplyInverse(b.data(), d->data());
    const double scale =
        BvpRiccatiSolver::kRelativeResidual * std::max(b.cwiseAbs().maxCoeff(), 1e-300);
    for (int refinement = 0;; ++refinement) {
      if (!d->allFinite()) return false;
      Multiply(d->data(), &residual_);
      residual_ -= b;
      if (residual_.cwiseAbs().maxCoeff() <= scale) return true;
      if (refinement == 1) return false;
      correction_.resize(b.size());
      ApplyInverse(residual_.data(), correction_.data());
      *d -= correction_;
    }
  }

 private:
  size_t Sq() const { return static_cast<size_t>(nx_) * nx_; }
  double* S(int k) { return S_.data() + k * Sq(); }
  double* T(int k) { return T_.data() + static_cast<size_t>(k) * nx_ * nnu_; }
  double* W(int k) { return W_.data() + static_cast<size_t>(k) * nx_ * nnu_; }
  double* LuOf(int k) { return lu_.data() + static_cast<size_t>(k) * kb_ * kb_; }
  const double* LuOf(int k) const { return lu_.data() + static_cast<size_t>(k) * kb_ * kb_; }
  int* PivotOf(int k) { return pivot_.data() + static_cast<size_t>(k) * kb_; }
  const int* PivotOf(int k) const { return pivot_.data() + static_cast<size_t>(k) * kb_; }
  double* GOf(int k) { return G_.data() + k * Sq(); }
  const double* GOf(int k) const { return G_.data() + k * Sq(); }
  double* YOf(int k) { return Y_.data() + 2 * k * Sq(); }
  double* RpOf(int k) { return Rp_.data() + 2 * k * Sq(); }
  double* VOf(int k) { return V_.data() + static_cast<size_t>(k) * 2 * nx_ * nnu_; }

  // x := K_k^-1 x for `columns` columns of 2 nx rows (leading dimension 2 nx): the LU of K_k,
  // or for Euler its block form [M 0; G I] (u; v) = (r; q): u = M^-1 r, v = q - G u.
  void SolveK(int k, double* x, int columns) const {
    const int n = SmallDim<kNx>(nx_);
    if (!euler_) {
      for (int c = 0; c < columns; ++c) {
        SmallLuSolve<kTwoNx>(LuOf(k), PivotOf(k), 2 * n, x + c * 2 * n);
      }
      return;
    }
    for (int c = 0; c < columns; ++c) SmallLuSolve<kNx>(LuOf(k), PivotOf(k), n, x + c * 2 * n);
    RiccatiGemm<kNx, kNx, 0, -1>(n, n, columns, GOf(k), n, x, 2 * n, x + n, 2 * n);
  }

  // The core system (no T row/column): d from b (both of length core_).
  void SolveCore(const double* b, double* d) {
    const int n = SmallDim<kNx>(nx_), N = N_, nnu = nnu_;
    double* sN = s_.data() + N * n;
    std::copy(b + pmp_.IntervalRow(N), b + pmp_.IntervalRow(N) + n, sN);
    terminal_lu_.Solve(sN);
    for (int k = N - 1; k >= 0; --k) {
      double* y = y_.data() + 2 * k * n;
      const double* bk = b + pmp_.IntervalRow(k);
      for (int i = 0; i < 2 * n; ++i) y[i] = bk[i];
      RiccatiGemm<kTwoNx, kNx, 1, -1>(
          2 * n, n, 1, RpOf(k), 2 * n, s_.data() + (k + 1) * n, n, y, 2 * n);
      SolveK(k, y, 1);
      std::copy(y + n, y + 2 * n, s_.data() + k * n);
    }
    std::copy(b, b + n, a_.data());
    for (int k = 0; k < N; ++k) {
      double* next = a_.data() + (k + 1) * n;
      std::copy(y_.data() + 2 * k * n, y_.data() + 2 * k * n + n, next);
      RiccatiGemm<kNx, kNx, 1, -1>(n, n, 1, YOf(k), 2 * n, a_.data() + k * n, n, next, n);
    }
    if (nnu > 0) {
      const double* bpsi = b + pmp_.IntervalRow(N) + n;
      for (int i = 0; i < nnu; ++i) {
        double v = bpsi[i];
        for (int j = 0; j < n; ++j) v -= psi_x_(i, j) * a_[N * n + j];
        dnu_[i] = v;
      }
      nu_lu_.Solve(dnu_.data());
      std::copy(dnu_.data(), dnu_.data() + nnu, d + pmp_.NodeColumn(N + 1));
    }
    for (int k = 0; k <= N; ++k) {
      double* x = d + pmp_.NodeColumn(k);
      double* p = x + n;
      std::copy(a_.data() + k * n, a_.data() + (k + 1) * n, x);
      if (nnu > 0) RiccatiGemm<kNx, 0, 1>(n, nnu, 1, W(k), n, dnu_.data(), nnu, x, n);
      std::copy(s_.data() + k * n, s_.data() + (k + 1) * n, p);
      RiccatiGemm<kNx, kNx, 1>(n, n, 1, S(k), n, x, n, p, n);
      if (nnu > 0) RiccatiGemm<kNx, 0, 1>(n, nnu, 1, T(k), n, dnu_.data(), nnu, p, n);
    }
  }

  // The whole system (the border of a free final time included), no checks.
  void ApplyInverse(const double* b, double* d) {
    if (!free_time_) {
      SolveCore(b, d);
      return;
    }
    // [J0 c; r^T 0] (d0, dT) = (b0, bT): d0 = J0^-1 b0 - w dT, dT = (bT - r . J0^-1 b0) / border.
    SolveCore(b, core_d_.data());
    const double dT = (b[core_] - time_row_.dot(core_d_)) / border_;
    for (int i = 0; i < core_; ++i) d[i] = core_d_[i] - w_[i] * dT;
    d[core_] = dT;
  }

  // r += d_c times column c of an interval block B (2 nx rows of width 4 nx, row-major).
  void MultiplyColumn(const double* B, int c, double dc, double* r) const {
    const int n = SmallDim<kNx>(nx_), width = 4 * n;
    for (int i = 0; i < 2 * n; ++i) r[i] += B[i * width + c] * dc;
  }

  // r = J d from the blocks (the factorized matrix; no sparse matrix needed).
  void Multiply(const double* d, Vec* r) const {
    const int n = SmallDim<kNx>(nx_), width = 4 * n;
    r->resize(pmp_.size());
    double* out = r->data();
    std::copy(d, d + n, out);  // the initial rows: the identity on x_0
    for (int k = 0; k < N_; ++k) {
      const double* B = pmp_.IntervalBlock(k).data();
      const double* dk = d + pmp_.NodeColumn(k);
      double* rk = out + pmp_.IntervalRow(k);
      // Column by column: 2 nx independent sums (a row-by-row dot product would chain 4 nx
      // dependent additions per row, latency-bound).
      for (int i = 0; i < 2 * n; ++i) rk[i] = 0.0;
      if (!euler_) {
        for (int c = 0; c < width; ++c) MultiplyColumn(B, c, dk[c], rk);
        continue;
      }
      // Euler's middle columns are the constants (0, I; I, 0) (PmpResidual): their terms,
      // added in the same column order, are d itself (1 * d exactly; a zero term would add
      // nothing but the sign of a zero).
      for (int c = 0; c < n; ++c) MultiplyColumn(B, c, dk[c], rk);
      for (int i = 0; i < n; ++i) {
        rk[i] += dk[2 * n + i];
        rk[n + i] += dk[n + i];
      }
      for (int c = 3 * n; c < width; ++c) MultiplyColumn(B, c, dk[c], rk);
    }
    // (x_N, p_N, nu) are contiguous in z.
    const int m = nx_ + nnu_;
    Eigen::Map<Vec>(out + pmp_.IntervalRow(N_), m).noalias() =
        terminal_ * Eigen::Map<const Vec>(d + pmp_.NodeColumn(N_), 2 * nx_ + nnu_);
    if (free_time_) {
      for (int i = 0; i < core_; ++i) out[i] += time_column_[i] * d[core_];
      out[core_] = time_row_.dot(Eigen::Map<const Vec>(d, core_));
    }
  }

  const PmpResidual& pmp_;
  int nx_, nnu_, N_, core_;
  bool free_time_;
  bool euler_;  // Scheme::kEuler: K_k = [M 0; G I], one nx x nx LU (see Factorize)
  int kb_;      // the order of K_k's LU: nx (Euler) or 2 nx
  Mat terminal_, psi_x_;
  SmallLu terminal_lu_;            // of the terminal costate rows' p_N block
  SmallLu nu_lu_;                  // of Psi_x W_N
  std::vector<double> lu_;         // per interval: the LU of K_k (kb x kb)
  std::vector<int> pivot_;         // per interval: its pivots
  std::vector<double> G_;          // Euler, per interval: R_p,bottom S_{k+1} (nx x nx)
  std::vector<double> Y_;          // per interval: K^-1 L_x (2nx x nx)
  std::vector<double> Rp_;         // per interval: R_p (2nx x nx)
  std::vector<double> V_;          // per interval: K^-1 R_p T_{k+1} (2nx x nnu)
  std::vector<double> S_, T_, W_;  // per node: p_k = S_k x_k + T_k dnu + s_k; x_k = a_k + W_k dnu
  std::vector<double> s_, y_, a_, dnu_;  // solve scratch: s, a per node, y per interval
  Vec time_column_, time_row_, w_, core_d_, residual_, correction_;
  double border_ = 0.0;  // -time_row_ . w_ (the (T, T) entry is zero)
};

std::unique_ptr<BvpRiccatiSolver::Sweep> MakeRiccatiSweep(const PmpResidual& pmp,
                                                          BvpRiccatiSolver::Kernel kernel) {
  if (kernel == BvpRiccatiSolver::Kernel::kFixedSize) {
    switch (pmp.ocp().nx()) {
      case 1:
        return std::make_unique<RiccatiSweep<1>>(pmp);
      case 2:
        return std::make_unique<RiccatiSweep<2>>(pmp);
      case 3:
        return std::make_unique<RiccatiSweep<3>>(pmp);
      case 4:
        return std::make_unique<RiccatiSweep<4>>(pmp);
      case 5:
        return std::make_unique<RiccatiSweep<5>>(pmp);
      case 6:
        return std::make_unique<RiccatiSweep<6>>(pmp);
      default:
        break;
    }
  }
  return std::make_unique<RiccatiSweep<0>>(pmp);
}

}  // namespace

BvpRiccatiSolver::BvpRiccatiSolver(const PmpResidual& pmp, Kernel kernel)
    : sweep_(pmp.free_initial_state() ? nullptr : MakeRiccatiSweep(pmp, kernel)) {}

BvpRiccatiSolver::~BvpRiccatiSolver() = default;

bool BvpRiccatiSolver::Factorize() { return sweep_ != nullptr && sweep_->Factorize(); }

bool BvpRiccatiSolver::Solve(const Vec& b, Vec* d) {
  return sweep_ != nullptr && sweep_->Solve(b, d);
}

}  // namespace ocpb
