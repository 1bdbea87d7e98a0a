#include "problems/channel/grid_predictor.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>

#include "problems/channel/channel_simulator.h"
#include "problems/channel/fftw_planner.h"
#include "problems/channel/measurement_sampling.h"

namespace ocpb {
namespace {

// A 20 m x 20 m grid at 0.25 m (80 x 80) with 80 measurements at grid points.
struct SmallCase {
  ChannelParameters params;
  SimulatedChannel channel;
  MeasurementSet measurements;
  SmallCase() {
    SimulationOptions o;
    o.grid = GridSpec::Workspace(20.0, 20.0, 0.25);
    channel = SimulateChannel(params, o, 9);
    measurements = DrawRandomMeasurements(channel, 80, 9);
  }
};

void ExpectMatchesPointwise(const GpChannelPredictor& pred,
                            const GridPrediction& g,
                            double mean_tol,
                            double var_low,
                            double var_high) {
  double worst_mean = 0.0, worst_low = 0.0, worst_high = 0.0;
  // Every grid point of every third row and column (tiles of 20 x 20 points all covered).
  for (int j = 0; j < g.grid.ny; j += 3) {
    for (int i = 0; i < g.grid.nx; i += 3) {
      PointPrediction p;
      pred.Predict(g.grid.Point(i, j), 0, &p);
      worst_mean = std::max(worst_mean, std::abs(g.mean_db(i, j) - p.mean_db));
      const double dv = g.variance_db2(i, j) - p.variance_db2;
      worst_low = std::min(worst_low, dv);
      worst_high = std::max(worst_high, dv);
      ASSERT_NEAR(g.s(i, j),
                  ExpectedInverseCnr(g.mean_db(i, j), g.variance_db2(i, j), pred.options().units),
                  1e-12 * g.s(i, j));
    }
  }
  EXPECT_LT(worst_mean, mean_tol);
  EXPECT_GT(worst_low, var_low);
  EXPECT_LT(worst_high, var_high);
}

TEST(PredictOnGrid, ExactMethodEqualsThePointwisePredictor) {
  const SmallCase s;
  const GpChannelPredictor pred(s.params, s.measurements);
  GridPredictionOptions o;
  o.variance = GridVarianceMethod::kExact;
  const GridPrediction g = PredictOnGrid(pred, s.channel.grid, o);
  ExpectMatchesPointwise(pred, g, 1e-9, -1e-9, 1e-9);
  EXPECT_NE(g.method.find("exact"), std::string::npos);
}

TEST(PredictOnGrid, LocalVarianceIsAnUpperBoundCloseToExact) {
  const SmallCase s;
  const GpChannelPredictor pred(s.params, s.measurements);
  const GridPrediction g = PredictOnGrid(pred, s.channel.grid, {});
  // Mean: exact (FFT convolution + near terms). Variance: conditioning on fewer measurements
  // can only raise it; with R = 3.5 eta the excess is small.
  ExpectMatchesPointwise(pred, g, 1e-9, -1e-9, 5e-3);
}

TEST(PredictOnGrid, OffLatticeMeasurementsUseTheFarFieldInterpolation) {
  const SmallCase s;
  MeasurementSet shifted = s.measurements;
  for (auto& q : shifted.positions) q += Eigen::Vector2d(0.013, -0.021);
  const GpChannelPredictor pred(s.params, shifted);
  const GridPrediction g = PredictOnGrid(pred, s.channel.grid, {});
  ExpectMatchesPointwise(pred, g, 1e-7, -1e-9, 5e-3);
}

// Bit-for-bit the same with 1, 2 or 3 threads: on the lattice (the FFT convolution runs next to
// the tiles), and with half the measurements moved off it (near sums and the far field too).
TEST(PredictOnGrid, ThreadsDoNotChangeTheResult) {
  const SmallCase s;
  MeasurementSet mixed = s.measurements;
  for (size_t k = 0; k < mixed.positions.size(); k += 2) {
    mixed.positions[k] += Eigen::Vector2d(0.013, -0.021);
  }
  for (const MeasurementSet& m : {s.measurements, mixed}) {
    const GpChannelPredictor pred(s.params, m);
    GridPredictionOptions one;
    one.num_threads = 1;
    const GridPrediction a = PredictOnGrid(pred, s.channel.grid, one);
    for (int threads : {2, 3}) {
      GridPredictionOptions o;
      o.num_threads = threads;
      const GridPrediction b = PredictOnGrid(pred, s.channel.grid, o);
      EXPECT_EQ(a.mean_db, b.mean_db) << threads;
      EXPECT_EQ(a.variance_db2, b.variance_db2) << threads;
      EXPECT_EQ(a.s, b.s) << threads;
    }
  }
}

// A larger FFT (what the online re-planning asks for, to reuse one plan) is the same linear
// convolution: the mean agrees to rounding, the variance (no FFT) exactly.
TEST(PredictOnGrid, LargerFftGivesTheSameMean) {
  const SmallCase s;
  const GpChannelPredictor pred(s.params, s.measurements);
  GridPredictionOptions larger;
  larger.min_fft_nx = 130;
  larger.min_fft_ny = 97;
  const GridPrediction a = PredictOnGrid(pred, s.channel.grid, {});
  const GridPrediction b = PredictOnGrid(pred, s.channel.grid, larger);
  EXPECT_LT((a.mean_db - b.mean_db).cwiseAbs().maxCoeff(), 1e-11);
  EXPECT_GT((a.mean_db - b.mean_db).cwiseAbs().maxCoeff(), 0.0);  // another FFT really ran
  EXPECT_EQ(a.variance_db2, b.variance_db2);
  larger.min_fft_nx = -1;
  EXPECT_THROW(PredictOnGrid(pred, s.channel.grid, larger), std::invalid_argument);
}

TEST(CachedRealFft2dPlans, OnePairPerSizeReused) {
  const auto a = CachedRealFft2dPlans(40, 60);
  const auto b = CachedRealFft2dPlans(40, 60);
  const auto c = CachedRealFft2dPlans(60, 40);
  EXPECT_EQ(a.get(), b.get());
  EXPECT_NE(a.get(), c.get());
  EXPECT_EQ(c->ny, 60);
  EXPECT_EQ(c->nx, 40);
  // 16 other sizes push (40, 60) out of the cache; the holders keep theirs alive.
  for (int k = 1; k <= 16; ++k) CachedRealFft2dPlans(40 + k, 60);
  EXPECT_NE(CachedRealFft2dPlans(40, 60).get(), a.get());
  EXPECT_NE(a->forward, nullptr);
}

TEST(PredictOnGrid, RejectsInvalidOptions) {
  const SmallCase s;
  const GpChannelPredictor pred(s.params, s.measurements);
  GridPredictionOptions o;
  o.neighborhood_radius_in_eta = 0.0;
  EXPECT_THROW(PredictOnGrid(pred, s.channel.grid, o), std::invalid_argument);
}

}  // namespace
}  // namespace ocpb
