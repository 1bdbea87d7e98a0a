#include "problems/channel/grid_predictor.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>

#include "problems/channel/channel_simulator.h"
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

TEST(PredictOnGrid, ThreadsDoNotChangeTheResult) {
  const SmallCase s;
  const GpChannelPredictor pred(s.params, s.measurements);
  GridPredictionOptions one, two;
  one.num_threads = 1;
  two.num_threads = 2;
  const GridPrediction a = PredictOnGrid(pred, s.channel.grid, one);
  const GridPrediction b = PredictOnGrid(pred, s.channel.grid, two);
  EXPECT_EQ(a.mean_db, b.mean_db);
  EXPECT_EQ(a.variance_db2, b.variance_db2);
  EXPECT_EQ(a.s, b.s);
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
