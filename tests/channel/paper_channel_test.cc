#include "problems/channel/paper_channel.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace ocpb {
namespace {

// The factory on a small workspace (24 m x 24 m at 0.2 m); the paper's size is benchmarked.
PaperChannelOptions SmallOptions() {
  PaperChannelOptions o;
  o.simulation.grid = GridSpec::Workspace(24.0, 24.0, 0.2);
  return o;
}

TEST(MakePaperChannel, BuildsEverythingAndIsReproducible) {
  const PaperChannel a = MakePaperChannel(3, 200, SmallOptions());
  const PaperChannel b = MakePaperChannel(3, 200, SmallOptions());
  EXPECT_EQ(a.truth.gain_db, b.truth.gain_db);
  EXPECT_EQ(a.measurements.values_db, b.measurements.values_db);
  EXPECT_EQ(a.predictor->num_measurements(), 200);
  ASSERT_NE(a.map, nullptr);
  EXPECT_EQ(a.grid.mean_db.rows(), a.truth.grid.nx);
  // Prediction from 200 samples over 576 m^2 is better than path loss alone (which leaves the
  // shadowing and multipath, sqrt(3.2^2 + 1.64^2) = 3.6 dB).
  const double rmse = a.RmseDb();
  EXPECT_GT(rmse, 0.5);
  EXPECT_LT(rmse, 3.3);
  // Both providers agree at a grid point (the map interpolates there).
  const Eigen::Vector2d q = a.truth.grid.Point(40, 77);
  double exact, mapped;
  a.Quality(ChannelProvider::kExact)->Evaluate(q, &exact, nullptr, nullptr);
  a.Quality(ChannelProvider::kMap)->Evaluate(q, &mapped, nullptr, nullptr);
  EXPECT_NEAR(mapped / exact, 1.0, 1e-4);
  EXPECT_NE(a.Quality(ChannelProvider::kMap)->Describe().find("map bicubic"), std::string::npos);
  EXPECT_NE(a.Quality(ChannelProvider::kExact)->Describe().find("gp-exact"), std::string::npos);
}

TEST(MakePaperChannel, OnlineMeasurementsRefreshTheMap) {
  PaperChannel c = MakePaperChannel(4, 150, SmallOptions());
  const double before = c.RmseDb();
  MeasurementSet more;
  for (int k = 0; k < 150; ++k) {
    const int i = (k * 37) % c.truth.grid.nx, j = (k * 53 + 11) % c.truth.grid.ny;
    bool taken = false;
    for (const auto& q : c.predictor->positions().colwise()) {
      taken |= (q - c.truth.grid.Point(i, j)).norm() < 1e-9;
    }
    for (const auto& q : more.positions) taken |= (q - c.truth.grid.Point(i, j)).norm() < 1e-9;
    if (taken || (c.truth.grid.Point(i, j) - c.estimated.base_station).norm() < 0.1) continue;
    more.positions.push_back(c.truth.grid.Point(i, j));
    more.values_db.push_back(c.truth.gain_db(i, j));
  }
  c.predictor->AddMeasurements(more);
  c.RefreshMap();
  EXPECT_LT(c.RmseDb(), before);
}

TEST(MakePaperChannel, OracleParametersAndNoMap) {
  PaperChannelOptions o = SmallOptions();
  o.estimate = false;
  o.build_map = false;
  const PaperChannel c = MakePaperChannel(5, 100, o);
  EXPECT_EQ(c.estimated.xi, o.truth.xi);
  EXPECT_EQ(c.map, nullptr);
  EXPECT_THROW(c.Quality(ChannelProvider::kMap), std::logic_error);
  EXPECT_THROW(MakePaperChannel(5, 2, o), std::invalid_argument);
  EXPECT_EQ(ChannelProviderFromString("map"), ChannelProvider::kMap);
  EXPECT_THROW(ChannelProviderFromString("bicubic"), std::invalid_argument);
}

}  // namespace
}  // namespace ocpb
