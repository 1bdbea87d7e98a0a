#include "transcriptions/single_shooting.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace ocpb {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

}  // namespace

SingleShootingNlp::SingleShootingNlp(const Ocp& ocp,
                                     const TranscriptionOptions& options,
                                     Integrator integrator)
    : ocp_(ocp),
      docp_(ocp, options.grid, integrator, options.terminal),
      nx_(ocp.nx()),
      nu_(ocp.nu()),
      N_(options.grid.intervals()) {
  if (const std::string off = ocp.GridOffHorizon(options.grid, Ocp::HorizonEnd::kNominal);
      !off.empty()) {
    throw std::invalid_argument("single-shooting: " + off);
  }
  if (nu_ < 1) throw std::invalid_argument("single-shooting: the problem has no controls");
  if (options.initial_guess && options.initial_guess->nu() != nu_) {
    throw std::invalid_argument("single-shooting: the initial guess has " +
                                std::to_string(options.initial_guess->nu()) +
                                " controls, the problem " + std::to_string(nu_));
  }
  std::string error;
  if (!options.scaling.IsValidFor(nx_, nu_, &error)) {
    throw std::invalid_argument("single-shooting: " + error);
  }
  objective_scale_ = options.scaling.objective;
  control_scale_ = options.scaling.control.size() == nu_ ? options.scaling.control : Vec::Ones(nu_);
  column_scale_ = control_scale_.replicate(N_, 1);
  const ControlSet& U = ocp.control_set();
  if (U.dimension() != 0 && U.dimension() != nu_) {
    throw std::invalid_argument("single-shooting: the control set's dimension is not nu");
  }

  // Bounds: the control set's bounding box at every interval.
  Vec lo = Vec::Constant(nu_, -kInfinity), hi = Vec::Constant(nu_, kInfinity);
  if (U.dimension() == nu_) U.BoundingBox(&lo, &hi);
  z_lower_ = lo.replicate(N_, 1).cwiseQuotient(column_scale_);
  z_upper_ = hi.replicate(N_, 1).cwiseQuotient(column_scale_);
  for (const ControlSet::Block& b : U.blocks()) {
    if (b.kind == ControlSet::Kind::kBall) balls_.push_back(b);
  }

  // Constraint rows and the Jacobian structure, group by group.
  const int n = num_variables();
  npsi_rows_ = options.terminal == TerminalMode::kHard ? ocp.num_terminal() : 0;
  nball_rows_ = static_cast<int>(balls_.size()) * N_;
  const int npath = ocp.num_path() * (N_ + 1);
  m_ = npsi_rows_ + nball_rows_ + npath;
  for (int i = 0; i < npsi_rows_; ++i) {
    for (int j = 0; j < n; ++j) {
      jac_rows_.push_back(i);
      jac_cols_.push_back(j);
    }
  }
  int row = npsi_rows_;
  for (int k = 0; k < N_; ++k) {
    for (const ControlSet::Block& b : balls_) {
      for (int j = 0; j < b.size; ++j) {
        jac_rows_.push_back(row);
        jac_cols_.push_back(k * nu_ + b.offset + j);
      }
      ++row;
    }
  }
  for (int k = 0; k <= N_; ++k) {
    const int cols = std::min(k + 1, N_) * nu_;
    for (int i = 0; i < ocp.num_path(); ++i) {
      for (int j = 0; j < cols; ++j) {
        jac_rows_.push_back(row);
        jac_cols_.push_back(j);
      }
      ++row;
    }
  }

  // Starting point: the guess on this grid, projected onto U.
  Mat U0 = options.initial_guess ? options.initial_guess->SampleIntervals(options.grid)
                                 : ocp.CheckedNominalControl().replicate(1, N_).eval();
  if (U.dimension() == nu_) {
    for (int k = 0; k < N_; ++k) U.Project(U0.col(k));
  }
  z0_ = Eigen::Map<const Vec>(U0.data(), U0.size()).cwiseQuotient(column_scale_);
}

void SingleShootingNlp::Bounds(Vec* z_lower, Vec* z_upper, Vec* g_lower, Vec* g_upper) const {
  *z_lower = z_lower_;
  *z_upper = z_upper_;
  g_lower->resize(m_);
  g_upper->resize(m_);
  g_lower->head(npsi_rows_).setZero();
  g_upper->head(npsi_rows_).setZero();
  for (int k = 0; k < N_; ++k) {
    for (size_t b = 0; b < balls_.size(); ++b) {
      const int row = ball_row() + k * static_cast<int>(balls_.size()) + static_cast<int>(b);
      (*g_lower)[row] = -kInfinity;
      (*g_upper)[row] = balls_[b].radius * balls_[b].radius;
    }
  }
  g_lower->tail(num_path_rows()).setConstant(-kInfinity);
  g_upper->tail(num_path_rows()).setZero();
}

Vec SingleShootingNlp::StartingPoint() const { return z0_; }

bool SingleShootingNlp::Prepare(ConstVecRef z) const {
  if (cache_.valid && cache_.z.size() == z.size() && cache_.z == z) return std::isfinite(cache_.J);
  cache_ = Cache();
  cache_.z = z;
  cache_.U = control_scale_.asDiagonal() * Eigen::Map<const Mat>(z.data(), nu_, N_);
  cache_.J = docp_.Simulate(cache_.U, &cache_.X);
  cache_.valid = true;
  return std::isfinite(cache_.J);
}

bool SingleShootingNlp::PrepareSteps() const {
  if (cache_.has_steps) return true;
  cache_.A.resize(N_);
  cache_.B.resize(N_);
  Vec ell_x, ell_u;
  for (int k = 0; k < N_; ++k) {
    StepJacobian(k, cache_.X.col(k), cache_.U.col(k), &cache_.A[k], &cache_.B[k], &ell_x, &ell_u);
    if (!cache_.A[k].allFinite() || !cache_.B[k].allFinite()) return false;
  }
  cache_.has_steps = true;
  return true;
}

bool SingleShootingNlp::Objective(ConstVecRef z, double* f) const {
  if (!Prepare(z)) return false;
  *f = objective_scale_ * cache_.J;
  return true;
}

bool SingleShootingNlp::Gradient(ConstVecRef z, VecRef grad) const {
  if (!Prepare(z)) return false;
  if (!cache_.has_gradient) {
    Mat Lambda;
    docp_.Adjoint(cache_.U, cache_.X, &Lambda, &cache_.G);
    cache_.has_gradient = true;
  }
  grad = objective_scale_ *
         Eigen::Map<const Vec>(cache_.G.data(), cache_.G.size()).cwiseProduct(column_scale_);
  return grad.allFinite();
}

bool SingleShootingNlp::Constraints(ConstVecRef z, VecRef g) const {
  if (!Prepare(z)) return false;
  const Mat& U = cache_.U;
  const Mat& X = cache_.X;
  if (npsi_rows_ > 0) ocp_.TerminalConstraints(X.col(N_), g.head(npsi_rows_));
  for (int k = 0; k < N_; ++k) {
    for (size_t b = 0; b < balls_.size(); ++b) {
      const int row = ball_row() + k * static_cast<int>(balls_.size()) + static_cast<int>(b);
      g[row] =
          (U.col(k).segment(balls_[b].offset, balls_[b].size) - balls_[b].center).squaredNorm();
    }
  }
  const int nc = ocp_.num_path();
  for (int k = 0; k <= N_ && nc > 0; ++k) {
    ocp_.PathConstraints(docp_.grid().t(k),
                         X.col(k),
                         U.col(std::min(k, N_ - 1)),
                         g.segment(path_row() + k * nc, nc));
  }
  return g.allFinite();
}

bool SingleShootingNlp::JacobianValues(ConstVecRef z, VecRef values) const {
  if (!Prepare(z)) return false;
  const int n = num_variables();
  const int nc = ocp_.num_path();
  if ((npsi_rows_ > 0 || nc > 0) && !PrepareSteps()) return false;
  const Mat& U = cache_.U;
  const Mat& X = cache_.X;
  int pos = 0;

  // Hard terminal rows: one backward matrix pass.
  if (npsi_rows_ > 0) {
    Vec psi(npsi_rows_);
    Mat Lambda(npsi_rows_, nx_);
    ocp_.TerminalConstraintsJacobian(X.col(N_), psi, Lambda);
    Mat jac(npsi_rows_, n);
    for (int k = N_ - 1; k >= 0; --k) {
      jac.middleCols(k * nu_, nu_) = Lambda * cache_.B[k];
      Lambda = Lambda * cache_.A[k];
    }
    for (int i = 0; i < npsi_rows_; ++i) {
      values.segment(pos, n) = jac.row(i).transpose().cwiseProduct(column_scale_);
      pos += n;
    }
  }

  // Ball rows: d/dv |v - c|^2 = 2 (v - c).
  for (int k = 0; k < N_; ++k) {
    for (const ControlSet::Block& b : balls_) {
      values.segment(pos, b.size) =
          2.0 * (U.col(k).segment(b.offset, b.size) - b.center)
                    .cwiseProduct(control_scale_.segment(b.offset, b.size));
      pos += b.size;
    }
  }

  // Path rows: forward sensitivities S_k = dx_k/dz (only the first k nu columns are nonzero).
  if (nc > 0) {
    Mat S = Mat::Zero(nx_, n);
    Vec c(nc);
    Mat cx(nc, nx_), cu(nc, nu_);
    for (int k = 0; k <= N_; ++k) {
      const int ku = std::min(k, N_ - 1);
      ocp_.PathConstraintsJacobian(docp_.grid().t(k), X.col(k), U.col(ku), c, cx, cu);
      const int cols = std::min(k + 1, N_) * nu_;
      Mat rows = cx * S.leftCols(cols);
      rows.middleCols(ku * nu_, nu_) += cu;
      for (int i = 0; i < nc; ++i) {
        values.segment(pos, cols) = rows.row(i).transpose().cwiseProduct(column_scale_.head(cols));
        pos += cols;
      }
      if (k < N_) {
        S.leftCols(k * nu_) = (cache_.A[k] * S.leftCols(k * nu_)).eval();
        S.middleCols(k * nu_, nu_) = cache_.B[k];
      }
    }
  }
  return values.allFinite();
}

void SingleShootingNlp::StepJacobian(
    int k, ConstVecRef x, ConstVecRef u, Mat* A, Mat* B, Vec* ell_x, Vec* ell_u) const {
  const double t = docp_.grid().t(k), h = docp_.grid().h(k);
  Vec f(nx_), Lx(nx_), Lu(nu_);
  Mat fx(nx_, nx_), fu(nx_, nu_);
  double L;
  const Mat I = Mat::Identity(nx_, nx_);
  if (docp_.integrator() == Integrator::kEuler) {
    ocp_.DynamicsJacobian(t, x, u, f, fx, fu);
    ocp_.RunningCostGradient(t, x, u, &L, Lx, Lu);
    *A = I + h * fx;
    *B = h * fu;
    *ell_x = h * Lx;
    *ell_u = h * Lu;
    return;
  }
  // RK4 as in DiscreteOcp: z_1 = x, k_i = f(t + c_i h, z_i, u), z_{i+1} = x + a_{i+1} h k_i,
  // x_next = x + h/6 sum w_i k_i, ell = h/6 sum w_i L(t + c_i h, z_i, u).
  const double c[4] = {0.0, 0.5, 0.5, 1.0};
  const double w[4] = {1.0, 2.0, 2.0, 1.0};
  Mat dz_dx = I, dz_du = Mat::Zero(nx_, nu_);
  Vec z = x;
  *A = I;
  *B = Mat::Zero(nx_, nu_);
  *ell_x = Vec::Zero(nx_);
  *ell_u = Vec::Zero(nu_);
  for (int i = 0; i < 4; ++i) {
    const double ti = t + c[i] * h;
    ocp_.DynamicsJacobian(ti, z, u, f, fx, fu);
    ocp_.RunningCostGradient(ti, z, u, &L, Lx, Lu);
    const Mat dk_dx = fx * dz_dx;
    const Mat dk_du = fx * dz_du + fu;
    *A += (h / 6.0) * w[i] * dk_dx;
    *B += (h / 6.0) * w[i] * dk_du;
    *ell_x += (h / 6.0) * w[i] * (dz_dx.transpose() * Lx);
    *ell_u += (h / 6.0) * w[i] * (dz_du.transpose() * Lx + Lu);
    if (i < 3) {
      const double a = c[i + 1] * h;
      z = x + a * f;
      dz_dx = I + a * dk_dx;
      dz_du = a * dk_du;
    }
  }
}

ControlTrajectory SingleShootingNlp::Controls(ConstVecRef z) const {
  return ControlTrajectory::PiecewiseConstant(
      docp_.grid(), control_scale_.asDiagonal() * Eigen::Map<const Mat>(z.data(), nu_, N_));
}

Mat SingleShootingNlp::SimulatedStates(ConstVecRef z) const {
  if (!Prepare(z)) return Mat();
  return cache_.X;
}

Mat SingleShootingNlp::Costates(ConstVecRef z, ConstVecRef lambda_scaled) const {
  if (lambda_scaled.size() != m_ || !Prepare(z)) return Mat();
  // Multipliers of the scaled problem (objective_scale J + lambda^T g) -> of J + lambda^T g.
  const Vec lambda = lambda_scaled / objective_scale_;
  const Mat& U = cache_.U;
  const Mat& X = cache_.X;
  const int nc = ocp_.num_path();
  Mat P(nx_, N_ + 1);
  double phi;
  Vec p(nx_);
  ocp_.TerminalObjectiveGradient(X.col(N_), docp_.terminal_mode(), &phi, p);
  if (npsi_rows_ > 0) {
    Vec psi(npsi_rows_);
    Mat psix(npsi_rows_, nx_);
    ocp_.TerminalConstraintsJacobian(X.col(N_), psi, psix);
    p += psix.transpose() * lambda.head(npsi_rows_);
  }
  Vec c(nc);
  Mat cx(nc, nx_), cu(nc, nu_);
  auto add_path = [&](int k) {
    if (nc == 0) return;
    ocp_.PathConstraintsJacobian(
        docp_.grid().t(k), X.col(k), U.col(std::min(k, N_ - 1)), c, cx, cu);
    p += cx.transpose() * lambda.segment(path_row() + k * nc, nc);
  };
  add_path(N_);
  P.col(N_) = p;
  Mat A, B;
  Vec ell_x, ell_u;
  for (int k = N_ - 1; k >= 0; --k) {
    StepJacobian(k, X.col(k), U.col(k), &A, &B, &ell_x, &ell_u);
    p = A.transpose() * p + ell_x;
    add_path(k);
    P.col(k) = p;
  }
  return P;
}

std::unique_ptr<TranscribedNlp> SingleShooting::Transcribe(
    const Ocp& ocp, const TranscriptionOptions& options) const {
  if (ocp.free_final_time()) {
    throw std::invalid_argument("single-shooting: problem '" + ocp.name() +
                                "' has a free final time, which single shooting does not take "
                                "(use a collocation transcription)");
  }
  return std::make_unique<SingleShootingNlp>(ocp, options, options.integrator);
}

}  // namespace ocpb
