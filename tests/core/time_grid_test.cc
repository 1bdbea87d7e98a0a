#include "core/time_grid.h"

#include <cmath>
#include <vector>

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

TEST(TimeGrid, CoarsenedKeepsEveryFactorthNodeExactly) {
  const TimeGrid fine = TimeGrid::Uniform(0.5, 40.5, 400);
  const TimeGrid coarse = fine.Coarsened(2);
  ASSERT_EQ(coarse.intervals(), 200);
  EXPECT_TRUE(coarse.uniform());
  for (int k = 0; k <= 200; ++k) EXPECT_EQ(coarse.t(k), fine.t(2 * k)) << k;
  EXPECT_EQ(fine.Coarsened(1).points(), fine.points());
  const TimeGrid uneven = TimeGrid::FromPoints({0.0, 0.1, 0.3, 0.7, 1.5});
  const TimeGrid kept = uneven.Coarsened(2);
  EXPECT_FALSE(kept.uniform());
  EXPECT_EQ(kept.points(), (std::vector<double>{0.0, 0.3, 1.5}));
  EXPECT_EQ(uneven.Coarsened(4).points(), (std::vector<double>{0.0, 1.5}));
  EXPECT_THROW(uneven.Coarsened(3), std::invalid_argument);
  EXPECT_THROW(uneven.Coarsened(0), std::invalid_argument);
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
