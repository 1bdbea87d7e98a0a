#include "solvers/riccati_kkt.h"

#include <Eigen/Cholesky>

namespace ocpb {

RiccatiOutcome RiccatiSolver::Solve(const RiccatiProblem& problem,
                                    double dw,
                                    double dc,
                                    RiccatiSolution* solution) {
  const int N = static_cast<int>(problem.stages.size());
  const int npsi = static_cast<int>(problem.C.rows());
  failed_stage_ = -1;
  factors_.resize(N);
  values_.resize(N);

  // V_N.
  const int nxN = static_cast<int>(problem.QN.rows());
  Mat P = problem.QN;
  P.diagonal().array() += dw;
  Vec p = problem.qN;
  Mat E = problem.C.transpose();
  Vec e = problem.c;
  Mat G = Mat::Zero(npsi, npsi);
  if (nxN == 0) E.resize(0, npsi);

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
      if (llt.info() != Eigen::Success) {
        failed_stage_ = k;
        return RiccatiOutcome::kNotPositiveDefinite;
      }
      f.K = -llt.solve(Hux);
      f.k = -llt.solve(gu);
      f.M = -llt.solve(BE);
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
    llt.compute(S);
    if (llt.info() != Eigen::Success) return RiccatiOutcome::kTerminalRowsDegenerate;
    Vec rhs = e;
    if (problem.x0.size() > 0) rhs += E.transpose() * problem.x0;
    nu = llt.solve(rhs);  // (G - dc I) nu = -rhs  <=>  S nu = rhs
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
