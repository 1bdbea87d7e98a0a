#include "drivers/online/online_channel.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/timer.h"
#include "problems/channel/quality_units.h"
#include "problems/channel/random_stream.h"

namespace ocpb {

bool OnlineChannelOptions::IsValid(std::string* error) const {
  if (!(map_resolution > 0.0) || !std::isfinite(map_resolution)) {
    if (error) *error = "map_resolution must be finite and > 0";
    return false;
  }
  if (!(region_margin >= 0.0) || !std::isfinite(region_margin)) {
    if (error) *error = "region_margin must be finite and >= 0 (0: the whole workspace)";
    return false;
  }
  return truth.IsValid(error) && simulation.IsValid(error) && estimation.IsValid(error) &&
         predictor.IsValid(error) && grid_prediction.IsValid(error);
}

OnlineChannel::OnlineChannel(std::uint64_t seed, const OnlineChannelOptions& options)
    : options_(options) {
  std::string error;
  if (!options_.IsValid(&error)) throw std::invalid_argument("online channel: " + error);
  auto truth = std::make_shared<const SimulatedChannel>(
      SimulateChannel(options_.truth, options_.simulation, seed));
  true_quality_ = std::make_shared<const TrueChannelQuality>(truth, options_.predictor.units);
  truth_ = std::move(truth);
  const GridSpec& g = truth_->grid;
  map_grid_ = GridSpec::Workspace(
      g.nx * g.resolution, g.ny * g.resolution, options_.map_resolution, g.x_min, g.y_min);
  current_grid_ = map_grid_;
  estimated_ = options_.truth;
}

long OnlineChannel::CellIndex(const Eigen::Vector2d& q) const {
  int i = 0, j = 0;
  truth_->grid.NearestCell(q, &i, &j);
  return static_cast<long>(j) * truth_->grid.nx + i;
}

MeasurementSet OnlineChannel::DrawRandom(int m, std::uint64_t seed, std::uint64_t stream) const {
  const GridSpec& g = truth_->grid;
  const ChannelParameters& p = truth_->parameters;
  auto eligible = [&](int i, int j) {
    return (g.Point(i, j) - p.base_station).norm() >= p.distance_floor;
  };
  long free_cells = 0;
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      if (eligible(i, j) && !measured_cells_.count(static_cast<long>(j) * g.nx + i)) ++free_cells;
    }
  }
  if (m < 1 || 2L * m > free_cells) {
    throw std::invalid_argument("measurements per draw must be between 1 and " +
                                std::to_string(free_cells / 2) + " (unmeasured cells / 2), got " +
                                std::to_string(m));
  }
  RandomStream random(seed, stream);
  std::unordered_set<long> taken;
  MeasurementSet out;
  while (static_cast<int>(out.values_db.size()) < m) {
    const auto k = static_cast<long>(random.Index(static_cast<std::uint64_t>(g.num_points())));
    const int i = static_cast<int>(k % g.nx), j = static_cast<int>(k / g.nx);
    if (!eligible(i, j) || measured_cells_.count(k) || !taken.insert(k).second) continue;
    out.positions.push_back(g.Point(i, j));
    out.values_db.push_back(truth_->gain_db(i, j));
  }
  return out;
}

ChannelUpdateTimings OnlineChannel::Update(const MeasurementSet& more,
                                           const std::vector<Eigen::Vector2d>* focus) {
  if (more.positions.size() != more.values_db.size()) {
    throw std::invalid_argument("online channel: positions and values differ in size");
  }
  for (size_t i = 0; i < more.positions.size(); ++i) {
    if (!measured_cells_.insert(CellIndex(more.positions[i])).second) continue;
    measurements_.positions.push_back(more.positions[i]);
    measurements_.values_db.push_back(more.values_db[i]);
  }
  if (num_measurements() < 3) {
    throw std::invalid_argument("online channel: need at least 3 measurements, have " +
                                std::to_string(num_measurements()));
  }
  ChannelUpdateTimings t;
  if (map_ != nullptr && !options_.refresh) return t;
  {
    const Stopwatch watch;
    if (options_.estimate) {
      try {
        EstimationOptions o = options_.estimation;
        if (predictor_ != nullptr) o.likelihood_start = estimated_;  // warm start (ML only)
        estimated_ = EstimateChannelParameters(measurements_, options_.truth, o);
        t.estimation_failed = false;
      } catch (const std::invalid_argument&) {
        // Too few pairs or no spatial correlation in the residuals: keep the last estimate.
        if (predictor_ == nullptr) throw;
        t.estimation_failed = true;
      }
    }
    t.estimate_seconds = watch.cpu();
  }
  {
    const Stopwatch watch;
    predictor_ =
        std::make_shared<GpChannelPredictor>(estimated_, measurements_, options_.predictor);
    t.factor_seconds = watch.cpu();
  }
  // The region of interest: whole cells of map_grid_ covering the focus points plus the margin
  // (at least 4 cells per side, as GridSpec requires).
  current_grid_ = map_grid_;
  if (focus != nullptr && !focus->empty() && options_.region_margin > 0.0) {
    const GridSpec& g = map_grid_;
    Eigen::Vector2d lo = focus->front(), hi = focus->front();
    for (const Eigen::Vector2d& q : *focus) {
      if (!q.allFinite()) continue;
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
    auto range = [](double a, double b, double origin, double h, int n, int* first, int* count) {
      int i0 = static_cast<int>(std::floor((a - origin) / h));
      int i1 = static_cast<int>(std::ceil((b - origin) / h));
      i0 = std::clamp(i0, 0, n);
      i1 = std::clamp(i1, 0, n);
      while (i1 - i0 < 4) {
        if (i0 > 0) --i0;
        if (i1 - i0 < 4 && i1 < n) ++i1;
      }
      *first = i0;
      *count = i1 - i0;
    };
    const double m = options_.region_margin;
    int i0 = 0, j0 = 0;
    range(lo.x() - m, hi.x() + m, g.x_min, g.resolution, g.nx, &i0, &current_grid_.nx);
    range(lo.y() - m, hi.y() + m, g.y_min, g.resolution, g.ny, &j0, &current_grid_.ny);
    current_grid_.x_min = g.x_min + i0 * g.resolution;
    current_grid_.y_min = g.y_min + j0 * g.resolution;
  }
  GridPrediction grid;
  {
    const Stopwatch watch;
    // Every region is part of map_grid_: one FFT size for all updates, so one FFTW plan.
    GridPredictionOptions o = options_.grid_prediction;
    o.min_fft_nx = std::max(o.min_fft_nx, map_grid_.nx);
    o.min_fft_ny = std::max(o.min_fft_ny, map_grid_.ny);
    grid = PredictOnGrid(*predictor_, current_grid_, o);
    t.grid_seconds = watch.cpu();
  }
  {
    const Stopwatch watch;
    map_ =
        std::make_shared<ChannelMap>(ChannelMap::FromPrediction(grid, *predictor_, options_.map));
    t.map_seconds = watch.cpu();
  }
  return t;
}

double OnlineChannel::TrueQuality(const Eigen::Vector2d& q) const { return true_quality_->At(q); }

void OnlineChannel::SampleLog10(double h,
                                std::vector<double>* x,
                                std::vector<double>* y,
                                Eigen::MatrixXd* predicted,
                                Eigen::MatrixXd* truth) const {
  const GridSpec& g = truth_->grid;
  const int nx = std::max(2, static_cast<int>(std::floor(g.nx * g.resolution / h)));
  const int ny = std::max(2, static_cast<int>(std::floor(g.ny * g.resolution / h)));
  x->resize(nx);
  y->resize(ny);
  for (int i = 0; i < nx; ++i) (*x)[i] = g.x_min + (i + 0.5) * h;
  for (int j = 0; j < ny; ++j) (*y)[j] = g.y_min + (j + 0.5) * h;
  predicted->resize(ny, nx);
  truth->resize(ny, nx);
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const Eigen::Vector2d q((*x)[i], (*y)[j]);
      double s = NAN;
      if (map_) map_->Evaluate(q, &s, nullptr, nullptr);
      (*predicted)(j, i) = std::log10(s);
      (*truth)(j, i) = std::log10(TrueQuality(q));
    }
  }
}

}  // namespace ocpb
