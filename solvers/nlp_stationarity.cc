#include "solvers/nlp_stationarity.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

namespace ocpb {

double NlpStationarity(const Nlp& nlp, ConstVecRef z, double active_tol) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  const int n = nlp.num_variables(), m = nlp.num_constraints();
  Vec grad(n);
  if (!nlp.Gradient(z, grad) || !grad.allFinite()) return kNaN;
  Vec zl, zu, gl, gu;
  nlp.Bounds(&zl, &zu, &gl, &gu);

  // Free variables get consecutive columns; fixed ones (at or beyond a bound) are dropped.
  std::vector<int> column(n, -1);
  int nf = 0;
  auto near = [active_tol](double v, double bound) {
    return std::isfinite(bound) &&
           std::abs(v - bound) <= active_tol * std::max(1.0, std::abs(bound));
  };
  for (int i = 0; i < n; ++i) {
    if (z[i] > zl[i] && z[i] < zu[i] && !near(z[i], zl[i]) && !near(z[i], zu[i])) {
      column[i] = nf++;
    }
  }
  Vec g_free(nf);
  for (int i = 0; i < n; ++i) {
    if (column[i] >= 0) g_free[column[i]] = grad[i];
  }
  const double scale = std::max(1.0, grad.lpNorm<Eigen::Infinity>());
  if (m == 0 || nf == 0) return nf == 0 ? 0.0 : g_free.lpNorm<Eigen::Infinity>() / scale;

  Vec g(m);
  if (!nlp.Constraints(z, g) || !g.allFinite()) return kNaN;
  std::vector<int> row(m, -1);
  int na = 0;
  for (int j = 0; j < m; ++j) {
    const bool active =
        gl[j] == gu[j] || g[j] <= gl[j] || g[j] >= gu[j] || near(g[j], gl[j]) || near(g[j], gu[j]);
    if (active) row[j] = na++;
  }
  Vec values(static_cast<Eigen::Index>(nlp.jacobian_rows().size()));
  if (!nlp.JacobianValues(z, values) || !values.allFinite()) return kNaN;
  std::vector<Eigen::Triplet<double>> entries;
  for (size_t s = 0; s < nlp.jacobian_rows().size(); ++s) {
    const int r = row[nlp.jacobian_rows()[s]], c = column[nlp.jacobian_cols()[s]];
    if (r >= 0 && c >= 0) entries.emplace_back(r, c, values[static_cast<Eigen::Index>(s)]);
  }
  if (na == 0) return g_free.lpNorm<Eigen::Infinity>() / scale;
  Eigen::SparseMatrix<double> J(na, nf);
  J.setFromTriplets(entries.begin(), entries.end());
  Eigen::SparseMatrix<double> normal = J * J.transpose();
  double largest = 0.0;
  for (int k = 0; k < na; ++k) largest = std::max(largest, normal.coeff(k, k));
  const double delta = 1e-12 * std::max(largest, 1e-300);
  for (int k = 0; k < na; ++k) normal.coeffRef(k, k) += delta;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(normal);
  if (ldlt.info() != Eigen::Success) return kNaN;
  const Vec rhs = -(J * g_free);
  Vec lambda = ldlt.solve(rhs);
  lambda += ldlt.solve(rhs - normal * lambda);  // one step of iterative refinement
  const Vec residual = g_free + J.transpose() * lambda;
  return residual.allFinite() ? residual.lpNorm<Eigen::Infinity>() / scale : kNaN;
}

}  // namespace ocpb
