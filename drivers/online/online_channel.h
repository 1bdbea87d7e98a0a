// The channel knowledge of a robot that keeps measuring while it moves (paper Section IV).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <unordered_set>
#include <vector>

#include <Eigen/Core>

#include "problems/channel/channel_map.h"
#include "problems/channel/channel_parameters.h"
#include "problems/channel/channel_simulator.h"
#include "problems/channel/gp_predictor.h"
#include "problems/channel/grid_predictor.h"
#include "problems/channel/measurement_file.h"
#include "problems/channel/parameter_estimator.h"
#include "problems/channel/true_channel.h"

namespace ocpb {

/// Options of OnlineChannel. Defaults: the paper's channel and the paper's procedure
/// (parameters re-estimated from all measurements at every update).
struct OnlineChannelOptions {
  ChannelParameters truth;       ///< the simulated channel (paper's values)
  SimulationOptions simulation;  ///< truth grid: 50 m x 50 m at 0.1 m, Rician multipath
  /// true: (K_PL, n_PL, xi, eta, rho) re-estimated from all measurements at every update (the
  /// paper's procedure); false: the predictor uses `truth` (an oracle).
  bool estimate = true;
  /// The estimator (estimation.method, default the channel library's) with wider lag bins than
  /// the companion's default (1 m, >= 20 pairs instead of 0.2 m, >= 40): 100 measurements over
  /// 50 m x 50 m give about 20-60 pairs per 1 m bin between 2 and 15 m and too few per 0.2 m
  /// bin to fit the shadowing at all (maximum likelihood uses the bins only for its first
  /// start).
  EstimationOptions estimation = [] {
    EstimationOptions o;
    o.bin_width = 1.0;
    o.min_pairs = 20;
    return o;
  }();
  GpPredictorOptions predictor;  ///< units of s (default W)
  /// Spacing of the grid on which s is re-predicted and splined (m, > 0; the map covers the
  /// truth grid's rectangle). 0.5 m keeps a re-prediction at a few tens of milliseconds; the
  /// shadowing correlation distance is 3.09 m, and the map's spline is C2 either way.
  double map_resolution = 0.5;
  /// Re-predictions after the first may be restricted to a region of interest (the bounding box
  /// of the points passed to Update: the robot, its destination and its current plan) grown by
  /// this margin (m, >= 0) and clipped to the workspace; 0: always the whole workspace. Beyond
  /// the region the map is flat (ChannelMap clamps), so the margin should exceed how far a
  /// re-plan can move the path; 10 m is about 3 shadowing correlation distances.
  double region_margin = 10.0;
  /// One thread by default, so that the CPU time of a re-prediction is its wall time.
  GridPredictionOptions grid_prediction = [] {
    GridPredictionOptions o;
    o.num_threads = 1;
    return o;
  }();
  MapOptions map;
  /// false: measurements are recorded but the prediction is never refreshed after the first
  /// Update (a control experiment: re-planning without new information).
  bool refresh = true;

  bool IsValid(std::string* error) const;
};

/// Timings of one OnlineChannel::Update, CPU seconds (one thread).
struct ChannelUpdateTimings {
  double estimate_seconds = 0.0;  ///< parameter re-estimation
  double factor_seconds = 0.0;    ///< GP predictor (Cholesky of Phi with all measurements)
  double grid_seconds = 0.0;      ///< prediction on the map grid
  double map_seconds = 0.0;       ///< bicubic spline of s
  /// true when re-estimation failed (too few lag pairs, or residuals without spatial
  /// correlation) and the previous estimate was kept
  bool estimation_failed = false;
  double total() const { return estimate_seconds + factor_seconds + grid_seconds + map_seconds; }
};

/// A simulated true channel (one realization of `options.truth`) and what a robot knows of it:
/// the measurements taken so far, the parameters estimated from them and the predicted s as a
/// bicubic map (ChannelMap), refreshed by Update(). Every measurement is the true gain_db of a
/// truth grid cell at the cell's centre; a cell is measured at most once (the simulated channel
/// is one fixed value per cell), so repeated positions never reach the predictor.
///
/// TrueQuality() is what the robot really pays: s_true(q) = scale 10^(-(Gamma_dB(cell(q)) -
/// N0)/10), the inverse CNR of the cell containing q (no expectation: the realization is
/// known to the simulator), in the predictor's units, so that the transmit power for rate R at q
/// is (2^R - 1)/K s_true(q) (TrueChannelQuality, shared with the offline records' judge).
class OnlineChannel {
 public:
  /// Simulates realization `seed`. Throws std::invalid_argument on invalid options.
  OnlineChannel(std::uint64_t seed, const OnlineChannelOptions& options = {});

  /// `m` measurements at distinct, not yet measured cells drawn uniformly from RandomStream(seed,
  /// stream) (cells within the distance floor of the base station excluded). Throws
  /// std::invalid_argument when m < 1 or fewer than 2 m unmeasured eligible cells remain.
  MeasurementSet DrawRandom(int m, std::uint64_t seed, std::uint64_t stream) const;
  // Measurements along a path: MeasureAlongPath(truth(), path, m) (measurement_sampling.h);
  // Update skips the cells already measured.

  /// Records `more` (positions must be truth cell centres from DrawRandom or MeasureAlongPath; a
  /// cell already measured is skipped), re-estimates the parameters from all measurements (if
  /// options.estimate; maximum likelihood starts from the previous estimate), rebuilds the GP
  /// predictor and re-predicts the map (unless options.refresh is false and a map exists).
  /// Returns the CPU times. When re-estimation fails after a first success, the previous
  /// estimate is kept (ChannelUpdateTimings::estimation_failed). Throws std::invalid_argument
  /// when fewer than 3 measurements are known or the first estimation fails.
  /// `focus` (optional, used when options.region_margin > 0): the points the map must cover.
  ChannelUpdateTimings Update(const MeasurementSet& more,
                              const std::vector<Eigen::Vector2d>* focus = nullptr);
  /// The grid of the current map (the whole workspace or a region of interest).
  const GridSpec& map_grid() const { return current_grid_; }

  /// The current predicted s (null before the first Update).
  std::shared_ptr<const ChannelQuality> map() const { return map_; }
  /// The true inverse CNR at q (see the class comment).
  double TrueQuality(const Eigen::Vector2d& q) const;
  /// log10 of the current predicted s and of the true s on a grid of spacing h over the truth
  /// rectangle (cell centres), rows over y: for figures.
  void SampleLog10(double h,
                   std::vector<double>* x,
                   std::vector<double>* y,
                   Eigen::MatrixXd* predicted,
                   Eigen::MatrixXd* truth) const;

  const SimulatedChannel& truth() const { return *truth_; }
  /// The true channel as a ChannelQuality (TrueQuality's numbers), for judging plans on it
  /// (ExecuteCommPlan, problems/comm_true_energy.h).
  const std::shared_ptr<const TrueChannelQuality>& true_quality() const { return true_quality_; }
  const MeasurementSet& measurements() const { return measurements_; }
  const ChannelParameters& estimated() const { return estimated_; }
  const OnlineChannelOptions& options() const { return options_; }
  int num_measurements() const { return static_cast<int>(measurements_.values_db.size()); }

 private:
  long CellIndex(const Eigen::Vector2d& q) const;

  OnlineChannelOptions options_;
  std::shared_ptr<const SimulatedChannel> truth_;
  std::shared_ptr<const TrueChannelQuality> true_quality_;
  GridSpec map_grid_;      // the whole workspace at map_resolution
  GridSpec current_grid_;  // the grid of map_
  MeasurementSet measurements_;
  std::unordered_set<long> measured_cells_;
  ChannelParameters estimated_;
  std::shared_ptr<const GpChannelPredictor> predictor_;
  std::shared_ptr<const ChannelMap> map_;
};

}  // namespace ocpb
