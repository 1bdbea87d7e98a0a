#include "tests/transcriptions/nlp_test_util.h"

#include <cmath>
#include <stdexcept>
#include <vector>

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include "transcriptions/euler.h"
#include "transcriptions/hermite_simpson.h"
#include "transcriptions/lgr.h"
#include "transcriptions/trapezoid.h"

namespace ocpb::testing {

Mat DenseJacobian(const Nlp& nlp, const Vec& z) {
  Vec values(nlp.jacobian_rows().size());
  if (!nlp.JacobianValues(z, values)) throw std::runtime_error("JacobianValues failed");
  Mat J = Mat::Zero(nlp.num_constraints(), nlp.num_variables());
  for (size_t s = 0; s < nlp.jacobian_rows().size(); ++s) {
    J(nlp.jacobian_rows()[s], nlp.jacobian_cols()[s]) += values[s];
  }
  return J;
}

Mat DenseHessian(const Nlp& nlp, const Vec& z, double sigma, const Vec& lambda) {
  Vec values(nlp.hessian_rows().size());
  if (!nlp.HessianValues(z, sigma, lambda, values))
    throw std::runtime_error("HessianValues failed");
  Mat H = Mat::Zero(nlp.num_variables(), nlp.num_variables());
  for (size_t s = 0; s < nlp.hessian_rows().size(); ++s) {
    const int r = nlp.hessian_rows()[s], c = nlp.hessian_cols()[s];
    H(r, c) += values[s];
    if (r != c) H(c, r) += values[s];
  }
  return H;
}

Vec LagrangianGradient(const Nlp& nlp, const Vec& z, double sigma, const Vec& lambda) {
  Vec grad(nlp.num_variables());
  if (!nlp.Gradient(z, grad)) throw std::runtime_error("Gradient failed");
  return sigma * grad + DenseJacobian(nlp, z).transpose() * lambda;
}

KktSolution SolveEqualityKkt(const Nlp& nlp, const Vec& z0, int max_iterations, double tolerance) {
  const int n = nlp.num_variables(), m = nlp.num_constraints();
  Vec zl, zu, gl, gu;
  nlp.Bounds(&zl, &zu, &gl, &gu);
  std::vector<int> free_index(n, -1);
  int nf = 0;
  for (int i = 0; i < n; ++i) {
    if (zl[i] == zu[i]) continue;
    if (std::isfinite(zl[i]) || std::isfinite(zu[i])) {
      throw std::logic_error("SolveEqualityKkt: only fixed or unbounded variables");
    }
    free_index[i] = nf++;
  }
  for (int r = 0; r < m; ++r) {
    if (gl[r] != gu[r]) throw std::logic_error("SolveEqualityKkt: only equality constraints");
  }
  KktSolution sol;
  sol.z = z0;
  for (int i = 0; i < n; ++i) {
    if (free_index[i] < 0) sol.z[i] = zl[i];
  }
  sol.lambda = Vec::Zero(m);
  Vec grad(n), g(m), jac(nlp.jacobian_rows().size()), hess(nlp.hessian_rows().size());
  for (int it = 0; it < max_iterations; ++it) {
    if (!nlp.Gradient(sol.z, grad) || !nlp.Constraints(sol.z, g) ||
        !nlp.JacobianValues(sol.z, jac) || !nlp.HessianValues(sol.z, 1.0, sol.lambda, hess)) {
      return sol;
    }
    std::vector<Eigen::Triplet<double>> t;
    for (size_t s = 0; s < nlp.hessian_rows().size(); ++s) {
      const int r = free_index[nlp.hessian_rows()[s]], c = free_index[nlp.hessian_cols()[s]];
      if (r < 0 || c < 0) continue;
      t.emplace_back(r, c, hess[s]);
      if (r != c) t.emplace_back(c, r, hess[s]);
    }
    for (size_t s = 0; s < nlp.jacobian_rows().size(); ++s) {
      const int c = free_index[nlp.jacobian_cols()[s]];
      if (c < 0) continue;
      t.emplace_back(nf + nlp.jacobian_rows()[s], c, jac[s]);
      t.emplace_back(c, nf + nlp.jacobian_rows()[s], jac[s]);
    }
    Eigen::SparseMatrix<double> K(nf + m, nf + m);
    K.setFromTriplets(t.begin(), t.end());
    Vec rhs(nf + m);
    for (int i = 0; i < n; ++i) {
      if (free_index[i] >= 0) rhs[free_index[i]] = -grad[i];
    }
    rhs.tail(m) = -(g - gl);
    Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
    lu.compute(K);
    if (lu.info() != Eigen::Success) return sol;
    const Vec step = lu.solve(rhs);
    if (!step.allFinite()) return sol;
    double dz = 0.0;
    for (int i = 0; i < n; ++i) {
      if (free_index[i] < 0) continue;
      sol.z[i] += step[free_index[i]];
      dz = std::max(dz, std::abs(step[free_index[i]]));
    }
    sol.lambda = step.tail(m);
    sol.iterations = it + 1;
    sol.step_norm = dz;
    if (dz <= tolerance * (1.0 + sol.z.cwiseAbs().maxCoeff())) {
      nlp.Constraints(sol.z, g);
      sol.constraint_norm = (g - gl).cwiseAbs().maxCoeff();
      sol.converged = true;
      return sol;
    }
  }
  nlp.Constraints(sol.z, g);
  sol.constraint_norm = (g - gl).cwiseAbs().maxCoeff();
  return sol;
}

std::unique_ptr<Transcription> MakeScheme(const std::string& name) {
  if (name == "euler") return std::make_unique<EulerTranscription>();
  if (name == "trapezoid") return std::make_unique<TrapezoidTranscription>();
  if (name == "hermite-simpson") return std::make_unique<HermiteSimpsonTranscription>();
  if (name == "lgr") return std::make_unique<LgrTranscription>();
  throw std::invalid_argument("unknown scheme " + name);
}

}  // namespace ocpb::testing
