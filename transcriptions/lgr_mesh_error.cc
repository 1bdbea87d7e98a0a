#include "transcriptions/lgr_mesh_error.h"

#include <Eigen/LU>
#include <cmath>
#include <limits>

namespace ocpb {

const RadauNodes& RadauNodeCache::Get(int K) {
  auto it = nodes_.find(K);
  if (it == nodes_.end()) it = nodes_.emplace(K, ComputeRadauNodes(K)).first;
  return it->second;
}

void LgrStateAt(const RadauNodes& nodes, const Mat& X_support, double tau, VecRef x) {
  Vec basis(nodes.K + 1);
  LagrangeBasis(nodes.support, nodes.support_weights, tau, basis);
  x = X_support * basis;
}

Vec LgrIntervalErrors(const Ocp& ocp,
                      const TimeGrid& mesh,
                      const std::vector<int>& degrees,
                      const Mat& states,
                      const ControlTrajectory& controls,
                      RadauNodeCache* cache) {
  RadauNodeCache local;
  RadauNodeCache& nodes_of = cache ? *cache : local;
  const int nx = ocp.nx(), N = mesh.intervals();
  Vec eta(N);
  Vec u(ocp.nu()), f(nx);
  int first = 0;  // column of interval k's first point in `states`
  for (int k = 0; k < N; ++k) {
    const int K = degrees[k], M = K + 1;
    const RadauNodes& own = nodes_of.Get(K);
    const RadauNodes& finer = nodes_of.Get(M);
    const Mat support = states.middleCols(first, K + 1);
    first += K;
    const double h = mesh.h(k);
    // The state polynomial at the M + 1 support points of degree M, f at its M LGR points.
    Mat X(nx, M + 1), F(nx, M);
    for (int j = 0; j <= M; ++j) LgrStateAt(own, support, finer.support[j], X.col(j));
    for (int l = 0; l < M; ++l) {
      const double t = mesh.t(k) + 0.5 * h * (finer.points[l] + 1.0);
      controls.Evaluate(t, ControlTrajectory::Side::kRight, u);
      ocp.Dynamics(t, X.col(l), u, F.col(l));
    }
    // D (M x (M+1)) applied to the support values gives the derivative at the M points, and
    // D 1 = 0, so D[:, 1:M] (X_j - X_0) = h/2 F: the integration matrix is D[:, 1:M]^-1.
    const Mat integrated =
        finer.differentiation.rightCols(M).partialPivLu().solve((0.5 * h) * F.transpose());
    double worst = 0.0;
    bool finite = F.allFinite();
    for (int i = 0; i < nx && finite; ++i) {
      const double scale = 1.0 + X.row(i).cwiseAbs().maxCoeff();
      for (int j = 1; j <= M; ++j) {
        const double e = std::abs(X(i, 0) + integrated(j - 1, i) - X(i, j)) / scale;
        worst = std::max(worst, e);
      }
    }
    eta[k] = finite && std::isfinite(worst) ? worst : std::numeric_limits<double>::quiet_NaN();
  }
  return eta;
}

}  // namespace ocpb
