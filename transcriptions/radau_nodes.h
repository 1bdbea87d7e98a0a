// Legendre-Gauss-Radau points, quadrature weights, differentiation matrix and barycentric
// Lagrange interpolation on [-1, 1].
#pragma once

#include "core/types.h"

namespace ocpb {

/// The K Legendre-Gauss-Radau (LGR) points -1 = tau_0 < tau_1 < ... < tau_{K-1} < 1: tau_0 and
/// the K - 1 roots of (P_{K-1}(tau) + P_K(tau)) / (1 + tau), with P_n the Legendre polynomials,
/// and the Radau quadrature weights (Abramowitz & Stegun 25.4.31)
///
///   w_0 = 2 / K^2,   w_i = (1 - tau_i) / (K^2 P_{K-1}(tau_i)^2),
///
/// which integrate every polynomial of degree <= 2K - 2 exactly on [-1, 1].
///
/// The state support points are the LGR points plus tau_K = +1 (K + 1 points); `differentiation`
/// (K x (K+1)) maps values on them to the derivative of their interpolating polynomial (degree K)
/// at the K LGR points: D_ij = l_j'(tau_i), computed in barycentric form (Berrut & Trefethen,
/// "Barycentric Lagrange interpolation", SIAM Review 46 (2004), eq. (9.4)):
///   D_ij = (v_j / v_i) / (tau_i - tau_j) for i != j,  D_ii = -sum_{j != i} D_ij.
/// The points come from Newton's method on (P_{K-1} + P_K)/(1 + tau) with deflation of the roots
/// already found, started at the Chebyshev-Gauss-Radau points -cos(2 pi i / (2K - 1)).
struct RadauNodes {
  int K = 0;
  Vec points;           ///< tau_0..tau_{K-1} (size K)
  Vec weights;          ///< quadrature weights (size K), summing to 2
  Vec support;          ///< tau_0..tau_{K-1}, +1 (size K + 1)
  Vec support_weights;  ///< barycentric weights of `support` (size K + 1)
  Vec point_weights;    ///< barycentric weights of `points` (size K), for control interpolation
  Mat differentiation;  ///< K x (K + 1)
};

/// The LGR data for K points; throws std::invalid_argument unless 1 <= K <= kMaxRadauPoints.
RadauNodes ComputeRadauNodes(int K);
inline constexpr int kMaxRadauPoints = 60;

/// P_n(x) and P_n'(x) by the three-term recurrence (n >= 0).
void LegendreAndDerivative(int n, double x, double* p, double* dp);

/// Barycentric weights v_j = 1 / prod_{m != j} (x_j - x_m) of distinct points x, rescaled so that
/// max |v_j| = 1 (interpolation only uses their ratios).
Vec BarycentricWeights(const Vec& x);

/// The Lagrange basis l_j(t) of the points x (with barycentric weights v) at t, into `basis`
/// (size x.size()): the second (true) barycentric form, exact (a unit vector) when t is a node.
void LagrangeBasis(const Vec& x, const Vec& v, double t, VecRef basis);

}  // namespace ocpb
