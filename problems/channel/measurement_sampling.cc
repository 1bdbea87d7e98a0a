#include "problems/channel/measurement_sampling.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <unordered_set>

#include "problems/channel/random_stream.h"

namespace ocpb {
namespace {

bool Eligible(const GridSpec& g, const ChannelParameters& p, int i, int j) {
  return (g.Point(i, j) - p.base_station).norm() >= p.distance_floor;
}

bool Eligible(const SimulatedChannel& c, int i, int j) {
  return Eligible(c.grid, c.parameters, i, j);
}

}  // namespace

long EligibleMeasurementPoints(const GridSpec& g, const ChannelParameters& parameters) {
  long eligible = 0;
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) eligible += Eligible(g, parameters, i, j) ? 1 : 0;
  }
  return eligible;
}

MeasurementSet DrawRandomMeasurements(const SimulatedChannel& channel, int m, std::uint64_t seed) {
  const GridSpec& g = channel.grid;
  const long eligible = EligibleMeasurementPoints(g, channel.parameters);
  if (m < 1 || 2L * m > eligible) {
    throw std::invalid_argument("samples must be between 1 and " + std::to_string(eligible / 2) +
                                " (half the grid points), got " + std::to_string(m));
  }
  std::vector<bool> taken(static_cast<std::size_t>(g.num_points()), false);
  RandomStream stream(seed, RandomStream::kMeasurementPositions);
  MeasurementSet set;
  set.positions.reserve(m);
  set.values_db.reserve(m);
  while (static_cast<int>(set.positions.size()) < m) {
    const auto k = static_cast<long>(stream.Index(static_cast<std::uint64_t>(g.num_points())));
    const int i = static_cast<int>(k % g.nx), j = static_cast<int>(k / g.nx);
    if (taken[static_cast<std::size_t>(k)] || !Eligible(channel, i, j)) continue;
    taken[static_cast<std::size_t>(k)] = true;
    set.positions.push_back(g.Point(i, j));
    set.values_db.push_back(channel.gain_db(i, j));
  }
  return set;
}

MeasurementSet MeasureAlongPath(const SimulatedChannel& channel,
                                const std::vector<Eigen::Vector2d>& path,
                                int samples) {
  if (samples < 0) throw std::invalid_argument("samples along a path must be >= 0");
  const GridSpec& g = channel.grid;
  const long n = static_cast<long>(path.size());
  const long count = n == 0 ? 0 : (samples == 0 ? n : samples);
  std::unordered_set<long> taken;
  MeasurementSet set;
  for (long s = 0; s < count; ++s) {
    long p = s;
    if (samples > 0) p = samples == 1 ? n - 1 : std::lround(double(s) * (n - 1) / (samples - 1));
    if (!path[p].allFinite()) {
      throw std::invalid_argument("path point " + std::to_string(p) + " is not finite");
    }
    int i, j;
    g.NearestCell(path[p], &i, &j);
    const long k = static_cast<long>(j) * g.nx + i;
    if (!Eligible(channel, i, j) || !taken.insert(k).second) continue;
    set.positions.push_back(g.Point(i, j));
    set.values_db.push_back(channel.gain_db(i, j));
  }
  return set;
}

}  // namespace ocpb
