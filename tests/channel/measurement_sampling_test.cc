#include "problems/channel/measurement_sampling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

namespace ocpb {
namespace {

// A 10 m x 10 m channel at 0.5 m (20 x 20 cells), base station at (5.1, 5.1) with a 0.3 m
// floor: the cell centred at (5.25, 5.25), 0.21 m away, is never measured; its neighbours are.
SimulatedChannel SmallChannel() {
  ChannelParameters p;
  p.base_station = Eigen::Vector2d(5.1, 5.1);
  p.distance_floor = 0.3;
  SimulationOptions o;
  o.grid = GridSpec::Workspace(10.0, 10.0, 0.5);
  return SimulateChannel(p, o, 5);
}

// The cell (i, j) containing q, computed here independently of GridSpec::NearestCell.
std::pair<int, int> Cell(const Eigen::Vector2d& q) {
  auto clampi = [](int v) { return std::max(0, std::min(19, v)); };
  return {clampi(static_cast<int>(std::floor(q.x() / 0.5))),
          clampi(static_cast<int>(std::floor(q.y() / 0.5)))};
}

TEST(MeasureAlongPath, MeasuresEachVisitedCellOnceAtItsCentreInPathOrder) {
  const SimulatedChannel c = SmallChannel();
  // Along y = 2.1 from x = 0.1 to 3.9 in 0.2 m steps: 20 points in 8 cells; then back to the
  // first cell (already measured) and one point beyond the grid (clamped to the last cell).
  std::vector<Eigen::Vector2d> path;
  for (int k = 0; k < 20; ++k) path.emplace_back(0.1 + 0.2 * k, 2.1);
  path.emplace_back(0.2, 2.2);
  path.emplace_back(12.0, -3.0);
  const MeasurementSet m = MeasureAlongPath(c, path);
  ASSERT_EQ(m.positions.size(), 9u);
  ASSERT_EQ(m.values_db.size(), 9u);
  for (int k = 0; k < 8; ++k) {
    EXPECT_DOUBLE_EQ(m.positions[k].x(), 0.25 + 0.5 * k);
    EXPECT_DOUBLE_EQ(m.positions[k].y(), 2.25);
    EXPECT_EQ(m.values_db[k], c.gain_db(k, 4));
  }
  EXPECT_DOUBLE_EQ(m.positions[8].x(), 9.75);
  EXPECT_DOUBLE_EQ(m.positions[8].y(), 0.25);
  EXPECT_EQ(m.values_db[8], c.gain_db(19, 0));
}

TEST(MeasureAlongPath, EvenlySpacedSamplesAndTheDistanceFloor) {
  const SimulatedChannel c = SmallChannel();
  // 41 points along x = 7.3, y from 0 to 10 (0.25 m apart: two points per cell).
  std::vector<Eigen::Vector2d> path;
  for (int k = 0; k <= 40; ++k) path.emplace_back(7.3, 0.25 * k);
  // 5 samples: indices 0, 10, 20, 30, 40 (y = 0, 2.5, 5, 7.5, 10).
  const MeasurementSet five = MeasureAlongPath(c, path, 5);
  ASSERT_EQ(five.positions.size(), 5u);
  const double ys[5] = {0.0, 2.5, 5.0, 7.5, 10.0};
  for (int s = 0; s < 5; ++s) {
    const auto [i, j] = Cell(Eigen::Vector2d(7.3, ys[s]));
    EXPECT_EQ(five.positions[s], c.grid.Point(i, j)) << s;
    EXPECT_EQ(five.values_db[s], c.gain_db(i, j)) << s;
  }
  // One sample: the last point. More samples than cells: each cell once.
  const MeasurementSet one = MeasureAlongPath(c, path, 1);
  ASSERT_EQ(one.positions.size(), 1u);
  EXPECT_EQ(one.positions[0], c.grid.Point(14, 19));
  const MeasurementSet many = MeasureAlongPath(c, path, 200);
  EXPECT_EQ(many.positions.size(), 20u);
  std::set<std::pair<double, double>> distinct;
  for (const auto& q : many.positions) distinct.insert({q.x(), q.y()});
  EXPECT_EQ(distinct.size(), 20u);
  // A path through the base station: its cell (centre (5.25, 5.25), 0.21 m away, inside the
  // 0.3 m floor) is skipped, its neighbours are not.
  const std::vector<Eigen::Vector2d> through = {{4.6, 5.1}, {5.1, 5.1}, {5.6, 5.1}};
  const MeasurementSet t = MeasureAlongPath(c, through);
  ASSERT_EQ(t.positions.size(), 2u);
  EXPECT_EQ(t.positions[0], c.grid.Point(9, 10));
  EXPECT_EQ(t.positions[1], c.grid.Point(11, 10));
  // Empty path: nothing.
  EXPECT_TRUE(MeasureAlongPath(c, {}, 3).positions.empty());
}

TEST(MeasureAlongPath, BadInputs) {
  const SimulatedChannel c = SmallChannel();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<Eigen::Vector2d> path = {{1, 1}, {nan, 2}, {3, 3}};
  try {
    MeasureAlongPath(c, path);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("path point 1 is not finite"), std::string::npos);
  }
  // Evenly spaced samples that skip the bad point (indices 0 and 2) do not see it.
  EXPECT_EQ(MeasureAlongPath(c, path, 2).positions.size(), 2u);
  EXPECT_THROW(MeasureAlongPath(c, path, -1), std::invalid_argument);
}

}  // namespace
}  // namespace ocpb
