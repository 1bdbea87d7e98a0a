// The paper's channel, ready for a problem: simulate, measure, estimate, predict, map.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "problems/channel/channel_map.h"
#include "problems/channel/channel_parameters.h"
#include "problems/channel/channel_simulator.h"
#include "problems/channel/gp_predictor.h"
#include "problems/channel/grid_predictor.h"
#include "problems/channel/measurement_file.h"
#include "problems/channel/parameter_estimator.h"

namespace ocpb {

/// Which ChannelQuality a problem evaluates s(q) with (record it with results: Describe()).
enum class ChannelProvider {
  kExact,  ///< GpChannelPredictor: the paper's formulas at q (about 0.1-0.3 ms per call, m=500)
  kMap,    ///< ChannelMap: bicubic spline of s on the grid (tens of ns per call)
};
const char* ToString(ChannelProvider provider);
/// "exact" or "map"; throws std::invalid_argument otherwise.
ChannelProvider ChannelProviderFromString(const std::string& name);

/// Everything MakePaperChannel does, with the paper's setting as defaults.
struct PaperChannelOptions {
  ChannelParameters truth;  ///< simulated channel (paper: -41.34, 3.86, 3.2, 3.09, 1.64, (5,5))
  SimulationOptions simulation;  ///< grid 50 m x 50 m at 0.1 m, Rician multipath K = 14.56
  /// true: the predictor uses parameters estimated from the measurements (the paper's
  /// procedure); false: it uses `truth` (an oracle, for isolating prediction error).
  bool estimate = true;
  EstimationOptions estimation;
  GpPredictorOptions predictor;  ///< units of s (default W), coincident-position policy
  bool build_map = true;         ///< predict the grid and build the map
  GridPredictionOptions grid_prediction;
  MapOptions map;

  bool IsValid(std::string* error) const;
};

/// A simulated channel with its measurements and predictors (see MakePaperChannel).
struct PaperChannel {
  std::uint64_t seed = 0;
  PaperChannelOptions options;
  SimulatedChannel truth;        ///< the realization (gain_db is the true Gamma_dB)
  MeasurementSet measurements;   ///< the m measurements drawn from it
  ChannelParameters estimated;   ///< the parameters the predictor uses
  EstimationSummary estimation;  ///< empty when options.estimate is false
  std::shared_ptr<GpChannelPredictor> predictor;
  GridPrediction grid;              ///< mean, variance and s on the grid (if build_map)
  std::shared_ptr<ChannelMap> map;  ///< null unless build_map
  double simulate_seconds = -1.0, estimate_seconds = -1.0, factor_seconds = -1.0,
         map_seconds = -1.0;  ///< wall times; grid.seconds is the grid prediction

  /// The exact predictor or the map as a ChannelQuality (throws std::logic_error for kMap
  /// when no map was built). The pointer shares ownership with this struct's members.
  std::shared_ptr<const ChannelQuality> Quality(ChannelProvider provider) const;
  /// Root-mean-square of (predicted mean - true gain_db) over the grid, dB (needs the grid).
  double RmseDb() const;
  /// After predictor->AddMeasurements(...): re-predicts the grid and rebuilds the map.
  void RefreshMap();
};

/// The paper's experiment (Section IV, Figs. 1-2), for the comm problems and the CLI:
///
/// 1. simulate the channel of options.truth on options.simulation.grid with `seed`
///    (ChannelSimulator; shadowing and multipath streams of the seed);
/// 2. draw `samples` measurements at distinct random grid points (DrawRandomMeasurements with
///    the same seed, its own stream);
/// 3. estimate (K_PL, n_PL, xi, eta, rho) from them (EstimateChannelParameters with
///    options.estimation; options.estimation.method: binned by default, or "ml"), unless
///    options.estimate is false;
/// 4. build the exact GP predictor (GpChannelPredictor), s in options.predictor.units
///    (default watts);
/// 5. if options.build_map: predict mean, variance and s on the grid (PredictOnGrid) and
///    build the bicubic map of s (ChannelMap).
///
/// Typical use in a problem:
///   PaperChannel c = MakePaperChannel(seed, 500);
///   std::shared_ptr<const ChannelQuality> s = c.Quality(ChannelProvider::kMap);
///   // record s->Describe() with the results
/// Cost with the defaults: about 0.5-1 s (simulation 0.3 s, grid prediction 0.2 s; maximum
/// likelihood adds 0.15-0.3 s).
/// Throws std::invalid_argument on invalid options or samples (< 3 or more than half the grid).
PaperChannel MakePaperChannel(std::uint64_t seed,
                              int samples,
                              const PaperChannelOptions& options = {});

}  // namespace ocpb
