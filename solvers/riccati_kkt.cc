#include "solvers/riccati_kkt.h"

#include <algorithm>

#include <Eigen/Cholesky>

namespace ocpb {

RiccatiOutcome RiccatiSolver::Solve(const RiccatiProblem& problem,
                                    double dw,
                                    double dc,
                                    RiccatiSolution* solution) {
  const int N = static_cast<int>(problem.stages.size());
  const int npsi = static_cast<int>(problem.C.rows());
  failed_stage_ = -1;
  negative_ = 0;
  factors_.resize(N);
  values_.resize(N);

  // V_N.
  const int nxN = static_cast<int>(problem.QN.rows());
  Mat P = problem.QN;
  P.diagonal().array() += dw;
  Vec p = problem.qN;
  // C is npsi x nxN; a caller without terminal rows may leave it empty (0 x 0).
  Mat E = npsi > 0 ? Mat(problem.C.transpose()) : Mat::Zero(nxN, 0);
  Vec e = problem.c;
  Mat G = Mat::Zero(npsi, npsi);

  Eigen::LLT<Mat> llt;
  for (int k = N - 1; k >= 0; --k) {
    const RiccatiStage& s = problem.stages[k];
    const int nx = static_cast<int>(s.A.cols());
    const int nu = static_cast<int>(s.B.cols());
    ValueFunction& v = values_[k];
    v.P = P;
    v.p = p;
    v.E = E;

    const Vec Pb_p = P * s.b + p;
    const Mat PA = P * s.A;
    const Mat PB = P * s.B;
    Mat Hxx = s.Q.topLeftCorner(nx, nx) + s.A.transpose() * PA;
    Mat Hux = s.Q.bottomLeftCorner(nu, nx) + s.B.transpose() * PA;
    Mat Huu = s.Q.bottomRightCorner(nu, nu) + s.B.transpose() * PB;
    Hxx.diagonal().array() += dw;
    Huu.diagonal().array() += dw;
    const Vec gx = s.q.head(nx) + s.A.transpose() * Pb_p;
    const Vec gu = s.q.tail(nu) + s.B.transpose() * Pb_p;
    const Mat BE = s.B.transpose() * E;  // nu x npsi

    StageFactor& f = factors_[k];
    if (nu > 0) {
      llt.compute(Huu);
      if (llt.info() == Eigen::Success) {
        // (Eigen's triangular solve must not see a right-hand side without columns.)
        f.K = nx > 0 ? Mat(-llt.solve(Hux)) : Mat(nu, 0);
        f.k = -llt.solve(gu);
        f.M = npsi > 0 ? Mat(-llt.solve(BE)) : Mat(nu, 0);
      } else {
        // H_uu is not positive definite. With terminal rows that may still be the right
        // inertia (a direction of negative curvature the terminal rows remove): count the
        // negative eigenvalues and go on with the symmetric eigendecomposition, unless H_uu is
        // singular or more negative directions appear than there are terminal rows.
        eig_.compute(Huu);
        const Vec& lam = eig_.eigenvalues();
        const double scale = std::max(1.0, lam.cwiseAbs().maxCoeff());
        const int neg = static_cast<int>((lam.array() < 0.0).count());
        negative_ += neg;
        if (eig_.info() != Eigen::Success || lam.cwiseAbs().minCoeff() <= 1e-12 * scale ||
            negative_ > npsi) {
          failed_stage_ = k;
          return RiccatiOutcome::kNotPositiveDefinite;
        }
        const Mat& V = eig_.eigenvectors();
        const Mat Hinv = V * lam.cwiseInverse().asDiagonal() * V.transpose();
        f.K = -Hinv * Hux;
        f.k = -Hinv * gu;
        f.M = -Hinv * BE;
      }
    } else {
      f.K = Mat::Zero(0, nx);
      f.k = Vec::Zero(0);
      f.M = Mat::Zero(0, npsi);
    }
    // V_k.
    Mat Pk = Hxx + Hux.transpose() * f.K;
    P = 0.5 * (Pk + Pk.transpose());
    p = gx + Hux.transpose() * f.k;
    e = e + E.transpose() * s.b + BE.transpose() * f.k;
    G = G + BE.transpose() * f.M;
    E = s.A.transpose() * E + Hux.transpose() * f.M;
  }

  // The terminal multiplier from the final Schur complement.
  Vec nu = Vec::Zero(npsi);
  if (npsi > 0) {
    Mat S = -(G + G.transpose()) * 0.5;
    S.diagonal().array() += dc;
    // The inertia of the whole KKT matrix is that of the dynamics pairs, plus the H_uu's, plus
    // that of G_0 - dc I (Haynsworth): it is right when -(G_0 - dc I) has exactly as many
    // negative eigenvalues as the H_uu's had, and no zero one.
    eig_.compute(S);
    const Vec& lam = eig_.eigenvalues();
    const double scale = std::max(1.0, lam.cwiseAbs().maxCoeff());
    if (eig_.info() != Eigen::Success || lam.cwiseAbs().minCoeff() <= 1e-13 * scale) {
      return RiccatiOutcome::kTerminalRowsDegenerate;
    }
    if (static_cast<int>((lam.array() < 0.0).count()) != negative_) {
      failed_stage_ = N;
      return RiccatiOutcome::kNotPositiveDefinite;
    }
    const Mat& V = eig_.eigenvectors();
    Vec rhs = e;
    if (problem.x0.size() > 0) rhs += E.transpose() * problem.x0;
    nu = V * (V.transpose() * rhs).cwiseQuotient(lam);  // (G - dc I) nu = -rhs <=> S nu = rhs
  }

  // Forward sweep.
  solution->x.resize(N + 1);
  solution->u.resize(N);
  solution->lambda.resize(N);
  solution->x[0] = problem.x0;
  for (int k = 0; k < N; ++k) {
    const RiccatiStage& s = problem.stages[k];
    const StageFactor& f = factors_[k];
    const Vec& xk = solution->x[k];
    Vec uk = f.k;
    if (xk.size() > 0) uk.noalias() += f.K * xk;
    if (npsi > 0) uk.noalias() += f.M * nu;
    Vec xn = s.b;
    if (xk.size() > 0) xn.noalias() += s.A * xk;
    if (uk.size() > 0) xn.noalias() += s.B * uk;
    const ValueFunction& v = values_[k];
    Vec lam = v.P * xn + v.p;
    if (npsi > 0) lam.noalias() += v.E * nu;
    solution->u[k] = std::move(uk);
    solution->lambda[k] = -lam;
    solution->x[k + 1] = std::move(xn);
  }
  solution->nu = nu;
  return RiccatiOutcome::kSolved;
}

}  // namespace ocpb
