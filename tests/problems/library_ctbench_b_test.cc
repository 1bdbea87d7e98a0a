// Tests specific to the ctbench_b library group (problems/library/ctbench_b/).
#include <cmath>

#include <gtest/gtest.h>

#include "problems/library/ctbench_b/beam.h"
#include "problems/library/ctbench_b/chain.h"
#include "problems/registry.h"

namespace ocpb {
namespace {

// The catenary constants of chain.h satisfy the three conditions of the optimum (both heights
// and the length), and the closed-form energy is the registered reference.
TEST(LibraryCtbenchB, ChainCatenaryConstantsSolveTheirConditions) {
  const double c = HangingChainOcp::kCatenaryC, m = HangingChainOcp::kCatenaryM,
               d = HangingChainOcp::kCatenaryD;
  const double s0 = -m / c, s1 = (1.0 - m) / c;
  EXPECT_NEAR(c * std::cosh(s0) + d, HangingChainOcp::kLeftHeight, 1e-12);
  EXPECT_NEAR(c * std::cosh(s1) + d, HangingChainOcp::kRightHeight, 1e-12);
  EXPECT_NEAR(c * (std::sinh(s1) - std::sinh(s0)), HangingChainOcp::kLength, 1e-12);
  EXPECT_NEAR(HangingChainOcp::CatenaryOptimum(), 5.068480110993416, 1e-12);
  EXPECT_EQ(FindProblem("chain").reference_value.value(), HangingChainOcp::CatenaryOptimum());
}

TEST(LibraryCtbenchB, BeamReferenceIsEightNinthsOverTheBound) {
  EXPECT_NEAR(FindProblem("beam").reference_value.value(), 80.0 / 9.0, 1e-14);
}

}  // namespace
}  // namespace ocpb
