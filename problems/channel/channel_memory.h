// OCPBench's estimates of the memory the channel model needs, checked before a channel is
// simulated (a GP of 10^5 measurements would need 320 GB and end in bad_alloc after minutes).
#pragma once

#include <string>

#include "core/memory_budget.h"

namespace ocpb {

/// A GP prediction from m measurements: 32 m^2 bytes (the covariance, its Cholesky factor and
/// the estimator's work matrices, 8 bytes an entry). Measured: `ocpbench channel predict
/// --samples 1000 --resolution 0.5 --no-files` peaks at 39.2 MB resident (debug build), of which
/// about 12.7 MB is the program itself (a run refused at validation): about 27 m^2 bytes.
inline double EstimateGpMemoryBytes(double measurements) {
  return 32.0 * measurements * measurements;
}

/// A simulated and predicted channel on a grid of `points` points: 160 bytes a point (the
/// gain, shadowing and multipath fields, the predicted mean, variance and s, the map's
/// coefficients); generous by design (not measured separately from the GP).
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
