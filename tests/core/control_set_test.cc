#include "core/control_set.h"

#include <cmath>

#include <gtest/gtest.h>

namespace ocpb {
namespace {

TEST(ControlSet, ProductOfBallAndBoxProjectsBlockwise) {
  ControlSet set;
  set.AddBall(2, 0.5).AddBox(Vec::Constant(1, 0.0), Vec::Constant(1, 6.0));
  EXPECT_EQ(set.dimension(), 3);
  EXPECT_FALSE(set.IsBox());
  Vec u(3);
  u << 3.0, 4.0, 7.0;
  EXPECT_NEAR(set.Violation(u), 4.5, 1e-15);
  set.Project(u);
  EXPECT_NEAR(u[0], 0.3, 1e-15);
  EXPECT_NEAR(u[1], 0.4, 1e-15);
  EXPECT_EQ(u[2], 6.0);
  EXPECT_NEAR(set.Violation(u), 0.0, 1e-15);
  Vec lo, hi;
  set.BoundingBox(&lo, &hi);
  EXPECT_EQ(lo[0], -0.5);
  EXPECT_EQ(hi[2], 6.0);
}

TEST(ControlSet, NonFiniteControlsAreInfinitelyViolating) {
  const ControlSet set = ControlSet::Unbounded(2);
  EXPECT_EQ(set.Violation(Vec::Zero(2)), 0.0);
  EXPECT_TRUE(std::isinf(set.Violation(Vec::Constant(2, NAN))));
}

TEST(ControlSet, RejectsInvalidBlocks) {
  ControlSet set;
  EXPECT_THROW(set.AddBall(2, -1.0), std::invalid_argument);
  EXPECT_THROW(set.AddBall(2, NAN), std::invalid_argument);
  EXPECT_THROW(set.AddBox(Vec::Constant(1, 1.0), Vec::Constant(1, 0.0)), std::invalid_argument);
  EXPECT_THROW(set.AddBox(Vec::Constant(2, 0.0), Vec::Constant(1, 1.0)), std::invalid_argument);
}

}  // namespace
}  // namespace ocpb
