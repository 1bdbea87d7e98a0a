#include "problems/channel/multipath.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace ocpb {
namespace {

TEST(Multipath, RicianK1456GivesThePapersRho) {
  const DbMoments m = RicianDbMoments(14.56);
  EXPECT_NEAR(m.std_db, 1.64, 0.005);
  EXPECT_NEAR(m.mean_db, -0.288, 0.002);
}

TEST(Multipath, RicianMomentsLimits) {
  // K -> 0 is Rayleigh: 10 log10 of an Exp(1) variable has mean -10 gamma / ln 10 = -2.5068 dB
  // and standard deviation 10 pi / (sqrt(6) ln 10) = 5.5697 dB.
  const DbMoments r = RicianDbMoments(1e-8);
  EXPECT_NEAR(r.mean_db, -2.5068, 1e-3);
  EXPECT_NEAR(r.std_db, 5.5697, 1e-3);
  // Large K: nearly deterministic, std ~ (10/ln10) sqrt(2/K).
  const DbMoments big = RicianDbMoments(1e4);
  EXPECT_NEAR(big.std_db, 4.3429 * std::sqrt(2.0 / 1e4), 2e-3);
  EXPECT_THROW(RicianDbMoments(0.0), std::invalid_argument);
}

TEST(Multipath, RicianDrawsMatchTheMomentsWithinSamplingError) {
  const MultipathOptions options;
  const DbMoments exact = RicianDbMoments(options.rician_k);
  RandomStream stream(11, RandomStream::kMultipath);
  const int n = 200000;
  double sum = 0.0, sum2 = 0.0, sum4 = 0.0;
  std::vector<double> x(n);
  for (int k = 0; k < n; ++k) {
    x[k] = DrawMultipathDb(options, 0.0, &stream);
    sum += x[k];
  }
  const double mean = sum / n;
  for (double v : x) {
    sum2 += (v - mean) * (v - mean);
    sum4 += std::pow(v - mean, 4);
  }
  const double var = sum2 / n, m4 = sum4 / n;
  // Standard errors of the sample mean and of the sample standard deviation
  // (delta method: sd(s) = sqrt((m4 - var^2) / n) / (2 s)).
  EXPECT_NEAR(mean, exact.mean_db, 4.0 * std::sqrt(var / n));
  const double se_sd = std::sqrt((m4 - var * var) / n) / (2.0 * std::sqrt(var));
  EXPECT_NEAR(std::sqrt(var), exact.std_db, 4.0 * se_sd);
  EXPECT_NEAR(std::sqrt(var), 1.64, 0.01);
}

TEST(Multipath, LogNormalAndNone) {
  MultipathOptions options;
  options.model = MultipathModel::kLogNormal;
  RandomStream stream(2, RandomStream::kMultipath);
  const int n = 100000;
  double sum2 = 0.0;
  for (int k = 0; k < n; ++k) sum2 += std::pow(DrawMultipathDb(options, 1.64, &stream), 2);
  EXPECT_NEAR(std::sqrt(sum2 / n), 1.64, 4.0 * 1.64 / std::sqrt(2.0 * n));
  options.model = MultipathModel::kNone;
  EXPECT_EQ(DrawMultipathDb(options, 1.64, &stream), 0.0);
  EXPECT_EQ(MultipathModelFromString("lognormal"), MultipathModel::kLogNormal);
  EXPECT_STREQ(ToString(MultipathModel::kRician), "rician");
  EXPECT_THROW(MultipathModelFromString("rayleigh"), std::invalid_argument);
}

}  // namespace
}  // namespace ocpb
