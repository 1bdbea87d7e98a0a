// Optional per-point fast paths a problem may offer to first-order methods on a forward-Euler grid.
#pragma once

#include "core/time_grid.h"
#include "core/types.h"

namespace ocpb {

/// A problem implements this interface next to Ocp when the pointwise work of the Hamiltonian
/// descent on a forward-Euler grid (DiscreteOcp with Integrator::kEuler) has structure its
/// generic Ocp functions cannot exploit; the descent finds it by dynamic_cast and otherwise uses
/// the Ocp functions. Its numbers must be those of the Ocp functions, bitwise where stated (the
/// descent's iterates must not depend on whether the interface exists; tests compare both).
///
/// The idea: a trial simulation evaluates L at every grid point (x_k, u_k), and the accepted
/// trial's points are exactly those where the backward sweep (adjoint and direction) works next.
/// Whatever the problem computed there (comm-path2d: the channel value and gradient, 2^R - 1,
/// the motion power) can be kept in StageCacheSize() doubles per point and reused instead of
/// evaluated again.
///
/// The functions take raw arrays (x: nx doubles, u: nu doubles, p: nx doubles), not Eigen::Ref:
/// they run once per grid point and trial, where building and destroying the Refs cost about as
/// much as the work (measured with callgrind on comm-path2d).
class EulerStageModel {
 public:
  virtual ~EulerStageModel() = default;

  /// Doubles kept per grid point (>= 0).
  virtual int StageCacheSize() const = 0;

  /// x_next = x + h f(t, x, u), bitwise as DiscreteOcp::Simulate computes it (x_i + h f_i): the
  /// trial states of an Armijo search without the generic Dynamics call per point.
  virtual void EulerStep(
      double t, double h, const double* x, const double* u, double* x_next) const = 0;

  /// The Euler states of a whole trial: column k + 1 of X (nx x (N + 1), column-major, column
  /// 0 given) is EulerStep(grid.t(k), grid.h(k), column k of X, column k of U (nu x N)), for k
  /// = 0 .. N - 1, bitwise. The default makes those calls; a problem may override it with the
  /// same arithmetic in one loop, without a virtual call per point.
  virtual void EulerStates(const TimeGrid& grid, int nx, int nu, const double* U, double* X) const {
    for (int k = 0; k < grid.intervals(); ++k) {
      EulerStep(grid.t(k), grid.h(k), X + k * nx, U + k * nu, X + (k + 1) * nx);
    }
  }

  /// L(t, x, u), bitwise equal to Ocp::RunningCost(t, x, u); also writes StageCacheSize()
  /// doubles to `cache` for a later BackwardPoint at the same (t, x, u).
  virtual double RunningCostCaching(double t,
                                    const double* x,
                                    const double* u,
                                    double* cache) const = 0;

  /// A cheap lower bound m(t, x, u) <= L(t, x, u) for every u in U, which must also hold for the
  /// floating-point values RunningCost returns (comm-path2d: the motion power, L minus a
  /// transmission term that is >= 0 and added last). The descent rejects Armijo trials whose
  /// bound already fails the Armijo test without evaluating L (and so without the channel).
  virtual double PointwiseRunningCostBound(double t, const double* x, const double* u) const = 0;

  /// m[k] = PointwiseRunningCostBound(grid.t(k), column k of X, column k of U) for k = 0 ..
  /// N - 1 (X nx x (N + 1), U nu x N, column-major), bitwise. The default makes those calls; a
  /// problem may override it with the same arithmetic in one loop.
  virtual void PointwiseRunningCostBounds(
      const TimeGrid& grid, int nx, int nu, const double* X, const double* U, double* m) const {
    for (int k = 0; k < grid.intervals(); ++k) {
      m[k] = PointwiseRunningCostBound(grid.t(k), X + k * nx, U + k * nu);
    }
  }

  /// One step of the backward sweep at grid point k (time t, step h), given the `cache`
  /// RunningCostCaching wrote for this (t, x, u), with p = lambda_{k+1} on entry:
  ///   u_star = argmin_{w in U} H(t, x, w, p)   (bitwise Ocp::MinimizeHamiltonian),
  ///   *h_star = H(t, x, u_star, p), *h_now = H(t, x, u, p)
  ///                                           (bitwise Ocp::MinimizeAndCompareHamiltonian),
  ///   p <- p + h H_x(t, x, u, p) = lambda_k    (bitwise lambda_{k+1} + h (f_x^T p + L_x), the
  ///                                            Euler adjoint step of DiscreteOcp::Adjoint).
  /// With a finite eps > 0, u_star is instead the proximal minimizer
  ///   argmin_{w in U} H(t, x, w, p) + |w - u|^2 / (2 eps)
  /// (ProximalHamiltonianMinimizer's numbers), *h_star = H(t, x, u_star, p) without the
  /// proximal term, and *h_min (when not null) = min_{w in U} H(t, x, w, p), the value at the
  /// paper's minimizer (the descent's stationarity measure sums h (h_min - h_now)). With eps
  /// infinite *h_min is *h_star.
  virtual void BackwardPoint(double t,
                             double h,
                             const double* x,
                             const double* u,
                             const double* cache,
                             double eps,
                             double* p,
                             double* u_star,
                             double* h_star,
                             double* h_now,
                             double* h_min) const = 0;
};

}  // namespace ocpb
