#include "problems/channel/shadowing_simulator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace ocpb {
namespace {

TEST(ShadowingSimulator, NextFftSizeHasSmallFactors) {
  EXPECT_EQ(NextFftSize(998), 1000);
  EXPECT_EQ(NextFftSize(254), 256);
  EXPECT_EQ(NextFftSize(11), 12);
  EXPECT_EQ(NextFftSize(1), 1);
}

TEST(ShadowingSimulator, PaperGridEmbeddingIsExact) {
  const ShadowingSimulator sim(GridSpec(), 3.2, 3.09);
  EXPECT_EQ(sim.embedding_nx(), 1000);
  EXPECT_EQ(sim.embedding_ny(), 1000);
  EXPECT_EQ(sim.clipped_fraction(), 0.0);  // no negative eigenvalue: exact covariance
  EXPECT_GT(sim.min_eigenvalue_ratio(), 0.0);
}

TEST(ShadowingSimulator, RejectsBadInput) {
  EXPECT_THROW(ShadowingSimulator(GridSpec(), 0.0, 3.0), std::invalid_argument);
  EXPECT_THROW(ShadowingSimulator(GridSpec(), 3.0, -1.0), std::invalid_argument);
  GridSpec g;
  g.nx = 2;
  EXPECT_THROW(ShadowingSimulator(g, 3.0, 3.0), std::invalid_argument);
}

TEST(ShadowingSimulator, SameSeedSameField) {
  GridSpec g;
  g.nx = g.ny = 32;
  const ShadowingSimulator sim(g, 3.2, 3.09);
  RandomStream a(5, RandomStream::kShadowing), b(5, RandomStream::kShadowing);
  EXPECT_EQ(sim.Draw(&a), sim.Draw(&b));
}

// Mean, variance and covariance at lags 0.5, 1, 3 and 6 m (along x, along y and diagonally)
// agree with xi^2 exp(-d/eta) within 4 standard errors of the average over 30 fixed seeds
// (standard error from the spread across seeds; fields are independent across seeds).
TEST(ShadowingSimulator, EmpiricalStatisticsMatchTheModel) {
  const double xi = 3.2, eta = 3.09;
  GridSpec g;
  g.nx = g.ny = 128;  // 12.8 m at 0.1 m
  const ShadowingSimulator sim(g, xi, eta);
  EXPECT_EQ(sim.clipped_fraction(), 0.0);
  struct Lag {
    int di, dj;
  };
  const std::vector<Lag> lags = {{5, 0}, {0, 10}, {6, 8}, {30, 0}, {0, 30}, {36, 48}, {60, 0}};
  const int seeds = 30;
  std::vector<double> means, vars;
  std::vector<std::vector<double>> covs(lags.size());
  for (int s = 0; s < seeds; ++s) {
    RandomStream stream(1000 + s, RandomStream::kShadowing);
    const Eigen::MatrixXd f = sim.Draw(&stream);
    means.push_back(f.mean());
    vars.push_back(f.array().square().mean());
    for (std::size_t l = 0; l < lags.size(); ++l) {
      const int di = lags[l].di, dj = lags[l].dj;
      const auto a = f.block(0, 0, g.nx - di, g.ny - dj).array();
      const auto b = f.block(di, dj, g.nx - di, g.ny - dj).array();
      covs[l].push_back((a * b).mean());
    }
  }
  auto check = [&](const std::vector<double>& v, double expected, const char* what) {
    double m = 0.0, m2 = 0.0;
    for (double x : v) m += x / v.size();
    for (double x : v) m2 += (x - m) * (x - m) / (v.size() - 1);
    const double se = std::sqrt(m2 / v.size());
    EXPECT_NEAR(m, expected, 4.0 * se) << what << " (standard error " << se << ")";
  };
  check(means, 0.0, "mean");
  check(vars, xi * xi, "variance");
  for (std::size_t l = 0; l < lags.size(); ++l) {
    const double d = g.resolution * std::hypot(lags[l].di, lags[l].dj);
    check(
        covs[l], xi * xi * std::exp(-d / eta), ("covariance at lag " + std::to_string(d)).c_str());
  }
}

}  // namespace
}  // namespace ocpb
