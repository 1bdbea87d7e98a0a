// Drawing channel measurements from a simulated realization.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "problems/channel/channel_simulator.h"
#include "problems/channel/measurement_file.h"

namespace ocpb {

/// m measurements at distinct grid points drawn uniformly without replacement, seeded by
/// RandomStream(seed, kMeasurementPositions). Each measurement is the simulated gain_db at that
/// point and its position the point itself. Points within the distance floor of the base
/// station are never drawn (the path-loss regressor is constant there; see
/// GpChannelPredictor). Throws std::invalid_argument when m < 1 or m exceeds half the eligible
/// points.
MeasurementSet DrawRandomMeasurements(const SimulatedChannel& channel, int m, std::uint64_t seed);

/// The grid points DrawRandomMeasurements draws from (those at least the distance floor away
/// from the base station), counted without simulating a channel: validation checks a sample
/// count with it (2 m of them are needed).
long EligibleMeasurementPoints(const GridSpec& grid, const ChannelParameters& parameters);

/// Measurements along a path (the one way to measure along a path: the online placements use
/// it too). `samples` = 0: every path point; `samples` > 0: the points at `samples` indices
/// spaced evenly over the path, first to last (index round(s (n - 1) / (samples - 1)); the last
/// point when samples = 1), so for a path sampled at equal time steps they are evenly spaced in
/// time. Each chosen point is measured in the grid cell containing it (clamped to the grid):
/// that cell's gain_db at the cell's centre. A cell met again is measured once (the first
/// visit), since the simulated channel is one fixed value per cell; cells within the distance
/// floor of the base station are skipped. So the result has at most `samples` (or path size)
/// measurements, in path order. Throws std::invalid_argument on a non-finite chosen point or
/// samples < 0.
MeasurementSet MeasureAlongPath(const SimulatedChannel& channel,
                                const std::vector<Eigen::Vector2d>& path,
                                int samples = 0);

}  // namespace ocpb
