// The rank test and the performance profiles behind `ocpbench compare`, against values computed
// by hand and by brute-force enumeration (a separate code path: pair counting, no ranks).
#include "bench/cli/mann_whitney.h"

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "bench/cli/performance_profile.h"

namespace ocpb {
namespace {

std::vector<double> Range(double first, int n) {
  std::vector<double> v;
  for (int i = 0; i < n; ++i) v.push_back(first + i);
  return v;
}

TEST(MannWhitneyU, SeparatedSamplesGiveTheSmallestPOfTheirSizes) {
  // 2 / C(n_base + n_new, n_base), written out: what 1, 2, 3, 4 and 5 repeats can show at best.
  const struct {
    int n_base, n_new;
    double p;
  } kCases[] = {{1, 1, 1.0},
                {2, 2, 2.0 / 6},
                {3, 3, 2.0 / 20},
                {4, 4, 2.0 / 70},
                {5, 5, 2.0 / 252},
                {3, 5, 2.0 / 56}};
  for (const auto& c : kCases) {
    const RankTestResult slower = MannWhitneyU(Range(1, c.n_base), Range(100, c.n_new));
    EXPECT_TRUE(slower.exact);
    EXPECT_NEAR(slower.p_value, c.p, 1e-12) << c.n_base << " vs " << c.n_new;
    EXPECT_DOUBLE_EQ(slower.u, c.n_base * c.n_new);  // every new value is above every base one
    EXPECT_DOUBLE_EQ(slower.mean_u, c.n_base * c.n_new / 2.0);
    const RankTestResult faster = MannWhitneyU(Range(100, c.n_base), Range(1, c.n_new));
    EXPECT_NEAR(faster.p_value, c.p, 1e-12);
    EXPECT_DOUBLE_EQ(faster.u, 0.0);
    EXPECT_NEAR(SmallestTwoSidedP(c.n_base, c.n_new), c.p, 1e-12);
  }
}

TEST(MannWhitneyU, EqualSamplesGiveOne) {
  const RankTestResult same = MannWhitneyU({0.2, 0.2, 0.2}, {0.2, 0.2, 0.2});
  EXPECT_DOUBLE_EQ(same.u, same.mean_u);
  EXPECT_DOUBLE_EQ(same.p_value, 1.0);
  EXPECT_DOUBLE_EQ(MannWhitneyU({0.1, 0.3, 0.5}, {0.2, 0.3, 0.4}).p_value, 1.0);
}

TEST(MannWhitneyU, NaNsAreDroppedAndAnEmptySideSaysNothing) {
  const RankTestResult r = MannWhitneyU({1.0, NAN, 2.0}, {5.0, 6.0});
  EXPECT_EQ(r.n_base, 2);
  EXPECT_EQ(r.n_new, 2);
  EXPECT_NEAR(r.p_value, 2.0 / 6, 1e-12);
  const RankTestResult empty = MannWhitneyU({}, {1.0, 2.0});
  EXPECT_EQ(empty.n_base, 0);
  EXPECT_DOUBLE_EQ(empty.p_value, 1.0);
}

// The exact p-value by enumerating every split of the pooled sample, with U counted pair by pair.
double BruteForceP(const std::vector<double>& base, const std::vector<double>& next) {
  std::vector<double> pooled = base;
  pooled.insert(pooled.end(), next.begin(), next.end());
  const int n = static_cast<int>(pooled.size()), k = static_cast<int>(next.size());
  auto u_of = [](const std::vector<double>& b, const std::vector<double>& x) {
    double u = 0.0;
    for (double xi : x) {
      for (double bi : b) u += xi > bi ? 1.0 : (xi == bi ? 0.5 : 0.0);
    }
    return u;
  };
  const double mean = base.size() * next.size() / 2.0;
  const double observed = std::abs(u_of(base, next) - mean);
  int at_least = 0, total = 0;
  for (unsigned mask = 0; mask < (1u << n); ++mask) {
    if (__builtin_popcount(mask) != k) continue;
    std::vector<double> b, x;
    for (int i = 0; i < n; ++i) (mask >> i & 1u ? x : b).push_back(pooled[i]);
    ++total;
    at_least += std::abs(u_of(b, x) - mean) >= observed - 1e-9 ? 1 : 0;
  }
  return static_cast<double>(at_least) / total;
}

TEST(MannWhitneyU, ExactDistributionMatchesBruteForceWithTies) {
  std::mt19937 rng(20251202);  // fixed seed: the same samples every run
  std::uniform_int_distribution<int> size(1, 6), value(0, 4);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<double> base(size(rng)), next(size(rng));
    for (double& x : base) x = value(rng);  // few distinct values: many ties
    for (double& x : next) x = value(rng) + (trial % 3 == 0 ? 1 : 0);
    const RankTestResult r = MannWhitneyU(base, next);
    ASSERT_TRUE(r.exact);
    EXPECT_NEAR(r.p_value, BruteForceP(base, next), 1e-12) << "trial " << trial;
  }
}

TEST(MannWhitneyU, LargeSamplesUseTheNormalApproximation) {
  // 40 vs 40 interleaved: U = 820, mean 800, variance 40 * 40 * 81 / 12 = 10800, so
  // z = (20 - 0.5) / sqrt(10800) and p = erfc(z / sqrt 2) = 0.8511597790 (computed by hand).
  std::vector<double> base, next;
  for (int i = 0; i < 40; ++i) {
    base.push_back(2 * i);
    next.push_back(2 * i + 1);
  }
  const RankTestResult r = MannWhitneyU(base, next);
  EXPECT_FALSE(r.exact);
  EXPECT_DOUBLE_EQ(r.u, 820.0);
  EXPECT_NEAR(r.p_value, 0.8511597790430958, 1e-12);
  // Separated: z = (800 - 0.5) / sqrt(10800), p = 1.435e-14.
  const RankTestResult far = MannWhitneyU(Range(0, 40), Range(1000, 40));
  EXPECT_NEAR(far.p_value, 1.435085306393683e-14, 1e-16);
}

TEST(StratifiedMannWhitneyU, OneRepeatPerSideIsTheSignTest) {
  std::vector<std::pair<std::vector<double>, std::vector<double>>> strata;
  for (int k = 1; k <= 6; ++k) {
    strata.push_back({{1.0 * k}, {1.0 * k + 0.5}});  // every case slower
    EXPECT_NEAR(StratifiedMannWhitneyU(strata).p_value, std::min(1.0, 2 * std::pow(0.5, k)), 1e-12)
        << k << " cases";
  }
  strata.back() = {{7.0}, {6.0}};  // 5 of 6 slower: 2 (1 + 6) / 64
  EXPECT_NEAR(StratifiedMannWhitneyU(strata).p_value, 14.0 / 64, 1e-12);
}

TEST(StratifiedMannWhitneyU, CasesOfDifferentSpeedAreNotRankedAgainstEachOther) {
  // Each case 3 vs 3 and separated (U = 9 of 9); the sum is at its maximum with probability
  // (1/20)^2, two-sided 2/400. A pooled test would rank the fast case against the slow one.
  const RankTestResult r = StratifiedMannWhitneyU(
      {{{1.0, 1.1, 1.2}, {1.3, 1.4, 1.5}}, {{100.0, 101.0, 102.0}, {103.0, 104.0, 105.0}}});
  EXPECT_TRUE(r.exact);
  EXPECT_NEAR(r.p_value, 2.0 / 400, 1e-12);
  EXPECT_DOUBLE_EQ(r.u, 18.0);
  EXPECT_EQ(r.n_base, 6);
  // Pooled, the fast case's new times rank below the slow case's base times: p = 0.18.
  const std::vector<double> base = {1.0, 1.1, 1.2, 100.0, 101.0, 102.0};
  const std::vector<double> next = {1.3, 1.4, 1.5, 103.0, 104.0, 105.0};
  EXPECT_NEAR(MannWhitneyU(base, next).p_value, BruteForceP(base, next), 1e-12);
  EXPECT_GT(MannWhitneyU(base, next).p_value, 0.1);
}

TEST(StratifiedMannWhitneyU, ManyLargeStrataFallBackToTheNormalSum) {
  std::vector<std::pair<std::vector<double>, std::vector<double>>> strata(
      200, {Range(0, 20), Range(0.5, 20)});
  // Each case: U = 210 against a mean of 200, variance 20 * 20 * 41 / 12; the sum over 200 cases
  // is 2000 above its mean: z = (2000 - 0.5) / sqrt(200 * 400 * 41 / 12), p = erfc(z / sqrt 2)
  // (by hand). A shift too small for any one case to show is found over many.
  const RankTestResult r = StratifiedMannWhitneyU(strata);
  EXPECT_FALSE(r.exact);
  EXPECT_NEAR(r.p_value, 0.00013103566492046707, 1e-15);
  EXPECT_EQ(r.n_base, 4000);
  EXPECT_GT(MannWhitneyU(strata[0].first, strata[0].second).p_value, 0.5);
}

TEST(PerformanceProfile, RatiosToTheBestOfEachInstance) {
  const double inf = std::numeric_limits<double>::infinity();
  const auto ratios = PerformanceRatios({{"p1", "a", 1.0},
                                         {"p1", "b", 2.0},
                                         {"p2", "a", 3.0},
                                         {"p2", "b", NAN},  // not solved
                                         {"p3", "a", inf},  // nobody solved p3: left out
                                         {"p3", "b", NAN}});
  ASSERT_EQ(ratios.at("a").size(), 2u);
  EXPECT_DOUBLE_EQ(ratios.at("a")[0], 1.0);
  EXPECT_DOUBLE_EQ(ratios.at("a")[1], 1.0);
  EXPECT_DOUBLE_EQ(ratios.at("b")[0], 2.0);
  EXPECT_TRUE(std::isinf(ratios.at("b")[1]));
  EXPECT_DOUBLE_EQ(ProfileFraction(ratios.at("b"), 1.0), 0.0);
  EXPECT_DOUBLE_EQ(ProfileFraction(ratios.at("b"), 2.0), 0.5);
  EXPECT_DOUBLE_EQ(ProfileFraction(ratios.at("b"), inf), 0.5);
  EXPECT_DOUBLE_EQ(ProfileFraction(ratios.at("a"), 1.0), 1.0);
  EXPECT_DOUBLE_EQ(ProfileFraction({}, 2.0), 0.0);
}

}  // namespace
}  // namespace ocpb
