#include "solvers/riccati_kkt.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "solvers/small_dims.h"
#include "solvers/small_lu.h"  // SmallDim

namespace ocpb {

namespace {

// Plain-loop kernels on column-major storage with leading dimensions. The stage blocks are a
// few rows and columns (nx + nu ~ 2..12): Eigen's dynamic-size products and triangular solves
// spend more in dispatch, blocking and temporaries than in the arithmetic there, so the
// recursion uses these, writing into the solver's workspace.

// C (m x n) = beta C + alpha A^T B, A: k x m, B: k x n. beta == 0 does not read C.
template <int kM = 0, int kN = 0, int kK = 0>
void GemmTN(int m_runtime,
            int n_runtime,
            int k_runtime,
            double alpha,
            const double* A,
            int lda,
            const double* B,
            int ldb,
            double beta,
            double* C,
            int ldc) {
  const int m = SmallDim<kM>(m_runtime), n = SmallDim<kN>(n_runtime), k = SmallDim<kK>(k_runtime);
  for (int j = 0; j < n; ++j) {
    const double* b = B + static_cast<long>(j) * ldb;
    double* c = C + static_cast<long>(j) * ldc;
    for (int i = 0; i < m; ++i) {
      const double* a = A + static_cast<long>(i) * lda;
      double s = 0.0;
      for (int l = 0; l < k; ++l) s += a[l] * b[l];
      c[i] = beta == 0.0 ? alpha * s : beta * c[i] + alpha * s;
    }
  }
}

// C (m x n) = beta C + alpha A B, A: m x k, B: k x n. beta == 0 does not read C.
template <int kM = 0, int kN = 0, int kK = 0>
void GemmNN(int m_runtime,
            int n_runtime,
            int k_runtime,
            double alpha,
            const double* A,
            int lda,
            const double* B,
            int ldb,
            double beta,
            double* C,
            int ldc) {
  const int m = SmallDim<kM>(m_runtime), n = SmallDim<kN>(n_runtime), k = SmallDim<kK>(k_runtime);
  for (int j = 0; j < n; ++j) {
    double* c = C + static_cast<long>(j) * ldc;
    if (beta == 0.0) {
      for (int i = 0; i < m; ++i) c[i] = 0.0;
    } else if (beta != 1.0) {
      for (int i = 0; i < m; ++i) c[i] *= beta;
    }
    const double* b = B + static_cast<long>(j) * ldb;
    for (int l = 0; l < k; ++l) {
      const double t = alpha * b[l];
      const double* a = A + static_cast<long>(l) * lda;
      for (int i = 0; i < m; ++i) c[i] += t * a[i];
    }
  }
}

// Cholesky factorization a = L L^T in place of the n x n matrix `a`: its lower triangle, diagonal
// included, is read and overwritten with L; the strict upper triangle is neither read nor
// written. False when a pivot is not positive or not finite (a is then partly overwritten).
// kN > 0 fixes n at compile time (small_lu.h's SmallDim), as in the kernels above.
template <int kN = 0>
bool CholeskyInPlace(double* a, int n_runtime) {
  const int n = SmallDim<kN>(n_runtime);
  for (int j = 0; j < n; ++j) {
    double* cj = a + static_cast<long>(j) * n;
    double d = cj[j];
    for (int l = 0; l < j; ++l)
      d -= a[j + static_cast<long>(l) * n] * a[j + static_cast<long>(l) * n];
    if (!(d > 0.0) || !std::isfinite(d)) return false;
    d = std::sqrt(d);
    cj[j] = d;
    for (int i = j + 1; i < n; ++i) {
      double s = cj[i];
      for (int l = 0; l < j; ++l) {
        s -= a[i + static_cast<long>(l) * n] * a[j + static_cast<long>(l) * n];
      }
      cj[i] = s / d;
    }
  }
  return true;
}

// X (n x m, leading dimension ldx) <- -(L L^T)^-1 X for the Cholesky factor in `l` (n x n).
template <int kN = 0, int kM = 0>
void CholeskySolveNegated(const double* l, int n_runtime, double* X, int m_runtime, int ldx) {
  const int n = SmallDim<kN>(n_runtime), m = SmallDim<kM>(m_runtime);
  for (int c = 0; c < m; ++c) {
    double* x = X + static_cast<long>(c) * ldx;
    for (int i = 0; i < n; ++i) {  // L y = x
      double s = x[i];
      for (int j = 0; j < i; ++j) s -= l[i + static_cast<long>(j) * n] * x[j];
      x[i] = s / l[i + static_cast<long>(i) * n];
    }
    for (int i = n - 1; i >= 0; --i) {  // L^T z = y
      double s = x[i];
      for (int j = i + 1; j < n; ++j) s -= l[j + static_cast<long>(i) * n] * x[j];
      x[i] = s / l[i + static_cast<long>(i) * n];
    }
    for (int i = 0; i < n; ++i) x[i] = -x[i];
  }
}

// The stage kernels' compile-time sizes (solvers/small_dims.h): nx in 1..8 and nu in 1..4, the
// registered problems' sizes (robot-arm's 7 and 4 with its free-time scaling included), a wider
// range than the Newton polish's.
template <class F>
bool WithStageDims(int nx, int nu, F&& f) {
  return WithDimsUpTo<8, 4>(nx, nu, f);
}

// Ruiz's equilibration of a symmetric matrix: d with every row of D K D of max-norm near 1 (ten
// passes; rows of zeros keep d = 1). D K D has K's inertia (Sylvester), and a zero test on its
// eigenvalues is scale-free where K's entries span many orders of magnitude.
void Equilibrate(const Mat& K, Vec* d, Vec* scratch) {
  const int n = static_cast<int>(K.rows());
  d->setOnes(n);
  scratch->resize(n);
  for (int pass = 0; pass < 10; ++pass) {
    for (int i = 0; i < n; ++i) {
      double r = 0.0;
      for (int j = 0; j < n; ++j) r = std::max(r, std::abs(K(i, j)) * (*d)[j]);
      (*scratch)[i] = r * (*d)[i];
    }
    for (int i = 0; i < n; ++i) {
      if ((*scratch)[i] > 0.0) (*d)[i] /= std::sqrt((*scratch)[i]);
    }
  }
}

}  // namespace

// One stage of the backward recursion: V_k from V_{k+1}, and the factors of u_k. kNx, kNu > 0
// fix nx = nx_{k+1} and nu at compile time (the interior stages); 0 takes them at run time.
// False (failed_stage_ set) when the inertia is wrong.
template <int kNx, int kNu>
bool RiccatiSolver::BackwardStage(const RiccatiStage& s, int k, double dw, int npsi) {
  const int nx = SmallDim<kNx>(static_cast<int>(s.A.cols()));
  const int nu = SmallDim<kNu>(static_cast<int>(s.B.cols()));
  const int nn = SmallDim<kNx>(static_cast<int>(s.A.rows()));  // nx_{k+1}
  const int nw = nx + nu;
  const ValueFunction& vn = values_[k + 1];
  const double* Q = s.Q.data();

  // P [A B] and P b + p.
  PW_.resize(nn, nw);
  GemmNN<kNx, kNx, kNx>(nn, nx, nn, 1.0, vn.P.data(), nn, s.A.data(), nn, 0.0, PW_.data(), nn);
  GemmNN<kNx, kNu, kNx>(
      nn, nu, nn, 1.0, vn.P.data(), nn, s.B.data(), nn, 0.0, PW_.data() + nn * nx, nn);
  Pbp_ = vn.p;
  GemmNN<kNx, 1, kNx>(nn, 1, nn, 1.0, vn.P.data(), nn, s.b.data(), nn, 1.0, Pbp_.data(), nn);
  // H = Q + [A B]^T P [A B] (+ dw I), the blocks that are used.
  Hxx_.resize(nx, nx);
  Hux_.resize(nu, nx);
  Huu_.resize(nu, nu);
  for (int j = 0; j < nx; ++j) {
    for (int i = 0; i < nx; ++i) Hxx_(i, j) = Q[i + j * nw];
    for (int i = 0; i < nu; ++i) Hux_(i, j) = Q[nx + i + j * nw];
  }
  for (int j = 0; j < nu; ++j) {
    for (int i = 0; i < nu; ++i) Huu_(i, j) = Q[nx + i + (nx + j) * nw];
  }
  GemmTN<kNx, kNx, kNx>(nx, nx, nn, 1.0, s.A.data(), nn, PW_.data(), nn, 1.0, Hxx_.data(), nx);
  GemmTN<kNu, kNx, kNx>(nu, nx, nn, 1.0, s.B.data(), nn, PW_.data(), nn, 1.0, Hux_.data(), nu);
  GemmTN<kNu, kNu, kNx>(
      nu, nu, nn, 1.0, s.B.data(), nn, PW_.data() + nn * nx, nn, 1.0, Huu_.data(), nu);
  for (int i = 0; i < nx; ++i) Hxx_(i, i) += dw;
  for (int i = 0; i < nu; ++i) Huu_(i, i) += dw;
  gx_ = s.q.head(nx);
  gu_ = s.q.tail(nu);
  GemmTN<kNx, 1, kNx>(nx, 1, nn, 1.0, s.A.data(), nn, Pbp_.data(), nn, 1.0, gx_.data(), nx);
  GemmTN<kNu, 1, kNx>(nu, 1, nn, 1.0, s.B.data(), nn, Pbp_.data(), nn, 1.0, gu_.data(), nu);
  BE_.resize(nu, npsi);
  GemmTN<kNu, 0, kNx>(nu, npsi, nn, 1.0, s.B.data(), nn, vn.E.data(), nn, 0.0, BE_.data(), nu);

  // u_k = K x_k + k + M nu.
  StageFactor& f = factors_[k];
  f.K = Hux_;
  f.k = gu_;
  f.M = BE_;
  f.cholesky = true;
  if (nu > 0) {
    f.L = Huu_;
    if (CholeskyInPlace<kNu>(f.L.data(), nu)) {
      CholeskySolveNegated<kNu, kNx>(f.L.data(), nu, f.K.data(), nx, nu);
      CholeskySolveNegated<kNu, 1>(f.L.data(), nu, f.k.data(), 1, nu);
      CholeskySolveNegated<kNu, 0>(f.L.data(), nu, f.M.data(), npsi, nu);
    } else {
      f.cholesky = false;
      // H_uu is not positive definite. With terminal rows that may still be the right
      // inertia (a direction of negative curvature the terminal rows remove): count the
      // negative eigenvalues and go on with the symmetric eigendecomposition, unless H_uu is
      // singular or more negative directions appear than there are terminal rows.
      eig_.compute(Huu_);
      const Vec& lam = eig_.eigenvalues();
      const double scale = std::max(1.0, lam.cwiseAbs().maxCoeff());
      const int neg = static_cast<int>((lam.array() < 0.0).count());
      const bool singular = lam.cwiseAbs().minCoeff() <= 1e-12 * scale;
      if (k == 0 && nx == 0 && npsi > 0 && joint_first_stage_ &&
          (eig_.info() != Eigen::Success || singular || negative_ + neg > npsi)) {
        // The first stage without a state, where H_uu's own test fails: its controls and the
        // terminal multiplier are solved together (JointFirstStage), exact whether H_uu is
        // singular or indefinite (the terminal rows may supply the curvature the stage lacks),
        // the inertia tested on the equilibrated joint matrix rather than on H_uu's unscaled
        // eigenvalues. (Taken wherever H_uu is not positive definite, it moved every problem
        // with a free final time by rounding and left quadrotor at the acceptable level at
        // tol 1e-10: measured 2026-12-07.)
        JointFirstStage(s, vn, npsi);
        return true;
      }
      negative_ += neg;
      if (eig_.info() != Eigen::Success || singular || negative_ > npsi) {
        failed_stage_ = k;
        return false;
      }
      const Mat& V = eig_.eigenvectors();
      f.Hinv.noalias() = V * lam.cwiseInverse().asDiagonal() * V.transpose();
      GemmNN<kNu, kNx, kNu>(
          nu, nx, nu, -1.0, f.Hinv.data(), nu, Hux_.data(), nu, 0.0, f.K.data(), nu);
      GemmNN<kNu, 1, kNu>(nu, 1, nu, -1.0, f.Hinv.data(), nu, gu_.data(), nu, 0.0, f.k.data(), nu);
      GemmNN<kNu, 0, kNu>(
          nu, npsi, nu, -1.0, f.Hinv.data(), nu, BE_.data(), nu, 0.0, f.M.data(), nu);
    }
  }
  // V_k: P = sym(H_xx + H_ux^T K), p = g_x + H_ux^T k, E = A^T E + H_ux^T M, and the
  // parameter's e += E^T b + (B^T E)^T k, G += (B^T E)^T M.
  ValueFunction& v = values_[k];
  v.P = Hxx_;
  GemmTN<kNx, kNx, kNu>(nx, nx, nu, 1.0, Hux_.data(), nu, f.K.data(), nu, 1.0, v.P.data(), nx);
  for (int j = 0; j < nx; ++j) {
    for (int i = j + 1; i < nx; ++i) {
      const double m = 0.5 * (v.P(i, j) + v.P(j, i));
      v.P(i, j) = m;
      v.P(j, i) = m;
    }
  }
  v.p = gx_;
  GemmTN<kNx, 1, kNu>(nx, 1, nu, 1.0, Hux_.data(), nu, f.k.data(), nu, 1.0, v.p.data(), nx);
  GemmTN<0, 1, kNx>(npsi, 1, nn, 1.0, vn.E.data(), nn, s.b.data(), nn, 1.0, e_.data(), npsi);
  GemmTN<0, 1, kNu>(npsi, 1, nu, 1.0, BE_.data(), nu, f.k.data(), nu, 1.0, e_.data(), npsi);
  GemmTN<0, 0, kNu>(npsi, npsi, nu, 1.0, BE_.data(), nu, f.M.data(), nu, 1.0, G_.data(), npsi);
  v.E.resize(nx, npsi);
  GemmTN<kNx, 0, kNx>(nx, npsi, nn, 1.0, s.A.data(), nn, vn.E.data(), nn, 0.0, v.E.data(), nx);
  GemmTN<kNx, 0, kNu>(nx, npsi, nu, 1.0, Hux_.data(), nu, f.M.data(), nu, 1.0, v.E.data(), nx);
  return true;
}

void RiccatiSolver::JointFirstStage(const RiccatiStage& s, const ValueFunction& vn, int npsi) {
  const int nu = static_cast<int>(s.B.cols());
  const int nn = static_cast<int>(s.A.rows());
  joint_ = true;
  joint_K_.setZero(nu + npsi, nu + npsi);
  joint_K_.topLeftCorner(nu, nu) = Huu_;  // dw included
  joint_K_.topRightCorner(nu, npsi) = BE_;
  joint_K_.bottomLeftCorner(npsi, nu) = BE_.transpose();
  joint_gu_ = gu_;
  // The parameter's e gains E^T b (its B^T E k part is the joint solve's).
  GemmTN(npsi, 1, nn, 1.0, vn.E.data(), nn, s.b.data(), nn, 1.0, e_.data(), npsi);
  ValueFunction& v = values_[0];  // no state: V_0 is the parameter's part alone
  v.P.resize(0, 0);
  v.p.resize(0);
  v.E.resize(0, npsi);
}

RiccatiOutcome RiccatiSolver::Solve(const RiccatiProblem& problem,
                                    double dw,
                                    double dc,
                                    RiccatiSolution* solution) {
  const int N = static_cast<int>(problem.stages.size());
  const int npsi = static_cast<int>(problem.C.rows());
  failed_stage_ = -1;
  negative_ = 0;
  factored_ = false;
  joint_ = false;
  joint_first_stage_ = problem.joint_first_stage;
  factors_.resize(N);
  values_.resize(N + 1);

  // V_N.
  const int nxN = static_cast<int>(problem.QN.rows());
  {
    ValueFunction& v = values_[N];
    v.P = problem.QN;
    v.P.diagonal().array() += dw;
    v.p = problem.qN;
    // C is npsi x nxN; a caller without terminal rows may leave it empty (0 x 0).
    v.E.resize(nxN, npsi);
    if (npsi > 0) v.E = problem.C.transpose();
  }
  // Slacks of terminal rows, eliminated: each row's constant gains slack_gradient / (slack_hessian
  // + dw) and its dual regularization 1 / (slack_hessian + dw).
  slack_inverse_.setZero(npsi);
  if (problem.slack_hessian.size() > 0) {
    if (problem.slack_hessian.size() != npsi || problem.slack_gradient.size() != npsi ||
        (problem.slack_hessian.array() < 0.0).any()) {
      throw std::invalid_argument(
          "RiccatiSolver::Solve: slack_hessian and slack_gradient need one entry >= 0 per "
          "terminal row");
    }
    for (int i = 0; i < npsi; ++i) {
      if (problem.slack_hessian[i] > 0.0) slack_inverse_[i] = 1.0 / (problem.slack_hessian[i] + dw);
    }
  }
  e_ = problem.c;
  if (problem.slack_gradient.size() > 0) e_ += problem.slack_gradient.cwiseProduct(slack_inverse_);
  G_.setZero(npsi, npsi);

  for (int k = N - 1; k >= 0; --k) {
    const RiccatiStage& s = problem.stages[k];
    const int nx = static_cast<int>(s.A.cols());
    const int nu = static_cast<int>(s.B.cols());
    const bool ok = s.A.rows() == nx
                        ? WithStageDims(nx,
                                        nu,
                                        [&]<int kNx, int kNu>() {
                                          return BackwardStage<kNx, kNu>(s, k, dw, npsi);
                                        })
                        : BackwardStage<0, 0>(s, k, dw, npsi);
    if (!ok) return RiccatiOutcome::kNotPositiveDefinite;
  }

  // The inertia of the whole KKT matrix is that of the dynamics pairs, plus the H_uu's, plus that
  // of G_0 - dc I (Haynsworth): it is right when -(G_0 - dc I) has exactly as many negative
  // eigenvalues as the H_uu's had, and no zero one.
  if (joint_) {
    // The first stage's controls and nu together: [H_uu, B^T E; E^T B, G - dc I - D] (D the
    // slacks' 1 / (Sigma + dw)) must have as many negative eigenvalues as there are terminal
    // rows beyond the later stages' negative curvature (Haynsworth again), and no zero one.
    joint_K_.bottomRightCorner(npsi, npsi) = 0.5 * (G_ + G_.transpose());
    joint_K_.bottomRightCorner(npsi, npsi).diagonal().array() -= dc;
    joint_K_.bottomRightCorner(npsi, npsi).diagonal() -= slack_inverse_;
    // Equilibrated (Ruiz: D K D with every row's largest entry near 1), which keeps the
    // inertia (Sylvester) and makes the eigenvalues' zero test scale-free: the condensed
    // blocks of a stiff problem span many orders of magnitude.
    Equilibrate(joint_K_, &joint_d_, &jrhs_);
    joint_K_ = joint_d_.asDiagonal() * joint_K_ * joint_d_.asDiagonal();
    joint_eig_.compute(joint_K_, Eigen::EigenvaluesOnly);
    const Vec& lam = joint_eig_.eigenvalues();
    const double scale = std::max(1.0, lam.cwiseAbs().maxCoeff());
    if (joint_eig_.info() != Eigen::Success || lam.cwiseAbs().minCoeff() <= 1e-13 * scale) {
      return RiccatiOutcome::kTerminalRowsDegenerate;
    }
    if (static_cast<int>((lam.array() < 0.0).count()) != npsi - negative_) {
      failed_stage_ = 0;
      return RiccatiOutcome::kNotPositiveDefinite;
    }
    // Solves by LU with partial pivoting: solving through the eigenvectors left the steps'
    // accuracy short of tol 1e-10 on quadrotor (its primal infeasibility oscillating between
    // 1e-8 and 3e-7 with full steps).
    joint_lu_.compute(joint_K_);
  } else if (npsi > 0) {
    S_ = -0.5 * (G_ + G_.transpose());
    S_.diagonal().array() += dc;
    S_.diagonal() += slack_inverse_;
    // With slacks, D = 1 / (Sigma + dw) grows without bound on an inactive row as mu falls: the
    // zero test below is made on the equilibrated matrix then (without slacks, as before).
    schur_d_.resize(0);
    if ((slack_inverse_.array() > 0.0).any()) {
      Equilibrate(S_, &schur_d_, &rhs_);
      S_ = schur_d_.asDiagonal() * S_ * schur_d_.asDiagonal();
    }
    schur_.compute(S_);
    const Vec& lam = schur_.eigenvalues();
    const double scale = std::max(1.0, lam.cwiseAbs().maxCoeff());
    if (schur_.info() != Eigen::Success || lam.cwiseAbs().minCoeff() <= 1e-13 * scale) {
      return RiccatiOutcome::kTerminalRowsDegenerate;
    }
    if (static_cast<int>((lam.array() < 0.0).count()) != negative_) {
      failed_stage_ = N;
      return RiccatiOutcome::kNotPositiveDefinite;
    }
  }
  b_.resize(N);
  for (int k = 0; k < N; ++k) b_[k] = &problem.stages[k].b;
  TerminalMultiplierAndForwardSweep(problem, b_, problem.x0, problem.slack_gradient, solution);
  factored_ = true;
  return RiccatiOutcome::kSolved;
}

void RiccatiSolver::TerminalMultiplierAndForwardSweep(const RiccatiProblem& problem,
                                                      const std::vector<const Vec*>& b,
                                                      const Vec& x0,
                                                      const Vec& slack_gradient,
                                                      RiccatiSolution* solution) {
  const int N = static_cast<int>(problem.stages.size());
  const int npsi = static_cast<int>(problem.C.rows());
  // The terminal multiplier from the final Schur complement, or with a joint first stage from
  // the joint system (with u_0).
  nu_.setZero(npsi);
  if (joint_) {
    jrhs_.resize(joint_K_.rows());
    const int nu0 = static_cast<int>(joint_gu_.size());
    jrhs_.head(nu0) = -joint_gu_;
    jrhs_.tail(npsi) = -e_;
    jrhs_ = jrhs_.cwiseProduct(joint_d_);
    jsol_ = joint_lu_.solve(jrhs_);
    jsol_ = jsol_.cwiseProduct(joint_d_);
    nu_ = jsol_.tail(npsi);
  } else if (npsi > 0) {
    const Vec& lam = schur_.eigenvalues();
    const Mat& V = schur_.eigenvectors();
    rhs_ = e_;
    const int nx0 = static_cast<int>(x0.size());
    if (nx0 > 0) {
      GemmTN(npsi, 1, nx0, 1.0, values_[0].E.data(), nx0, x0.data(), nx0, 1.0, rhs_.data(), npsi);
    }
    // (G - dc I) nu = -rhs <=> S nu = rhs (equilibrated: D S D y = D rhs, nu = D y).
    if (schur_d_.size() > 0) rhs_ = rhs_.cwiseProduct(schur_d_);
    nu_.noalias() = V * (V.transpose() * rhs_).cwiseQuotient(lam);
    if (schur_d_.size() > 0) nu_ = nu_.cwiseProduct(schur_d_);
  }
  solution->nu = nu_;
  solution->s = nu_.cwiseProduct(slack_inverse_);
  if (slack_gradient.size() > 0) solution->s -= slack_gradient.cwiseProduct(slack_inverse_);
  const double* nu = nu_.data();

  // Forward sweep.
  solution->x.resize(N + 1);
  solution->u.resize(N);
  solution->lambda.resize(N);
  solution->x[0] = x0;
  for (int k = 0; k < N; ++k) {
    const RiccatiStage& s = problem.stages[k];
    const StageFactor& f = factors_[k];
    const ValueFunction& vn = values_[k + 1];
    const int nx = static_cast<int>(s.A.cols());
    const int nu_k = static_cast<int>(s.B.cols());
    const int nn = static_cast<int>(s.A.rows());
    const Vec& xk = solution->x[k];
    Vec& uk = solution->u[k];
    Vec& xn = solution->x[k + 1];
    Vec& lam = solution->lambda[k];
    if (k == 0 && joint_) {
      uk = jsol_.head(nu_k);
    } else {
      uk = f.k;
      GemmNN(nu_k, 1, nx, 1.0, f.K.data(), nu_k, xk.data(), nx, 1.0, uk.data(), nu_k);
      GemmNN(nu_k, 1, npsi, 1.0, f.M.data(), nu_k, nu, npsi, 1.0, uk.data(), nu_k);
    }
    xn = *b[k];
    GemmNN(nn, 1, nx, 1.0, s.A.data(), nn, xk.data(), nx, 1.0, xn.data(), nn);
    GemmNN(nn, 1, nu_k, 1.0, s.B.data(), nn, uk.data(), nu_k, 1.0, xn.data(), nn);
    lam = vn.p;
    GemmNN(nn, 1, nn, 1.0, vn.P.data(), nn, xn.data(), nn, 1.0, lam.data(), nn);
    GemmNN(nn, 1, npsi, 1.0, vn.E.data(), nn, nu, npsi, 1.0, lam.data(), nn);
    for (int i = 0; i < nn; ++i) lam[i] = -lam[i];
  }
}

void RiccatiSolver::SolveFactored(const RiccatiProblem& problem,
                                  const RiccatiRhs& rhs,
                                  RiccatiSolution* solution) {
  if (!factored_) {
    throw std::logic_error("RiccatiSolver::SolveFactored: the last Solve did not succeed");
  }
  const int N = static_cast<int>(problem.stages.size());
  const int npsi = static_cast<int>(problem.C.rows());
  if (static_cast<int>(factors_.size()) != N) {
    throw std::logic_error("RiccatiSolver::SolveFactored: not the factorized problem's stages");
  }
  // The vector part of the backward recursion with the factors of the last Solve: with
  // Pbp = P_{k+1} b + p_{k+1}, g = q + [A B]^T Pbp, k_k = -H_uu^-1 g_u and
  // p_k = g_x + H_ux^T k_k = g_x + K_k^T g_u (H_ux^T = -K_k^T H_uu); the parameter's
  // e += E_{k+1}^T (b + B k_k). G, P, E, K and M do not depend on the right-hand side.
  values_[N].p = rhs.qN;
  e_ = rhs.c;
  if (rhs.slack_gradient.size() > 0) e_ += rhs.slack_gradient.cwiseProduct(slack_inverse_);
  for (int k = N - 1; k >= 0; --k) {
    const RiccatiStage& s = problem.stages[k];
    StageFactor& f = factors_[k];
    const ValueFunction& vn = values_[k + 1];
    const int nx = static_cast<int>(s.A.cols());
    const int nu = static_cast<int>(s.B.cols());
    const int nn = static_cast<int>(s.A.rows());
    const Vec& b = rhs.b[k];
    Pbp_ = vn.p;
    GemmNN(nn, 1, nn, 1.0, vn.P.data(), nn, b.data(), nn, 1.0, Pbp_.data(), nn);
    gx_ = rhs.q[k].head(nx);
    gu_ = rhs.q[k].tail(nu);
    GemmTN(nx, 1, nn, 1.0, s.A.data(), nn, Pbp_.data(), nn, 1.0, gx_.data(), nx);
    GemmTN(nu, 1, nn, 1.0, s.B.data(), nn, Pbp_.data(), nn, 1.0, gu_.data(), nu);
    if (k == 0 && joint_) {  // the joint solve takes g_u and e += E^T b
      joint_gu_ = gu_;
      GemmTN(npsi, 1, nn, 1.0, vn.E.data(), nn, b.data(), nn, 1.0, e_.data(), npsi);
      continue;
    }
    if (nu > 0) {
      if (f.cholesky) {
        f.k = gu_;
        CholeskySolveNegated(f.L.data(), nu, f.k.data(), 1, nu);
      } else {
        f.k.noalias() = -f.Hinv * gu_;
      }
    } else {
      f.k.resize(0);
    }
    ValueFunction& v = values_[k];
    v.p = gx_;
    GemmTN(nx, 1, nu, 1.0, f.K.data(), nu, gu_.data(), nu, 1.0, v.p.data(), nx);
    if (npsi > 0) {
      rhs_ = b;  // b + B k_k
      GemmNN(nn, 1, nu, 1.0, s.B.data(), nn, f.k.data(), nu, 1.0, rhs_.data(), nn);
      GemmTN(npsi, 1, nn, 1.0, vn.E.data(), nn, rhs_.data(), nn, 1.0, e_.data(), npsi);
    }
  }
  b_.resize(N);
  for (int k = 0; k < N; ++k) b_[k] = &rhs.b[k];
  TerminalMultiplierAndForwardSweep(problem, b_, rhs.x0, rhs.slack_gradient, solution);
}

double RiccatiKktResidual(
    const RiccatiProblem& p, double dw, double dc, const RiccatiSolution& z, RiccatiRhs* r) {
  const int N = static_cast<int>(p.stages.size());
  const int npsi = static_cast<int>(p.C.rows());
  double worst = 0.0;
  const auto max_abs = [](const Vec& v) { return v.size() > 0 ? v.cwiseAbs().maxCoeff() : 0.0; };
  r->q.resize(N);
  r->b.resize(N);
  for (int k = 0; k < N; ++k) {
    const RiccatiStage& s = p.stages[k];
    const int nx = static_cast<int>(s.A.cols()), nu = static_cast<int>(s.B.cols());
    const int nn = static_cast<int>(s.A.rows()), nw = nx + nu;
    // Stationarity in (x_k, u_k): (Q + dw I) w + q - [A B]^T lambda_k + [lambda_{k-1}; 0],
    // in the plain-loop kernels (Eigen's dynamic-size products cost more than the arithmetic
    // on blocks this small).
    Vec& st = r->q[k];
    st = s.q;
    GemmNN(nw, 1, nx, 1.0, s.Q.data(), nw, z.x[k].data(), nx, 1.0, st.data(), nw);
    GemmNN(nw,
           1,
           nu,
           1.0,
           s.Q.data() + static_cast<long>(nx) * nw,
           nw,
           z.u[k].data(),
           nu,
           1.0,
           st.data(),
           nw);
    for (int i = 0; i < nx; ++i) st[i] += dw * z.x[k][i];
    for (int i = 0; i < nu; ++i) st[nx + i] += dw * z.u[k][i];
    GemmTN(nx, 1, nn, -1.0, s.A.data(), nn, z.lambda[k].data(), nn, 1.0, st.data(), nw);
    GemmTN(nu, 1, nn, -1.0, s.B.data(), nn, z.lambda[k].data(), nn, 1.0, st.data() + nx, nw);
    if (k > 0) {
      for (int i = 0; i < nx; ++i) st[i] += z.lambda[k - 1][i];
    } else {
      for (int i = 0; i < nx; ++i) st[i] = 0.0;  // x_0 is given, not a variable: no row
    }
    Vec& dyn = r->b[k];
    dyn = z.x[k + 1] - s.b;
    GemmNN(nn, 1, nx, -1.0, s.A.data(), nn, z.x[k].data(), nx, 1.0, dyn.data(), nn);
    GemmNN(nn, 1, nu, -1.0, s.B.data(), nn, z.u[k].data(), nu, 1.0, dyn.data(), nn);
    worst = std::max({worst, max_abs(st), max_abs(dyn)});
    st = -st;  // the correction's q: its stationarity rows are the residual
  }
  Vec& stN = r->qN;
  const int nxN = static_cast<int>(p.QN.rows());
  stN = p.qN + dw * z.x[N];
  GemmNN(nxN, 1, nxN, 1.0, p.QN.data(), nxN, z.x[N].data(), nxN, 1.0, stN.data(), nxN);
  if (N > 0) stN += z.lambda[N - 1];
  if (npsi > 0) {
    GemmTN(nxN, 1, npsi, 1.0, p.C.data(), npsi, z.nu.data(), npsi, 1.0, stN.data(), nxN);
  }
  worst = std::max(worst, max_abs(stN));
  stN = -stN;
  r->c.resize(npsi);
  r->slack_gradient.resize(0);
  if (npsi > 0) {
    r->c = p.c - dc * z.nu;
    GemmNN(npsi, 1, nxN, 1.0, p.C.data(), npsi, z.x[N].data(), nxN, 1.0, r->c.data(), npsi);
    if (p.slack_hessian.size() > 0) {
      // The slacks' rows and their stationarity (slack_hessian + dw) s + slack_gradient - nu.
      r->slack_gradient.setZero(npsi);
      for (int i = 0; i < npsi; ++i) {
        if (!(p.slack_hessian[i] > 0.0)) continue;
        r->c[i] -= z.s[i];
        r->slack_gradient[i] = (p.slack_hessian[i] + dw) * z.s[i] + p.slack_gradient[i] - z.nu[i];
      }
      worst = std::max(worst, max_abs(r->slack_gradient));
      r->slack_gradient = -r->slack_gradient;
    }
    worst = std::max(worst, max_abs(r->c));
    r->c = -r->c;
  }
  r->x0.setZero(p.x0.size());
  return worst;
}

}  // namespace ocpb
