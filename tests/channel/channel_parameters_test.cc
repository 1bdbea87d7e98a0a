#include "problems/channel/channel_parameters.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "problems/channel/gp_predictor.h"
#include "problems/channel/grid_predictor.h"
#include "problems/channel/multipath.h"
#include "problems/channel/paper_channel.h"
#include "problems/channel/parameter_estimator.h"

namespace ocpb {
namespace {

TEST(ChannelParameters, DefaultsAreThePapersAndValid) {
  const ChannelParameters p;
  EXPECT_EQ(p.k_pl, -41.34);
  EXPECT_EQ(p.n_pl, 3.86);
  EXPECT_EQ(p.xi, 3.20);
  EXPECT_EQ(p.eta, 3.09);
  EXPECT_EQ(p.rho, 1.64);
  EXPECT_EQ(p.base_station, Eigen::Vector2d(5.0, 5.0));
  std::string error;
  EXPECT_TRUE(p.IsValid(&error)) << error;
}

TEST(ChannelParameters, EveryOptionsStructDefaultsAreValid) {
  std::string error;
  EXPECT_TRUE(GridSpec().IsValid(&error)) << error;
  EXPECT_TRUE(QualityUnits().IsValid(&error)) << error;
  EXPECT_TRUE(MultipathOptions().IsValid(&error)) << error;
  EXPECT_TRUE(SimulationOptions().IsValid(&error)) << error;
  EXPECT_TRUE(EstimationOptions().IsValid(&error)) << error;
  EXPECT_TRUE(GpPredictorOptions().IsValid(&error)) << error;
  EXPECT_TRUE(GridPredictionOptions().IsValid(&error)) << error;
  EXPECT_TRUE(PaperChannelOptions().IsValid(&error)) << error;
}

TEST(ChannelParameters, InvalidFieldsAreNamed) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::string error;
  ChannelParameters p;
  p.xi = 0.0;
  EXPECT_FALSE(p.IsValid(&error));
  EXPECT_NE(error.find("xi"), std::string::npos);
  p = ChannelParameters();
  p.eta = nan;
  EXPECT_FALSE(p.IsValid(&error));
  EXPECT_NE(error.find("eta"), std::string::npos);
  p = ChannelParameters();
  p.distance_floor = -1.0;
  EXPECT_FALSE(p.IsValid(&error));
  EXPECT_NE(error.find("floor"), std::string::npos);
  p = ChannelParameters();
  p.base_station.x() = nan;
  EXPECT_FALSE(p.IsValid(nullptr));
  GridSpec g;
  g.nx = 3;
  EXPECT_FALSE(g.IsValid(&error));
  EstimationOptions e;
  e.eta_max = e.eta_min;
  EXPECT_FALSE(e.IsValid(&error));
  QualityUnits u;
  u.power_unit_scale = 0.0;
  EXPECT_FALSE(u.IsValid(&error));
  GridPredictionOptions gp;
  gp.tile_points = 1;
  EXPECT_FALSE(gp.IsValid(&error));
}

TEST(ChannelParameters, PathLossUsesTheFloor) {
  const ChannelParameters p;
  EXPECT_DOUBLE_EQ(p.PathLossDb(Eigen::Vector2d(6.0, 5.0)), -41.34);
  EXPECT_NEAR(p.PathLossDb(Eigen::Vector2d(15.0, 5.0)), -41.34 - 38.6, 1e-12);
  EXPECT_NEAR(p.PathLossDb(Eigen::Vector2d(5.0, 5.0)), -41.34 + 38.6, 1e-12);  // d = 0.1 m
  EXPECT_NEAR(p.PathLossDb(Eigen::Vector2d(5.05, 5.0)), -41.34 + 38.6, 1e-12);
}

TEST(ChannelParameters, PathLossDerivativesMatchFiniteDifferences) {
  const ChannelParameters p;
  const Eigen::Vector2d q(12.3, 7.9);
  Eigen::Vector2d g;
  Eigen::Matrix2d H;
  p.PathLossDb(q, &g, &H);
  const double h = 1e-5;
  for (int k = 0; k < 2; ++k) {
    const Eigen::Vector2d e = h * Eigen::Vector2d::Unit(k);
    EXPECT_NEAR(g[k], (p.PathLossDb(q + e) - p.PathLossDb(q - e)) / (2 * h), 1e-7);
    Eigen::Vector2d gp, gm;
    p.PathLossDb(q + e, &gp, nullptr);
    p.PathLossDb(q - e, &gm, nullptr);
    EXPECT_NEAR((H.col(k) - (gp - gm) / (2 * h)).norm(), 0.0, 1e-6);
  }
  p.PathLossDb(Eigen::Vector2d(5.02, 5.03), &g, &H);  // inside the floor
  EXPECT_EQ(g, Eigen::Vector2d::Zero());
  EXPECT_EQ(H, Eigen::Matrix2d::Zero());
}

TEST(GridSpec, PaperWorkspaceHas250000CellCentres) {
  const GridSpec g = GridSpec::Workspace(50.0, 50.0, 0.1);
  EXPECT_EQ(g.nx, 500);
  EXPECT_EQ(g.ny, 500);
  EXPECT_EQ(g.num_points(), 250000);
  EXPECT_NEAR(g.Point(0, 0).x(), 0.05, 1e-12);
  EXPECT_NEAR(g.Point(499, 499).y(), 49.95, 1e-12);
  EXPECT_DOUBLE_EQ(g.x_max(), 50.0);
  int i, j;
  g.NearestCell(Eigen::Vector2d(12.34, 49.99), &i, &j);
  EXPECT_EQ(i, 123);
  EXPECT_EQ(j, 499);
  g.NearestCell(Eigen::Vector2d(-3.0, 80.0), &i, &j);
  EXPECT_EQ(i, 0);
  EXPECT_EQ(j, 499);
  EXPECT_THROW(GridSpec::Workspace(0.2, 50.0, 0.1), std::invalid_argument);
  EXPECT_THROW(GridSpec::Workspace(50.0, 50.0, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace ocpb
