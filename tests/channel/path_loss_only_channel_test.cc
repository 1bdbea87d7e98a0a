#include "problems/channel/path_loss_only_channel.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace ocpb {
namespace {

TEST(PathLossOnlyChannel, ValueIsInverseCnrInWatts) {
  const PathLossOnlyChannel c;
  double s;
  // d = 10 m: Gamma = -41.34 - 38.6 = -79.94 dBm, CNR = 30.06 dB, s = 1e-3 / 10^3.006 W.
  c.Evaluate(Eigen::Vector2d(15.0, 5.0), &s, nullptr, nullptr);
  EXPECT_NEAR(s, 1e-3 * std::pow(10.0, -3.006), 1e-15);
  EXPECT_NE(c.Describe().find("path-loss"), std::string::npos);
}

TEST(PathLossOnlyChannel, DerivativesMatchFiniteDifferences) {
  const PathLossOnlyChannel c(ChannelParameters(), QualityUnits(), 4.0);
  auto S = [&](const Eigen::Vector2d& q) {
    double s;
    c.Evaluate(q, &s, nullptr, nullptr);
    return s;
  };
  for (const Eigen::Vector2d& q : {Eigen::Vector2d(20.0, 30.0), Eigen::Vector2d(5.7, 4.1)}) {
    double s;
    Eigen::Vector2d g;
    Eigen::Matrix2d H;
    c.Evaluate(q, &s, &g, &H);
    const double h = 1e-5;
    for (int k = 0; k < 2; ++k) {
      const Eigen::Vector2d e = h * Eigen::Vector2d::Unit(k);
      EXPECT_NEAR(g[k], (S(q + e) - S(q - e)) / (2 * h), 1e-6 * g.norm());
      Eigen::Vector2d gp, gm;
      c.Evaluate(q + e, nullptr, &gp, nullptr);
      c.Evaluate(q - e, nullptr, &gm, nullptr);
      EXPECT_NEAR((H.col(k) - (gp - gm) / (2 * h)).norm(), 0.0, 1e-6 * H.norm());
    }
  }
  Eigen::Vector2d g;
  Eigen::Matrix2d H;
  c.Evaluate(Eigen::Vector2d(5.0, 5.01), nullptr, &g, &H);  // inside the floor
  EXPECT_EQ(g, Eigen::Vector2d::Zero());
  EXPECT_EQ(H, Eigen::Matrix2d::Zero());
}

TEST(PathLossOnlyChannel, RejectsBadInput) {
  ChannelParameters p;
  p.eta = 0.0;
  EXPECT_THROW(PathLossOnlyChannel{p}, std::invalid_argument);
  EXPECT_THROW(PathLossOnlyChannel(ChannelParameters(), QualityUnits(), -1.0),
               std::invalid_argument);
}

}  // namespace
}  // namespace ocpb
