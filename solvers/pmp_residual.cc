#include "solvers/pmp_residual.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "solvers/all_finite.h"
#include "solvers/small_dims.h"
#include "solvers/small_lu.h"

namespace ocpb {
namespace {

// Gx = f_x + f_u U_x, Gp = f_u U_p, Ex = H_xx + H_xu U_x, Ep = f_x^T + H_xu U_p: the node's
// blocks, column-major (H_xx, H_xu the blocks of the (nx+nu)^2 PointHessian `hess`), in plain
// loops at the compile-time sizes kNx, kNu when nonzero (solvers/small_dims.h): nx x nu x nx is
// far too small for Eigen's dynamic-size kernels, whose dispatch costs more than the arithmetic.
template <int kNx, int kNu>
void PmpNodeBlocks(int nx_runtime,
                   int nu_runtime,
                   const double* __restrict fx,
                   const double* __restrict fu,
                   const double* __restrict hess,
                   const double* __restrict Ux,
                   const double* __restrict Up,
                   double* __restrict Gx,
                   double* __restrict Gp,
                   double* __restrict Ex,
                   double* __restrict Ep) {
  const int nx = SmallDim<kNx>(nx_runtime), nu = SmallDim<kNu>(nu_runtime), nz = nx + nu;
  // Column by column, the products added in the order l = 0, 1, ... to every entry (each
  // entry's sum in the same order as one entry at a time), so the loop over the rows i runs
  // over contiguous columns and vectorizes.
  for (int j = 0; j < nx; ++j) {
    double* __restrict gx = Gx + j * nx;
    double* __restrict gp = Gp + j * nx;
    double* __restrict ex = Ex + j * nx;
    double* __restrict ep = Ep + j * nx;
    for (int i = 0; i < nx; ++i) {
      gx[i] = fx[j * nx + i];
      gp[i] = 0.0;
      ex[i] = hess[j * nz + i];
      ep[i] = fx[i * nx + j];
    }
    for (int l = 0; l < nu; ++l) {
      const double ux = Ux[j * nu + l], up = Up[j * nu + l];
      const double* fl = fu + l * nx;
      const double* hl = hess + (nx + l) * nz;
      for (int i = 0; i < nx; ++i) {
        gx[i] += fl[i] * ux;
        gp[i] += fl[i] * up;
        ex[i] += hl[i] * ux;
        ep[i] += hl[i] * up;
      }
    }
  }
}

// g = l + A^T p for the column-major nx x m matrix A (H_x = L_x + f_x^T p with m = nx, H_u =
// L_u + f_u^T p with m = nu): each entry summed in the order i = 0, 1, ..., at the compile-time
// sizes when nonzero (the runtime loops cost about three times the arithmetic).
template <int kNx, int kM>
void GradientPlusTransposedProduct(int nx_runtime,
                                   int m_runtime,
                                   const double* __restrict l,
                                   const double* __restrict A,
                                   const double* __restrict p,
                                   double* __restrict g) {
  const int nx = SmallDim<kNx>(nx_runtime), m = SmallDim<kM>(m_runtime);
  for (int j = 0; j < m; ++j) {
    double v = l[j];
    for (int i = 0; i < nx; ++i) v += A[j * nx + i] * p[i];
    g[j] = v;
  }
}

// Interval k's Jacobian entries that change (row-major rows of width 4 nx over x_k, p_k,
// x_{k+1}, p_{k+1}, from `rows`): the state rows' -h G_x - I and -h G_p, the costate rows' -h E_x
// and -h E_p - I (the middle columns: PmpResidual::EulerConstantEntries), at the compile-time
// kNx when nonzero, so the loops unroll.
template <int kNx>
void EulerIntervalEntries(int nx_runtime,
                          double h,
                          const double* __restrict Gx,
                          const double* __restrict Gp,
                          const double* __restrict Ex,
                          const double* __restrict Ep,
                          double* __restrict rows) {
  const int nx = SmallDim<kNx>(nx_runtime), W = 4 * nx;
  for (int i = 0; i < nx; ++i) {
    double* s = rows + i * W;         // state row i: columns x_k, p_k, x_{k+1}, p_{k+1}
    double* c = rows + (nx + i) * W;  // costate row i
    for (int j = 0; j < nx; ++j) {
      const double eye = i == j ? 1.0 : 0.0;
      const int ij = j * nx + i;  // (i, j) of the column-major node blocks
      s[j] = -h * Gx[ij] - eye;
      s[3 * nx + j] = -h * Gp[ij];
      c[j] = -h * Ex[ij];
      c[3 * nx + j] = -h * Ep[ij] - eye;
    }
  }
}

}  // namespace

PmpResidual::PmpResidual(const Ocp& ocp, const TimeGrid& grid, TerminalMode mode, Scheme scheme)
    : ocp_(ocp),
      grid_(grid),
      mode_(mode),
      scheme_(scheme),
      free_time_(ocp.free_final_time().has_value()),
      free_initial_(ocp.HasFreeInitialState()),
      initial_cost_(free_initial_ && ocp.HasInitialCost()),
      initial_bounds_(ocp.InitialNodeBounds()),
      nx_(ocp.nx()),
      nu_(ocp.nu()),
      npsi_(ocp.num_terminal()),
      nnu_(mode == TerminalMode::kHard ? ocp.num_terminal() : 0),
      N_(grid.intervals()),
      size_(2 * ocp.nx() * (grid.intervals() + 1) + nnu_ + (free_time_ ? 1 : 0)),
      derivative_(ocp) {
  CheckApplicable(ocp, grid);
  initial_gradient_.resize(nx_);
  initial_hessian_.setZero(nx_, nx_);
  if (free_time_) {
    s_.resize(N_ + 1);
    for (int k = 0; k <= N_; ++k) s_[k] = (grid.t(k) - grid.t0()) / (grid.tf() - grid.t0());
    s_[N_] = 1.0;
  }
  values_.resize(N_ + 1);
  for (NodeValues& n : values_) {
    n.u.resize(nu_);
    n.f.resize(nx_);
    n.Hx.resize(nx_);
    n.Lx.resize(nx_);
    n.Lu.resize(nu_);
    n.fx.resize(nx_, nx_);
    n.fu.resize(nx_, nu_);
  }
  for (NodeBlocks& n : blocks_) {
    n.Hu.resize(nu_);
    n.hess.resize(nx_ + nu_, nx_ + nu_);
    n.Ux.resize(nu_, nx_);
    n.Up.resize(nu_, nx_);
    n.Gx.resize(nx_, nx_);
    n.Gp.resize(nx_, nx_);
    n.Ex.resize(nx_, nx_);
    n.Ep.resize(nx_, nx_);
  }
  BuildStructure();
}

void PmpResidual::CheckApplicable(const Ocp& ocp, const TimeGrid& grid) {
  if (!ocp.HasHamiltonianMinimizer()) {
    throw std::invalid_argument("problem '" + ocp.name() +
                                "' has no closed-form Hamiltonian minimizer");
  }
  if (ocp.num_path() > 0) {
    throw std::invalid_argument(
        "problem '" + ocp.name() +
        "' has path constraints, which the indirect method does not handle");
  }
  if (const std::string off = ocp.GridOffHorizon(grid, Ocp::HorizonEnd::kAdmissible);
      !off.empty()) {
    throw std::invalid_argument(off);
  }
}

void PmpResidual::BuildStructure() {
  // The entries' layout (BuildSparseMatrix's order): the initial rows' identity, each interval's
  // dense block, the terminal blocks, then the free final time's column and row.
  const int nx = nx_;
  // A free initial state's rows are dense over (x_0, p_0) (the transversality rows read p_0 and
  // phi0's Hessian); a fixed one keeps the identity, so its structure is the same as before.
  initial_entries_ = free_initial_ ? 2 * nx * nx : nx;
  interval_entries_ = 8 * nx * nx;
  terminal_offset_ = initial_entries_ + N_ * interval_entries_;
  time_offset_ = terminal_offset_ + 2 * nx * nx + 2 * nx * nnu_;
  int entries = time_offset_;
  if (free_time_) {
    const int h_row_nodes = scheme_ == Scheme::kEuler ? N_ + 1 : 1;
    entries += 2 * nx * N_ + 2 * nx * h_row_nodes;
  }
  entries_.assign(entries, 0.0);
  if (scheme_ == Scheme::kEuler) EulerConstantEntries();
}

void PmpResidual::EulerConstantEntries() {
  // Interval k's rows over (x_k, p_k, x_{k+1}, p_{k+1}): the state rows are (-I - h G_x, 0, I,
  // -h G_p), the costate rows (-h E_x, I, 0, -I - h E_p); the middle columns never change.
  const int nx = nx_, W = 4 * nx_;
  for (int k = 0; k < N_; ++k) {
    double* base = entries_.data() + initial_entries_ + k * interval_entries_;
    for (int i = 0; i < nx; ++i) {
      double* s = base + i * W;
      double* c = base + (nx + i) * W;
      for (int j = 0; j < nx; ++j) {
        const double eye = i == j ? 1.0 : 0.0;
        s[nx + j] = 0.0;
        s[2 * nx + j] = eye;
        c[nx + j] = eye;
        c[2 * nx + j] = 0.0;
      }
    }
  }
}

void PmpResidual::BuildSparseMatrix() const {
  const int nx = nx_, W = 4 * nx_;
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(entries_.size());
  for (int i = 0; i < nx; ++i) {
    if (!free_initial_) {
      t.emplace_back(i, i, 0.0);
      continue;
    }
    for (int c = 0; c < 2 * nx; ++c) t.emplace_back(i, c, 0.0);
  }
  for (int k = 0; k < N_; ++k) {
    for (int r = 0; r < 2 * nx; ++r) {
      for (int c = 0; c < W; ++c) t.emplace_back(Row(k) + r, Col(k) + c, 0.0);
    }
  }
  const int rt = Row(N_);
  for (int i = 0; i < nx; ++i) {
    for (int c = 0; c < 2 * nx; ++c) t.emplace_back(rt + i, Col(N_) + c, 0.0);
  }
  for (int i = 0; i < nx; ++i) {
    for (int j = 0; j < nnu_; ++j) t.emplace_back(rt + i, Col(N_ + 1) + j, 0.0);
  }
  for (int i = 0; i < nnu_; ++i) {
    for (int j = 0; j < nx; ++j) t.emplace_back(rt + nx + i, Col(N_) + j, 0.0);
  }
  if (free_time_) {
    const int last = size_ - 1;
    for (int k = 0; k < N_; ++k) {
      for (int r = 0; r < 2 * nx; ++r) t.emplace_back(Row(k) + r, last, 0.0);
    }
    // The H row: node N's (x, p) for the trapezoid; every node's for Euler (the row sums H_k
    // over the intervals, each depending on x_k and p_{k+1}).
    for (int k = scheme_ == Scheme::kEuler ? 0 : N_; k <= N_; ++k) {
      for (int c = 0; c < 2 * nx; ++c) t.emplace_back(last, Col(k) + c, 0.0);
    }
  }
  if (t.size() != entries_.size()) {
    throw std::logic_error("PmpResidual: the sparse structure disagrees with the entries' layout");
  }
  jacobian_.resize(size_, size_);
  jacobian_.setFromTriplets(t.begin(), t.end());
  jacobian_.makeCompressed();
  value_index_.resize(t.size());
  const int* outer = jacobian_.outerIndexPtr();
  const int* inner = jacobian_.innerIndexPtr();
  for (size_t e = 0; e < t.size(); ++e) {
    const int c = t[e].col(), r = t[e].row();
    const int* pos = std::lower_bound(inner + outer[c], inner + outer[c + 1], r);
    value_index_[e] = static_cast<int>(pos - inner);
  }
}

Vec PmpResidual::Pack(const Mat& X, const Mat& P, const Vec& nu, double T) const {
  if (X.rows() != nx_ || X.cols() != N_ + 1 || P.rows() != nx_ || P.cols() != N_ + 1 ||
      nu.size() != nnu_) {
    throw std::invalid_argument("PmpResidual::Pack: X and P must be nx x (N+1), nu of size " +
                                std::to_string(nnu_));
  }
  Vec z(size_);
  for (int k = 0; k <= N_; ++k) {
    z.segment(Col(k), nx_) = X.col(k);
    z.segment(Col(k) + nx_, nx_) = P.col(k);
  }
  z.segment(Col(N_ + 1), nnu_) = nu;
  if (free_time_) z[size_ - 1] = T;
  return z;
}

void PmpResidual::Unpack(ConstVecRef z, Mat* X, Mat* P, Vec* nu) const {
  if (X) X->resize(nx_, N_ + 1);
  if (P) P->resize(nx_, N_ + 1);
  for (int k = 0; k <= N_; ++k) {
    if (X) X->col(k) = z.segment(Col(k), nx_);
    if (P) P->col(k) = z.segment(Col(k) + nx_, nx_);
  }
  if (nu) *nu = z.segment(Col(N_ + 1), nnu_);
}

double PmpResidual::FinalTime(ConstVecRef z) const {
  return free_time_ ? z[size_ - 1] : grid_.tf();
}

double PmpResidual::NodeTime(int k, double T) const {
  return free_time_ ? grid_.t0() + (T - grid_.t0()) * s_[k] : grid_.t(k);
}

TimeGrid PmpResidual::GridOf(ConstVecRef z) const {
  return free_time_ ? grid_.StretchedTo(FinalTime(z)) : grid_;
}

Mat PmpResidual::Controls(ConstVecRef z) const {
  const bool euler = scheme_ == Scheme::kEuler;
  Mat U(nu_, euler ? N_ : N_ + 1);
  Vec u(nu_);
  const double T = FinalTime(z);
  for (int k = 0; k < U.cols(); ++k) {
    // Euler pairs x_k with p_{k+1}; the trapezoid x_k with p_k.
    const int kp = euler ? k + 1 : k;
    ocp_.MinimizeHamiltonian(
        NodeTime(k, T), z.segment(Col(k), nx_), z.segment(Col(kp) + nx_, nx_), u);
    U.col(k) = u;
  }
  return U;
}

ControlTrajectory PmpResidual::ControlFunction(ConstVecRef z) const {
  return scheme_ == Scheme::kEuler ? ControlTrajectory::PiecewiseConstant(GridOf(z), Controls(z))
                                   : ControlTrajectory::PiecewiseLinear(GridOf(z), Controls(z));
}

bool PmpResidual::EvaluateNode(int k,
                               double t,
                               ConstVecRef x,
                               ConstVecRef p,
                               bool with_jacobian,
                               bool reuse,
                               NodeValues* n,
                               NodeBlocks* b) {
  const int nx = nx_, nu = nu_;
  failure_node_ = k;
  // The node's blocks in plain loops on their column-major storage (nx x nu x nx is too small
  // for Eigen's dynamic-size kernels, whose dispatch costs more than the arithmetic).
  const double* fx = n->fx.data();
  const double* fu = n->fu.data();
  const double* pv = p.data();
  if (!reuse) {
    ocp_.MinimizeHamiltonianWithGradients(t, x, p, n->u, n->f, n->fx, n->fu, &n->L, n->Lx, n->Lu);
    double* Hx = n->Hx.data();
    WithSmallDims(nx, nu, [&]<int kNx, int>() {
      GradientPlusTransposedProduct<kNx, kNx>(nx, nx, n->Lx.data(), fx, pv, Hx);
    });
    if (!(std::isfinite(n->L) && AllFinite(Hx, nx) && AllFinite(n->f.data(), nx) &&
          AllFinite(n->u.data(), nu))) {
      failure_ = Failure::kNonFinite;
      return false;
    }
  }
  if (!with_jacobian) return true;
  WithSmallDims(nx, nu, [&]<int kNx, int kNu>() {
    GradientPlusTransposedProduct<kNx, kNu>(nx, nu, n->Lu.data(), fu, pv, b->Hu.data());
  });
  const Vec no_mu;
  ocp_.PointHessian(t, x, n->u, 1.0, p, no_mu, b->hess);
  const int nz = nx + nu;
  const double* hess = b->hess.data();
  if (!(AllFinite(hess, nz * nz) && AllFinite(fx, nx * nx) && AllFinite(fu, nx * nu))) {
    failure_ = Failure::kNonFinite;
    return false;
  }
  if (!derivative_.Compute(n->u, b->Hu, n->fu, b->hess, b->Ux, b->Up)) {
    failure_ = Failure::kSingularMinimizer;
    return false;
  }
  WithSmallDims(nx, nu, [&]<int kNx, int kNu>() {
    PmpNodeBlocks<kNx, kNu>(nx,
                            nu,
                            fx,
                            fu,
                            hess,
                            b->Ux.data(),
                            b->Up.data(),
                            b->Gx.data(),
                            b->Gp.data(),
                            b->Ex.data(),
                            b->Ep.data());
  });
  return true;
}

bool PmpResidual::EvaluateTrapezoid(ConstVecRef z,
                                    VecRef F,
                                    double T,
                                    bool with_jacobian,
                                    bool reuse,
                                    double abandon_limit,
                                    double* squares,
                                    double* cost) {
  const int nx = nx_, W = 4 * nx_;
  double* v = entries_.data();
  auto put = [v](int e, double value) { v[e] = value; };
  const double duration = T - grid_.t0();
  double J = 0.0;
  if (!EvaluateNode(0,
                    NodeTime(0, T),
                    z.segment(0, nx),
                    z.segment(nx, nx),
                    with_jacobian,
                    reuse,
                    &values_[0],
                    &blocks_[0])) {
    return false;
  }
  for (int k = 0; k < N_; ++k) {
    const NodeValues& a = values_[k];
    NodeValues& b = values_[k + 1];
    const NodeBlocks& da = blocks_[k % 2];
    NodeBlocks& db = blocks_[(k + 1) % 2];
    const auto xa = z.segment(Col(k), nx), pa = z.segment(Col(k) + nx, nx);
    const auto xb = z.segment(Col(k + 1), nx), pb = z.segment(Col(k + 1) + nx, nx);
    if (!EvaluateNode(k + 1, NodeTime(k + 1, T), xb, pb, with_jacobian, reuse, &b, &db)) {
      return false;
    }
    const double h = free_time_ ? duration * (s_[k + 1] - s_[k]) : grid_.h(k), hh = 0.5 * h;
    F.segment(Row(k), nx) = xb - xa - hh * (a.f + b.f);
    F.segment(Row(k) + nx, nx) = pb - pa + hh * (a.Hx + b.Hx);
    J += hh * (a.L + b.L);
    *squares += F.segment(Row(k), 2 * nx).squaredNorm();
    if (*squares > abandon_limit) return Abandon(k);
    if (!with_jacobian) continue;
    const int base = initial_entries_ + k * interval_entries_;
    for (int i = 0; i < nx; ++i) {
      const int s = base + i * W;         // state row i
      const int c = base + (nx + i) * W;  // costate row i
      for (int j = 0; j < nx; ++j) {
        const double eye = i == j ? 1.0 : 0.0;
        put(s + j, -hh * da.Gx(i, j) - eye);
        put(s + nx + j, -hh * da.Gp(i, j));
        put(s + 2 * nx + j, -hh * db.Gx(i, j) + eye);
        put(s + 3 * nx + j, -hh * db.Gp(i, j));
        put(c + j, hh * da.Ex(i, j));
        put(c + nx + j, hh * da.Ep(i, j) - eye);
        put(c + 2 * nx + j, hh * db.Ex(i, j));
        put(c + 3 * nx + j, hh * db.Ep(i, j) + eye);
      }
    }
    if (free_time_) {
      // d/dT of h_k/2 (...) with h_k = (T - t0) ds_k; f, H_x do not depend on t (autonomous).
      const double hds = 0.5 * (s_[k + 1] - s_[k]);
      const int e = time_offset_ + 2 * nx * k;
      for (int i = 0; i < nx; ++i) {
        put(e + i, -hds * (a.f[i] + b.f[i]));
        put(e + nx + i, hds * (a.Hx[i] + b.Hx[i]));
      }
    }
  }

  *cost = J;
  return true;
}

bool PmpResidual::EvaluateEuler(ConstVecRef z,
                                VecRef F,
                                double T,
                                bool with_jacobian,
                                bool reuse,
                                double abandon_limit,
                                double* squares,
                                double* cost) {
  const int nx = nx_;
  double* v = entries_.data();
  auto put = [v](int e, double value) { v[e] = value; };
  const double duration = T - grid_.t0();
  double J = 0.0, dJdT = 0.0;
  NodeBlocks& d = blocks_[0];
  const double* zd = z.data();
  double* Fd = F.data();
  for (int k = 0; k < N_; ++k) {
    const double* xa = zd + Col(k);
    const double* pa = xa + nx;
    const double* xb = zd + Col(k + 1);
    const double* pb = xb + nx;
    // u_k = u*(t_k, x_k, p_{k+1}): the node evaluation with the next costate.
    NodeValues& a = values_[k];
    if (!EvaluateNode(k,
                      NodeTime(k, T),
                      z.segment(Col(k), nx),
                      z.segment(Col(k + 1) + nx, nx),
                      with_jacobian,
                      reuse,
                      &a,
                      &d)) {
      return false;
    }
    const double ds = free_time_ ? s_[k + 1] - s_[k] : 0.0;
    const double h = free_time_ ? duration * ds : grid_.h(k);
    double* Fs = Fd + Row(k);
    double* Fc = Fs + nx;
    const double* f = a.f.data();
    const double* Hx = a.Hx.data();
    double pf = 0.0, sq = 0.0;
    for (int i = 0; i < nx; ++i) {
      Fs[i] = xb[i] - xa[i] - h * f[i];
      Fc[i] = pa[i] - pb[i] - h * Hx[i];
      pf += pb[i] * f[i];
      sq += Fs[i] * Fs[i] + Fc[i] * Fc[i];
    }
    J += h * a.L;
    if (free_time_) dJdT += ds * (pf + a.L);
    *squares += sq;
    if (*squares > abandon_limit) return Abandon(k);
    if (!with_jacobian) continue;
    double* rows = v + initial_entries_ + k * interval_entries_;
    WithSmallDims(nx, nu_, [&]<int kNx, int>() {
      EulerIntervalEntries<kNx>(nx, h, d.Gx.data(), d.Gp.data(), d.Ex.data(), d.Ep.data(), rows);
    });
    if (free_time_) {
      // d/dT of h_k (...) with h_k = (T - t0) ds_k (autonomous: f, H_x do not depend on t).
      const int e = time_offset_ + 2 * nx * k;
      for (int i = 0; i < nx; ++i) {
        put(e + i, -ds * a.f[i]);
        put(e + nx + i, -ds * a.Hx[i]);
      }
      // The H row: d(ds_k H_k)/dx_k = ds_k (H_x + U_x^T H_u), d/dp_{k+1} = ds_k (f + U_p^T H_u)
      // (H_u = 0 at an interior u*; kept for exactness on the active set).
      const int row = time_offset_ + 2 * nx * N_;
      const Vec dx = a.Hx + d.Ux.transpose() * d.Hu;
      const Vec dp = a.f + d.Up.transpose() * d.Hu;
      for (int j = 0; j < nx; ++j) {
        put(row + 2 * nx * k + j, ds * dx[j]);
        put(row + 2 * nx * (k + 1) + nx + j, ds * dp[j]);
      }
    }
  }
  if (free_time_) {
    F[size_ - 1] = dJdT;
    if (with_jacobian) {
      // Columns the sum does not touch (p_0, x_N) stay structural zeros.
      const int row = time_offset_ + 2 * nx * N_;
      for (int j = 0; j < nx; ++j) {
        put(row + nx + j, 0.0);
        put(row + 2 * nx * N_ + j, 0.0);
      }
    }
  }
  *cost = J;
  return true;
}

const Eigen::SparseMatrix<double>& PmpResidual::jacobian() const {
  if (value_index_.empty()) BuildSparseMatrix();
  if (jacobian_stale_) {
    double* v = jacobian_.valuePtr();
    for (size_t e = 0; e < entries_.size(); ++e) v[value_index_[e]] = entries_[e];
    jacobian_stale_ = false;
  }
  return jacobian_;
}

bool PmpResidual::IsLastEvaluatedPoint(ConstVecRef z) const {
  return values_valid_ && z.size() == evaluated_z_.size() &&
         std::memcmp(z.data(), evaluated_z_.data(), sizeof(double) * z.size()) == 0;
}

bool PmpResidual::Abandon(int k) {
  failure_ = Failure::kAbandoned;
  failure_node_ = k;
  return false;
}

bool PmpResidual::EvaluateInitialRows(ConstVecRef z, VecRef F, bool with_jacobian, double* J) {
  const int nx = nx_;
  double* v = entries_.data();
  if (!free_initial_) {
    F.head(nx) = z.head(nx) - ocp_.x0();
    if (with_jacobian) {
      for (int i = 0; i < nx; ++i) v[i] = 1.0;
    }
    return true;
  }
  // Row i of a free component: x_0,i - clip(x_0,i - (p_0,i + dphi0/dx_0,i), lo_i, hi_i), the
  // transversality condition p(t0) = -grad phi0 where the bound is inactive and x_0,i = the
  // bound where it is active (the projection's natural residual; semismooth as u*'s clipping).
  const auto x0 = z.head(nx);
  const auto p0 = z.segment(nx, nx);
  initial_gradient_.setZero(nx);
  if (initial_cost_) {
    double phi0 = 0.0;
    ocp_.InitialCostGradient(x0, &phi0, initial_gradient_);
    *J += phi0;
    if (with_jacobian) ocp_.InitialCostHessian(x0, 1.0, initial_hessian_);
  }
  if (with_jacobian) {
    std::fill(v, v + initial_entries_, 0.0);
    if (!initial_cost_) initial_hessian_.setZero(nx, nx);
  }
  const Vec& lo = initial_bounds_.lower;
  const Vec& hi = initial_bounds_.upper;
  for (int i = 0; i < nx; ++i) {
    double* row = v + 2 * nx * i;  // columns x_0, then p_0
    if (!(lo[i] < hi[i])) {        // fixed
      F[i] = x0[i] - lo[i];
      if (with_jacobian) row[i] = 1.0;
      continue;
    }
    const double r = p0[i] + initial_gradient_[i];
    const double y = x0[i] - r;
    if (y < lo[i] || y > hi[i]) {  // the bound is active
      F[i] = x0[i] - (y < lo[i] ? lo[i] : hi[i]);
      if (with_jacobian) row[i] = 1.0;
      continue;
    }
    F[i] = r;
    if (with_jacobian) {
      for (int j = 0; j < nx; ++j) row[j] = initial_hessian_(i, j);
      row[nx + i] = 1.0;
    }
  }
  if (!(F.head(nx).allFinite() && (!with_jacobian || initial_hessian_.allFinite()))) {
    failure_ = Failure::kNonFinite;
    failure_node_ = 0;
    return false;
  }
  return true;
}

bool PmpResidual::Evaluate(
    ConstVecRef z, VecRef F, double* cost, bool with_jacobian, double abandon_above) {
  const int nx = nx_;
  const bool reuse = with_jacobian && IsLastEvaluatedPoint(z);
  values_valid_ = false;  // until this evaluation succeeds
  if (with_jacobian) jacobian_stale_ = true;
  failure_ = Failure::kNone;
  failure_node_ = -1;
  double* v = entries_.data();
  auto put = [v](int e, double value) { v[e] = value; };

  double J = 0.0, initial_cost = 0.0;
  if (!EvaluateInitialRows(z, F, with_jacobian, &initial_cost)) return false;
  const double T = FinalTime(z);
  if (free_time_ && !(T > grid_.t0() && ocp_.AdmitsFinalTime(T))) {
    failure_ = Failure::kBadFinalTime;
    failure_node_ = N_ + 1;
    return false;
  }
  // NaN never exceeds the limit: a non-finite residual fails below, as before. An evaluation
  // with the Jacobian is never abandoned: a half-written Jacobian would be left behind.
  const double abandon_limit = with_jacobian ? std::numeric_limits<double>::infinity()
                                             : abandon_above * (1.0 + kAbandonMargin);
  double squares = F.head(nx).squaredNorm();
  const bool ok =
      scheme_ == Scheme::kEuler
          ? EvaluateEuler(z, F, T, with_jacobian, reuse, abandon_limit, &squares, &J)
          : EvaluateTrapezoid(z, F, T, with_jacobian, reuse, abandon_limit, &squares, &J);
  if (!ok) return false;
  J += initial_cost;

  // Terminal rows.
  failure_node_ = N_ + 1;
  const auto xN = z.segment(Col(N_), nx), pN = z.segment(Col(N_) + nx, nx);
  const int rt = Row(N_);
  const bool hard = nnu_ > 0;
  Vec grad(nx);
  Mat hess(nx, nx);
  Mat psix(npsi_, nx);
  Vec psi(npsi_);
  double terminal = 0.0;
  if (!hard) {
    ocp_.TerminalObjectiveGradient(xN, mode_, &terminal, grad);
    F.segment(rt, nx) = pN - grad;
    if (with_jacobian) {
      if (mode_ == TerminalMode::kPenalty && npsi_ > 0) {
        ocp_.TerminalConstraintsJacobian(xN, psi, psix);
        const Vec w = ocp_.terminal_weights();
        ocp_.TerminalHessian(xN, 1.0, 2.0 * w.cwiseProduct(psi), hess);
        hess.noalias() += 2.0 * psix.transpose() * w.asDiagonal() * psix;
      } else {
        ocp_.TerminalHessian(xN, 1.0, Vec::Zero(npsi_), hess);
      }
    }
  } else {
    const auto nu = z.segment(Col(N_ + 1), nnu_);
    ocp_.TerminalCostGradient(xN, &terminal, grad);
    ocp_.TerminalConstraintsJacobian(xN, psi, psix);
    F.segment(rt, nx) = pN - grad - psix.transpose() * nu;
    F.segment(rt + nx, nnu_) = psi;
    if (with_jacobian) ocp_.TerminalHessian(xN, 1.0, nu, hess);
  }
  J += terminal;
  if (with_jacobian) {
    if (!hess.allFinite() || !psix.allFinite()) {
      failure_ = Failure::kNonFinite;
      return false;
    }
    const int T = terminal_offset_;
    for (int i = 0; i < nx; ++i) {
      for (int j = 0; j < nx; ++j) {
        put(T + i * 2 * nx + j, -hess(i, j));
        put(T + i * 2 * nx + nx + j, i == j ? 1.0 : 0.0);
      }
    }
    const int Tnu = T + 2 * nx * nx;
    for (int i = 0; i < nx; ++i) {
      for (int j = 0; j < nnu_; ++j) put(Tnu + i * nnu_ + j, -psix(j, i));
    }
    const int Tpsi = Tnu + nx * nnu_;
    for (int i = 0; i < nnu_; ++i) {
      for (int j = 0; j < nx; ++j) put(Tpsi + i * nx + j, psix(i, j));
    }
  }
  if (free_time_ && scheme_ == Scheme::kTrapezoid) {
    // H(t_N) = p_N^T f_N + L_N at u_N = u*(t_N, x_N, p_N): the node N scratch of the loop.
    const NodeValues& n = values_[N_];
    const NodeBlocks& d = blocks_[N_ % 2];
    F[size_ - 1] = pN.dot(n.f) + n.L;
    if (with_jacobian) {
      const int e = time_offset_ + 2 * nx * N_;
      const Vec dx = n.Hx + d.Ux.transpose() * d.Hu;
      const Vec dp = n.f + d.Up.transpose() * d.Hu;
      for (int j = 0; j < nx; ++j) {
        put(e + j, dx[j]);
        put(e + nx + j, dp[j]);
      }
    }
  }
  if (cost) *cost = J;
  if (!F.allFinite() || !std::isfinite(J)) {
    failure_ = Failure::kNonFinite;
    return false;
  }
  failure_node_ = -1;
  if (!reuse) evaluated_z_ = z;
  values_valid_ = true;
  return true;
}

Eigen::Map<const PmpResidual::RowMajorMat> PmpResidual::IntervalBlock(int k) const {
  return Eigen::Map<const RowMajorMat>(
      entries_.data() + initial_entries_ + k * interval_entries_, 2 * nx_, 4 * nx_);
}

void PmpResidual::TerminalBlock(MatRef block) const {
  const int nx = nx_;
  const double* v = entries_.data();
  block.setZero();
  const int T = terminal_offset_;
  for (int i = 0; i < nx; ++i) {
    for (int j = 0; j < 2 * nx; ++j) block(i, j) = v[T + i * 2 * nx + j];
  }
  const int Tnu = T + 2 * nx * nx;
  for (int i = 0; i < nx; ++i) {
    for (int j = 0; j < nnu_; ++j) block(i, 2 * nx + j) = v[Tnu + i * nnu_ + j];
  }
  const int Tpsi = Tnu + nx * nnu_;
  for (int i = 0; i < nnu_; ++i) {
    for (int j = 0; j < nx; ++j) block(nx + i, j) = v[Tpsi + i * nx + j];
  }
}

void PmpResidual::TimeColumn(VecRef column) const {
  const double* v = entries_.data();
  column.setZero();
  for (int k = 0; k < N_; ++k) {
    for (int r = 0; r < 2 * nx_; ++r) {
      column[Row(k) + r] = v[time_offset_ + 2 * nx_ * k + r];
    }
  }
}

void PmpResidual::TimeRow(VecRef row) const {
  const double* v = entries_.data();
  row.setZero();
  const int e = time_offset_ + 2 * nx_ * N_;
  const int first = scheme_ == Scheme::kEuler ? 0 : N_;
  for (int k = first; k <= N_; ++k) {
    for (int c = 0; c < 2 * nx_; ++c) {
      row[Col(k) + c] = v[e + 2 * nx_ * (k - first) + c];
    }
  }
}

std::string PmpResidual::FailureMessage() const {
  const std::string where =
      failure_node_ == N_ + 1 ? "the terminal rows" : "node " + std::to_string(failure_node_);
  switch (failure_) {
    case Failure::kNone:
      return "";
    case Failure::kNonFinite:
      return "NaN/inf in the residual or its derivatives at " + where;
    case Failure::kBadFinalTime:
      return "the free final time is not finite, not after t0, or outside its bounds";
    case Failure::kAbandoned:
      return "the residual's sum of squares exceeded the caller's bound at " + where;
    case Failure::kSingularMinimizer:
      return "the Hamiltonian's reduced Hessian in u is singular at " + where +
             " (u* is not differentiable there: H not strictly convex in u?)";
  }
  return "";
}

}  // namespace ocpb
