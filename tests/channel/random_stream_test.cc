#include "problems/channel/random_stream.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace ocpb {
namespace {

TEST(RandomStream, SameSeedAndStreamGiveTheSameNumbers) {
  RandomStream a(42, RandomStream::kShadowing), b(42, RandomStream::kShadowing);
  RandomStream c(42, RandomStream::kMultipath), d(43, RandomStream::kShadowing);
  bool differs_c = false, differs_d = false;
  for (int k = 0; k < 100; ++k) {
    const double x = a.Normal();
    EXPECT_EQ(x, b.Normal());
    differs_c |= x != c.Normal();
    differs_d |= x != d.Normal();
  }
  EXPECT_TRUE(differs_c);
  EXPECT_TRUE(differs_d);
}

TEST(RandomStream, KnownFirstValuesPinThePlatformIndependentAlgorithm) {
  // SplitMix64 of 0 is a published constant of the generator.
  EXPECT_EQ(RandomStream::SplitMix64(0), 0xE220A8397B1DCDAFULL);
  RandomStream a(1, 1);
  const double u = a.Uniform();
  EXPECT_GT(u, 0.0);
  EXPECT_LE(u, 1.0);
}

TEST(RandomStream, NormalMomentsWithinSamplingError) {
  RandomStream s(7, 99);
  const int n = 200000;
  double sum = 0.0, sum2 = 0.0, sum4 = 0.0;
  for (int k = 0; k < n; ++k) {
    const double x = s.Normal();
    sum += x;
    sum2 += x * x;
    sum4 += x * x * x * x;
  }
  // Standard errors: mean 1/sqrt(n), variance sqrt(2/n), 4th moment sqrt(96/n).
  EXPECT_NEAR(sum / n, 0.0, 4.0 / std::sqrt(n));
  EXPECT_NEAR(sum2 / n, 1.0, 4.0 * std::sqrt(2.0 / n));
  EXPECT_NEAR(sum4 / n, 3.0, 4.0 * std::sqrt(96.0 / n));
}

TEST(RandomStream, IndexIsUniformAndInRange) {
  RandomStream s(3, 5);
  const int bins = 7, n = 70000;
  std::vector<int> count(bins, 0);
  for (int k = 0; k < n; ++k) {
    const auto i = s.Index(bins);
    ASSERT_LT(i, static_cast<std::uint64_t>(bins));
    ++count[i];
  }
  // Chi-square with 6 degrees of freedom: 99.9% quantile 22.5.
  double chi2 = 0.0;
  for (int c : count) chi2 += (c - n / bins) * (c - n / bins) / double(n / bins);
  EXPECT_LT(chi2, 22.5);
  EXPECT_EQ(s.Index(1), 0u);
}

}  // namespace
}  // namespace ocpb
