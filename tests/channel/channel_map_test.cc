#include "problems/channel/channel_map.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "problems/channel/path_loss_only_channel.h"

namespace ocpb {
namespace {

// A map of the path-loss channel sampled on a 20 m x 20 m grid at 0.1 m.
ChannelMap PathLossMap(MapQuantity quantity, const PathLossOnlyChannel& truth, GridSpec* grid) {
  *grid = GridSpec::Workspace(20.0, 20.0, 0.1);
  Eigen::MatrixXd s(grid->nx, grid->ny);
  for (int j = 0; j < grid->ny; ++j) {
    for (int i = 0; i < grid->nx; ++i)
      truth.Evaluate(grid->Point(i, j), &s(i, j), nullptr, nullptr);
  }
  MapOptions o;
  o.quantity = quantity;
  return ChannelMap(*grid, s, o, truth.Describe());
}

TEST(ChannelMap, InterpolatesASmoothChannelAccurately) {
  const PathLossOnlyChannel truth;
  for (MapQuantity quantity : {MapQuantity::kLogS, MapQuantity::kS}) {
    GridSpec grid;
    const ChannelMap map = PathLossMap(quantity, truth, &grid);
    double worst = 0.0;
    for (double x = 8.03; x < 19.9; x += 0.37) {
      for (double y = 0.11; y < 19.9; y += 0.41) {
        double a, b;
        map.Evaluate(Eigen::Vector2d(x, y), &a, nullptr, nullptr);
        truth.Evaluate(Eigen::Vector2d(x, y), &b, nullptr, nullptr);
        worst = std::max(worst, std::abs(a / b - 1.0));
      }
    }
    // 3 m or more from the base station, s ~ d^3.86 is smooth at the 0.1 m scale.
    EXPECT_LT(worst, 1e-6) << ToString(quantity);
    EXPECT_NE(map.Describe().find(ToString(quantity)), std::string::npos);
  }
}

TEST(ChannelMap, DerivativesAreTheInterpolantsOwn) {
  const PathLossOnlyChannel truth;
  GridSpec grid;
  const ChannelMap map = PathLossMap(MapQuantity::kLogS, truth, &grid);
  auto S = [&](const Eigen::Vector2d& q) {
    double s;
    map.Evaluate(q, &s, nullptr, nullptr);
    return s;
  };
  for (const Eigen::Vector2d& q : {Eigen::Vector2d(3.21, 9.87), Eigen::Vector2d(15.5, 0.3)}) {
    double s;
    Eigen::Vector2d g;
    Eigen::Matrix2d H;
    map.Evaluate(q, &s, &g, &H);
    const double h = 1e-6;
    for (int k = 0; k < 2; ++k) {
      const Eigen::Vector2d e = h * Eigen::Vector2d::Unit(k);
      EXPECT_NEAR(g[k], (S(q + e) - S(q - e)) / (2 * h), 1e-6 * g.norm());
      Eigen::Vector2d gp, gm;
      map.Evaluate(q + e, nullptr, &gp, nullptr);
      map.Evaluate(q - e, nullptr, &gm, nullptr);
      EXPECT_NEAR((H.col(k) - (gp - gm) / (2 * h)).norm(), 0.0, 1e-5 * H.norm());
    }
  }
}

TEST(ChannelMap, ClampsOutsideTheWorkspace) {
  const PathLossOnlyChannel truth;
  GridSpec grid;
  const ChannelMap map = PathLossMap(MapQuantity::kLogS, truth, &grid);
  double inside, outside;
  Eigen::Vector2d g;
  map.Evaluate(Eigen::Vector2d(20.0, 7.0), &inside, nullptr, nullptr);
  map.Evaluate(Eigen::Vector2d(25.0, 7.0), &outside, &g, nullptr);
  EXPECT_DOUBLE_EQ(inside, outside);
  EXPECT_EQ(g[0], 0.0);
  EXPECT_NE(g[1], 0.0);
}

TEST(ChannelMap, RejectsBadValues) {
  const GridSpec grid = GridSpec::Workspace(2.0, 2.0, 0.1);
  EXPECT_THROW(ChannelMap(grid, Eigen::MatrixXd::Zero(grid.nx, grid.ny), {}, "zeros"),
               std::invalid_argument);
  EXPECT_THROW(ChannelMap(grid, Eigen::MatrixXd::Ones(3, 3), {}, "size"), std::invalid_argument);
  EXPECT_EQ(MapQuantityFromString("s"), MapQuantity::kS);
  EXPECT_THROW(MapQuantityFromString("log"), std::invalid_argument);
}

}  // namespace
}  // namespace ocpb
