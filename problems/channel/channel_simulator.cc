#include "problems/channel/channel_simulator.h"

#include <stdexcept>

namespace ocpb {

bool SimulationOptions::IsValid(std::string* error) const {
  return grid.IsValid(error) && multipath.IsValid(error);
}

double SimulatedChannel::GainAt(const Eigen::Vector2d& q) const {
  int i, j;
  grid.NearestCell(q, &i, &j);
  return gain_db(i, j);
}

ChannelSimulator::ChannelSimulator(const ChannelParameters& parameters,
                                   const SimulationOptions& options)
    : parameters_(parameters), options_(options) {
  std::string error;
  if (!parameters.IsValid(&error)) throw std::invalid_argument("channel parameters: " + error);
  if (!options.IsValid(&error)) throw std::invalid_argument("simulation options: " + error);
  shadowing_ = std::make_shared<ShadowingSimulator>(options.grid, parameters.xi, parameters.eta);
  const GridSpec& g = options.grid;
  path_loss_db_.resize(g.nx, g.ny);
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) path_loss_db_(i, j) = parameters.PathLossDb(g.Point(i, j));
  }
}

SimulatedChannel ChannelSimulator::Simulate(std::uint64_t seed) const {
  SimulatedChannel c;
  c.grid = options_.grid;
  c.parameters = parameters_;
  c.multipath = options_.multipath;
  c.seed = seed;
  c.path_loss_db = path_loss_db_;
  RandomStream shadow_stream(seed, RandomStream::kShadowing);
  c.shadowing_db = shadowing_->Draw(&shadow_stream);
  c.shadowing_clipped_fraction = shadowing_->clipped_fraction();
  RandomStream mp_stream(seed, RandomStream::kMultipath);
  c.multipath_db.resize(c.grid.nx, c.grid.ny);
  for (Eigen::Index k = 0; k < c.multipath_db.size(); ++k) {
    c.multipath_db.data()[k] = DrawMultipathDb(options_.multipath, parameters_.rho, &mp_stream);
  }
  c.gain_db = c.path_loss_db + c.shadowing_db + c.multipath_db;
  return c;
}

SimulatedChannel SimulateChannel(const ChannelParameters& parameters,
                                 const SimulationOptions& options,
                                 std::uint64_t seed) {
  return ChannelSimulator(parameters, options).Simulate(seed);
}

}  // namespace ocpb
