#include "problems/channel/paper_channel.h"

#include <cmath>
#include <stdexcept>

#include "core/timer.h"
#include "problems/channel/measurement_sampling.h"

namespace ocpb {

const char* ToString(ChannelProvider provider) {
  return provider == ChannelProvider::kExact ? "exact" : "map";
}

ChannelProvider ChannelProviderFromString(const std::string& name) {
  if (name == "exact") return ChannelProvider::kExact;
  if (name == "map") return ChannelProvider::kMap;
  throw std::invalid_argument("unknown channel provider '" + name + "' (valid: exact, map)");
}

bool PaperChannelOptions::IsValid(std::string* error) const {
  return truth.IsValid(error) && simulation.IsValid(error) && estimation.IsValid(error) &&
         predictor.IsValid(error) && grid_prediction.IsValid(error);
}

std::shared_ptr<const ChannelQuality> PaperChannel::Quality(ChannelProvider provider) const {
  if (provider == ChannelProvider::kExact) return predictor;
  if (map == nullptr) throw std::logic_error("paper channel: no map was built (build_map)");
  return map;
}

double PaperChannel::RmseDb() const {
  if (grid.mean_db.size() != truth.gain_db.size()) {
    throw std::logic_error("paper channel: no grid prediction (build_map)");
  }
  return std::sqrt((grid.mean_db - truth.gain_db).array().square().mean());
}

void PaperChannel::RefreshMap() {
  const Stopwatch watch;
  grid = PredictOnGrid(*predictor, truth.grid, options.grid_prediction);
  map = std::make_shared<ChannelMap>(ChannelMap::FromPrediction(grid, *predictor, options.map));
  map_seconds = watch.wall() - grid.seconds;
}

PaperChannel MakePaperChannel(std::uint64_t seed, int samples, const PaperChannelOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument("paper channel: " + error);
  if (samples < 3) {
    throw std::invalid_argument("need at least 3 samples, got " + std::to_string(samples));
  }
  PaperChannel c;
  c.seed = seed;
  c.options = options;
  {
    const Stopwatch watch;
    c.truth = SimulateChannel(options.truth, options.simulation, seed);
    c.simulate_seconds = watch.wall();
  }
  c.measurements = DrawRandomMeasurements(c.truth, samples, seed);
  {
    const Stopwatch watch;
    c.estimated = options.estimate
                      ? EstimateChannelParameters(
                            c.measurements, options.truth, options.estimation, &c.estimation)
                      : options.truth;
    c.estimate_seconds = watch.wall();
  }
  {
    const Stopwatch watch;
    c.predictor =
        std::make_shared<GpChannelPredictor>(c.estimated, c.measurements, options.predictor);
    c.factor_seconds = watch.wall();
  }
  if (options.build_map) c.RefreshMap();
  return c;
}

}  // namespace ocpb
