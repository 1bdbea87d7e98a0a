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

/// Measurements along a path: for every path point the grid cell containing it (clamped to the
/// grid); the measurement is that cell's gain_db at the cell's centre. A cell visited again is
/// measured once (the first visit), since the simulated channel is one fixed value per cell;
/// cells within the distance floor of the base station are skipped. Throws
/// std::invalid_argument on a non-finite path point.
MeasurementSet MeasureAlongPath(const SimulatedChannel& channel,
                                const std::vector<Eigen::Vector2d>& path);

}  // namespace ocpb
