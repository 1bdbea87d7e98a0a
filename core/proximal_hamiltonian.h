// The proximal Hamiltonian minimizer of the method of successive approximations (Sakawa and
// Shindo), offered by problems that have it in closed form.
#pragma once

#include "core/types.h"

namespace ocpb {

/// A problem implements this next to Ocp when it can compute
///
///   w = argmin_{w in U} H(t, x, w, p) + |w - center|^2 / (2 eps),   eps > 0,
///
/// in closed form (or to rounding by a documented one-dimensional solve). The proximal term makes
/// the minimizer move at most about eps |grad_u H| from `center`: the direction of Sakawa and
/// Shindo's successive approximations ("On global convergence of an algorithm for optimal
/// control", IEEE Trans. Automatic Control 25(6), 1980), which for eps -> infinity is the
/// paper's u* = argmin H. Methods without it use ConvexPointMinimizer (solvers/). Tests check the
/// minimizer against a brute-force search over U.
class ProximalHamiltonianMinimizer {
 public:
  virtual ~ProximalHamiltonianMinimizer() = default;
  virtual void MinimizeProximalHamiltonian(
      double t, ConstVecRef x, ConstVecRef p, ConstVecRef center, double eps, VecRef w) const = 0;
};

}  // namespace ocpb
