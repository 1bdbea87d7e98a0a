// OCPBench's estimates of the memory the channel model needs, checked before a channel is
// simulated (a GP of 10^5 measurements would need 320 GB and end in bad_alloc after minutes).
#pragma once

#include <string>

#include "core/memory_budget.h"

namespace ocpb {

/// A GP prediction from m measurements: 32 m^2 bytes (the covariance, its Cholesky factor and
/// the estimator's work matrices, 8 bytes an entry). Measured peaks of `ocpbench channel predict
/// --samples m --resolution 0.5 --no-files` less its 17 MB at m = 0: 23 m^2 bytes at m = 1000,
/// 21 m^2 at m = 4000.
inline double EstimateGpMemoryBytes(double measurements) {
  return 32.0 * measurements * measurements;
}

/// A simulated and predicted channel on a grid of `points` points: 160 bytes a point (the
/// gain, shadowing and multipath fields, the predicted mean, variance and s, the map's
/// coefficients). Measured: 105 bytes a point at 500 x 500 points (`--resolution 0.1`).
inline double EstimateChannelGridBytes(double points) { return 160.0 * points; }

/// Throws std::invalid_argument (CheckMemoryEstimate) naming `grid_field` when the grid alone,
/// or `measurements_field` when the grid and the GP together, exceed the memory budget.
inline void CheckChannelMemory(double measurements,
                               const std::string& measurements_field,
                               double grid_points,
                               const std::string& grid_field) {
  const double grid = EstimateChannelGridBytes(grid_points);
  CheckMemoryEstimate(
      grid,
      grid_field,
      "a channel grid of " + std::to_string(static_cast<long long>(grid_points)) + " points");
  CheckMemoryEstimate(
      grid + EstimateGpMemoryBytes(measurements),
      measurements_field,
      std::to_string(static_cast<long long>(measurements)) +
          " measurements (the GP prediction's covariance and its factor, and the channel grid)");
}

}  // namespace ocpb
