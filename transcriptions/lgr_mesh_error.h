// Patterson, Hager and Rao's local error estimate of a Legendre-Gauss-Radau solution on each mesh
// interval, for LGR's ph mesh refinement.
#pragma once

#include <map>
#include <vector>

#include "core/control_trajectory.h"
#include "core/ocp.h"
#include "core/time_grid.h"
#include "core/types.h"
#include "transcriptions/radau_nodes.h"

namespace ocpb {

/// LGR data per degree, computed once per degree a mesh uses (ComputeRadauNodes is O(K^3)).
class RadauNodeCache {
 public:
  /// The nodes for K points; throws std::invalid_argument unless 1 <= K <= kMaxRadauPoints.
  const RadauNodes& Get(int K);

 private:
  std::map<int, RadauNodes> nodes_;
};

/// The LGR state polynomial of interval k at tau in [-1, 1]: the Lagrange polynomial of degree
/// K through the support values X_support (nx x (K + 1): the K LGR points, then the next
/// interval's first point) at nodes.support.
void LgrStateAt(const RadauNodes& nodes, const Mat& X_support, double tau, VecRef x);

/// The estimate of Patterson, Hager and Rao ("A ph mesh refinement method for optimal control",
/// Optim. Control Appl. Meth. 36 (2015) 398-421, Sec. 3) on each interval k of `mesh` with
/// K_k = degrees[k] collocation points, t = t_k + h_k (tau + 1) / 2:
///
///  - the M = K_k + 1 LGR points tau^_0..tau^_{M-1} and tau^_M = +1 of degree M;
///  - X(tau^_j): the interval's state polynomial (LgrStateAt) at those points, U(tau^_l) the
///    control (`controls`, the scheme's interpolation) at the M LGR points;
///  - X^(tau^_j) = X(tau^_0) + h_k/2 sum_l I_jl f(t_l, X(tau^_l), U(tau^_l)), j = 1..M, with I
///    the LGR integration matrix of degree M (the inverse of the differentiation matrix's
///    columns 1..M: integrating the polynomial that interpolates f at the M points);
///  - e_k = max_i max_j |X^_i(tau^_j) - X_i(tau^_j)| / (1 + max_j |X_i(tau^_j)|).
///
/// The polynomial of degree K and the quadrature of degree M both approximate x; on a smooth
/// solution their difference is the polynomial's interpolation error, O(h^(K+1)) at fixed K
/// (the h-model PhMergedError uses; asserted by
/// MeshError.LgrEstimateDecreasesAsHToTheDegreePlusOne) and decreasing exponentially in K.
///
/// `mesh` is on the solution's horizon (stretched to T for a free final time); `states` is nx x
/// (sum_k K_k + 1): interval 0's K_0 points, interval 1's, ..., x(tf), as LGR stores them.
/// Returns one entry per interval; NaN where f is not finite. `cache` (may be null) keeps the
/// nodes between calls.
Vec LgrIntervalErrors(const Ocp& ocp,
                      const TimeGrid& mesh,
                      const std::vector<int>& degrees,
                      const Mat& states,
                      const ControlTrajectory& controls,
                      RadauNodeCache* cache = nullptr);

}  // namespace ocpb
