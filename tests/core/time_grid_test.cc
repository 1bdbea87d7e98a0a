#include "core/time_grid.h"

#include <cmath>

#include <gtest/gtest.h>

namespace ocpb {
namespace {

TEST(TimeGrid, UniformAndLocate) {
  const TimeGrid g = TimeGrid::Uniform(0.0, 40.0, 400);
  EXPECT_EQ(g.intervals(), 400);
  EXPECT_NEAR(g.h(17), 0.1, 1e-14);
  EXPECT_EQ(g.tf(), 40.0);
  EXPECT_EQ(g.Locate(0.0), 0);
  EXPECT_EQ(g.Locate(0.15), 1);
  EXPECT_EQ(g.Locate(40.0), 399);
  EXPECT_EQ(g.Locate(-1.0), 0);
  const TimeGrid r = g.Refined(3);
  EXPECT_EQ(r.intervals(), 1200);
  EXPECT_NEAR(r.t(3), g.t(1), 1e-12);
}

TEST(TimeGrid, RejectsInvalidGridsWithAClearMessage) {
  EXPECT_THROW(TimeGrid::Uniform(0.0, 1.0, 0), std::invalid_argument);
  EXPECT_THROW(TimeGrid::Uniform(1.0, 1.0, 10), std::invalid_argument);
  EXPECT_THROW(TimeGrid::Uniform(0.0, NAN, 10), std::invalid_argument);
  EXPECT_THROW(TimeGrid::FromPoints({0.0, 0.5, 0.5}), std::invalid_argument);
  try {
    TimeGrid::Uniform(0.0, -1.0, 10);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "time grid: need finite t0 < tf");
  }
}

}  // namespace
}  // namespace ocpb
