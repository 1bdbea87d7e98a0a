#include "transcriptions/sparse_builder.h"

#include <stdexcept>

#include <gtest/gtest.h>

namespace ocpb {
namespace {

TEST(TripletPattern, OverlappingBlocksShareSlots) {
  TripletPattern p(4, 4);
  const std::vector<int> a = p.Block({0, 1}, {1, 2});
  const std::vector<int> b = p.Block({1, 2}, {2, 3});
  EXPECT_EQ(p.size(), 7);  // (1,2) is in both blocks
  EXPECT_EQ(a[3], b[0]);   // slot of (1, 2)
  EXPECT_EQ(p.rows()[a[3]], 1);
  EXPECT_EQ(p.cols()[a[3]], 2);
  EXPECT_EQ(p.Slot(0, 1), a[0]);
  EXPECT_EQ(p.size(), 7);
}

TEST(TripletPattern, LowerOnlyDropsUpperEntries) {
  TripletPattern p(3, 3);
  const std::vector<int> s = p.Block({2, 0}, {0, 2}, true);
  // (2,0) kept, (2,2) kept, (0,0) kept, (0,2) dropped.
  EXPECT_GE(s[0], 0);
  EXPECT_GE(s[1], 0);
  EXPECT_GE(s[2], 0);
  EXPECT_EQ(s[3], -1);
  EXPECT_EQ(p.size(), 3);
  for (int k = 0; k < p.size(); ++k) EXPECT_GE(p.rows()[k], p.cols()[k]);
}

TEST(TripletPattern, RejectsEntriesOutsideTheMatrix) {
  TripletPattern p(2, 3);
  EXPECT_THROW(p.Slot(2, 0), std::logic_error);
  EXPECT_THROW(p.Slot(0, -1), std::logic_error);
}

}  // namespace
}  // namespace ocpb
