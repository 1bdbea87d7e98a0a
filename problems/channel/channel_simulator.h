// A simulated channel realization over the workspace grid.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include <Eigen/Core>

#include "problems/channel/channel_parameters.h"
#include "problems/channel/multipath.h"
#include "problems/channel/shadowing_simulator.h"

namespace ocpb {

/// What to simulate besides the channel parameters.
struct SimulationOptions {
  GridSpec grid;               ///< default: 50 m x 50 m at 0.1 m (250,000 points)
  MultipathOptions multipath;  ///< default: Rician, K = 14.56

  bool IsValid(std::string* error) const;
};

/// One realization on the grid, every field nx x ny in dB (see GridSpec for the layout):
///   gain_db = path_loss_db + shadowing_db + multipath_db
/// with path_loss_db = ChannelParameters::PathLossDb at the grid points (distance floor
/// included), shadowing_db exponentially correlated (ShadowingSimulator) and multipath_db
/// independent per point (MultipathModel). gain_db is Gamma_dB, the received power in dBm for a
/// 0 dBm transmitter; the CNR in dB is gain_db - N0_dBm.
struct SimulatedChannel {
  GridSpec grid;
  ChannelParameters parameters;
  MultipathOptions multipath;
  std::uint64_t seed = 0;
  Eigen::MatrixXd path_loss_db;
  Eigen::MatrixXd shadowing_db;
  Eigen::MatrixXd multipath_db;
  Eigen::MatrixXd gain_db;
  double shadowing_clipped_fraction = 0.0;  ///< ShadowingSimulator::clipped_fraction()

  /// gain_db at the grid cell containing q (clamped to the grid).
  double GainAt(const Eigen::Vector2d& q) const;
};

/// Simulates realizations for fixed parameters and grid; keeps the shadowing embedding so that
/// many seeds cost one FFT each. Simulate() is const and thread-safe.
///
/// Randomness: shadowing uses RandomStream(seed, kShadowing), multipath
/// RandomStream(seed, kMultipath); a seed gives the same realization on every platform up to
/// the rounding of FFTW and libm.
class ChannelSimulator {
 public:
  /// Throws std::invalid_argument on invalid parameters or options.
  ChannelSimulator(const ChannelParameters& parameters, const SimulationOptions& options);

  SimulatedChannel Simulate(std::uint64_t seed) const;

  const ShadowingSimulator& shadowing() const { return *shadowing_; }

 private:
  ChannelParameters parameters_;
  SimulationOptions options_;
  std::shared_ptr<const ShadowingSimulator> shadowing_;
  Eigen::MatrixXd path_loss_db_;
};

/// One-shot convenience: ChannelSimulator(parameters, options).Simulate(seed).
SimulatedChannel SimulateChannel(const ChannelParameters& parameters,
                                 const SimulationOptions& options,
                                 std::uint64_t seed);

}  // namespace ocpb
