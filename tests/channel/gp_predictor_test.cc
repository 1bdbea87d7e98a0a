#include "problems/channel/gp_predictor.h"

#include <gtest/gtest.h>

#include <Eigen/LU>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "problems/channel/random_stream.h"

namespace ocpb {
namespace {

// m measurements at random positions in [0, 20]^2 (away from the base station) with path
// loss plus noise; the paper's parameters.
MeasurementSet Synthetic(int m, std::uint64_t seed) {
  RandomStream r(seed, 77);
  const ChannelParameters p;
  MeasurementSet set;
  while (static_cast<int>(set.positions.size()) < m) {
    const Eigen::Vector2d q(20.0 * r.Uniform(), 20.0 * r.Uniform());
    if ((q - p.base_station).norm() < 0.5) continue;
    set.positions.push_back(q);
    set.values_db.push_back(p.PathLossDb(q) + 3.0 * r.Normal());
  }
  return set;
}

// The paper's formulas with a dense inverse, as an independent reference.
void Reference(const ChannelParameters& p,
               const MeasurementSet& set,
               const Eigen::Vector2d& q,
               double* mean,
               double* var) {
  const int m = static_cast<int>(set.positions.size());
  Eigen::MatrixXd phi(m, m);
  Eigen::VectorXd psi(m), r(m);
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < m; ++j) {
      phi(i, j) = p.xi * p.xi * std::exp(-(set.positions[i] - set.positions[j]).norm() / p.eta);
    }
    phi(i, i) += p.rho * p.rho;
    psi[i] = p.xi * p.xi * std::exp(-(q - set.positions[i]).norm() / p.eta);
    const double h = -10.0 * std::log10((set.positions[i] - p.base_station).norm());
    r[i] = set.values_db[i] - (p.k_pl + p.n_pl * h);
  }
  const Eigen::MatrixXd inv = phi.fullPivLu().inverse();
  *mean = p.PathLossDb(q) + psi.dot(inv * r);
  *var = p.xi * p.xi + p.rho * p.rho - psi.dot(inv * psi);
}

TEST(GpChannelPredictor, MatchesThePapersFormulas) {
  const ChannelParameters p;
  const MeasurementSet set = Synthetic(40, 1);
  const GpChannelPredictor pred(p, set);
  for (const Eigen::Vector2d& q : {Eigen::Vector2d(3.3, 17.1),
                                   Eigen::Vector2d(12.0, 12.0),
                                   Eigen::Vector2d(40.0, 2.0),
                                   set.positions[7]}) {
    double mean, var;
    Reference(p, set, q, &mean, &var);
    EXPECT_NEAR(pred.Mean(q), mean, 1e-9);
    EXPECT_NEAR(pred.Variance(q), var, 1e-9);
    double s;
    pred.Evaluate(q, &s, nullptr, nullptr);
    EXPECT_NEAR(s / ExpectedInverseCnr(mean, var, QualityUnits()), 1.0, 1e-9);
  }
  // Far from every measurement the prediction reverts to path loss with the prior variance.
  EXPECT_NEAR(
      pred.Mean(Eigen::Vector2d(400.0, 400.0)), p.PathLossDb(Eigen::Vector2d(400, 400)), 1e-9);
  EXPECT_NEAR(pred.Variance(Eigen::Vector2d(400.0, 400.0)), pred.PriorVariance(), 1e-9);
  EXPECT_NE(pred.Describe().find("gp-exact m=40"), std::string::npos);
}

// Central differences: gradient h = 1e-5 (error ~ h^2 f''' + eps f / h), Hessian from the
// analytic gradient. Points at least 0.2 m from every measurement (the kernel's kinks) and
// outside the distance floor.
TEST(GpChannelPredictor, DerivativesMatchFiniteDifferences) {
  const ChannelParameters p;
  const MeasurementSet set = Synthetic(60, 2);
  const GpChannelPredictor pred(p, set);
  RandomStream r(3, 1);
  int tested = 0;
  while (tested < 25) {
    const Eigen::Vector2d q(22.0 * r.Uniform() - 1.0, 22.0 * r.Uniform() - 1.0);
    double dmin = (q - p.base_station).norm();
    for (const auto& qi : set.positions) dmin = std::min(dmin, (q - qi).norm());
    if (dmin < 0.2) continue;
    ++tested;
    PointPrediction a;
    pred.Predict(q, 2, &a);
    double s;
    Eigen::Vector2d gs;
    Eigen::Matrix2d hs;
    pred.Evaluate(q, &s, &gs, &hs);
    const double h = 1e-5;
    for (int k = 0; k < 2; ++k) {
      const Eigen::Vector2d e = h * Eigen::Vector2d::Unit(k);
      PointPrediction plus, minus;
      pred.Predict(q + e, 1, &plus);
      pred.Predict(q - e, 1, &minus);
      EXPECT_NEAR(a.mean_grad[k], (plus.mean_db - minus.mean_db) / (2 * h), 1e-6);
      EXPECT_NEAR(a.variance_grad[k], (plus.variance_db2 - minus.variance_db2) / (2 * h), 1e-6);
      EXPECT_NEAR(
          (a.mean_hess.col(k) - (plus.mean_grad - minus.mean_grad) / (2 * h)).norm(), 0.0, 1e-5);
      EXPECT_NEAR(
          (a.variance_hess.col(k) - (plus.variance_grad - minus.variance_grad) / (2 * h)).norm(),
          0.0,
          1e-5);
      double sp, sm;
      Eigen::Vector2d gp, gm;
      pred.Evaluate(q + e, &sp, &gp, nullptr);
      pred.Evaluate(q - e, &sm, &gm, nullptr);
      EXPECT_NEAR(gs[k], (sp - sm) / (2 * h), 1e-6 * gs.norm() + 1e-18);
      EXPECT_NEAR((hs.col(k) - (gp - gm) / (2 * h)).norm(), 0.0, 1e-5 * hs.norm() + 1e-18);
    }
    EXPECT_NEAR((a.variance_hess - a.variance_hess.transpose()).norm(), 0.0, 1e-12);
  }
}

TEST(GpChannelPredictor, KinksAtMeasurementsGiveFiniteDerivatives) {
  const ChannelParameters p;
  const MeasurementSet set = Synthetic(20, 4);
  const GpChannelPredictor pred(p, set);
  double s;
  Eigen::Vector2d g;
  Eigen::Matrix2d H;
  pred.Evaluate(set.positions[3], &s, &g, &H);
  EXPECT_TRUE(std::isfinite(s) && g.allFinite() && H.allFinite());
  // The variance at a measurement is below the prior, and positive everywhere.
  EXPECT_LT(pred.Variance(set.positions[3]), pred.PriorVariance());
  EXPECT_GT(pred.Variance(set.positions[3]), 0.0);
}

TEST(GpChannelPredictor, AddMeasurementsEqualsRebuilding) {
  const ChannelParameters p;
  const MeasurementSet all = Synthetic(50, 5);
  MeasurementSet first, second;
  for (int i = 0; i < 50; ++i) {
    MeasurementSet& dst = i < 35 ? first : second;
    dst.positions.push_back(all.positions[i]);
    dst.values_db.push_back(all.values_db[i]);
  }
  const GpChannelPredictor fresh(p, all);
  GpChannelPredictor bordered(p, first), refactored(p, first);
  bordered.AddMeasurements(second, GpChannelPredictor::UpdateMethod::kBorderedCholesky);
  refactored.AddMeasurements(second, GpChannelPredictor::UpdateMethod::kRefactorize);
  EXPECT_EQ(bordered.num_measurements(), 50);
  EXPECT_NEAR((bordered.alpha() - fresh.alpha()).norm(), 0.0, 1e-10);
  EXPECT_NEAR((refactored.alpha() - fresh.alpha()).norm(), 0.0, 1e-10);
  EXPECT_NEAR((bordered.cholesky_factor() - fresh.cholesky_factor()).norm(), 0.0, 1e-10);
  const Eigen::Vector2d q(7.7, 13.1);
  EXPECT_NEAR(bordered.Variance(q), fresh.Variance(q), 1e-10);
  EXPECT_NEAR(bordered.Mean(q), fresh.Mean(q), 1e-10);
}

TEST(GpChannelPredictor, BadInputsGiveClearErrors) {
  const ChannelParameters p;
  MeasurementSet set = Synthetic(5, 6);
  auto message = [&](const MeasurementSet& s, const GpPredictorOptions& o) -> std::string {
    try {
      GpChannelPredictor pred(p, s, o);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "no error";
  };
  MeasurementSet two = set;
  two.positions.resize(2);
  two.values_db.resize(2);
  EXPECT_NE(message(two, {}).find("at least 3"), std::string::npos);
  MeasurementSet bad = set;
  bad.values_db[1] = std::numeric_limits<double>::infinity();
  EXPECT_NE(message(bad, {}).find("non-finite"), std::string::npos);
  bad = set;
  bad.positions[2].y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(message(bad, {}).find("non-finite"), std::string::npos);
  bad = set;
  bad.positions[4] = Eigen::Vector2d(5.0, 5.05);
  EXPECT_NE(message(bad, {}).find("distance floor"), std::string::npos);
  // Coincident positions: an error by default, merged (averaged) on request.
  MeasurementSet twin = set;
  twin.positions.push_back(set.positions[1]);
  twin.values_db.push_back(set.values_db[1] + 2.0);
  EXPECT_NE(message(twin, {}).find("coincides"), std::string::npos);
  GpPredictorOptions merge;
  merge.merge_coincident = true;
  const GpChannelPredictor merged(p, twin, merge);
  EXPECT_EQ(merged.num_measurements(), 5);
  EXPECT_NEAR(merged.values()[1], set.values_db[1] + 1.0, 1e-12);
  // A rejected batch leaves the predictor unchanged.
  GpChannelPredictor pred(p, set);
  const Eigen::VectorXd alpha = pred.alpha();
  MeasurementSet more;
  more.positions = {Eigen::Vector2d(30, 30), set.positions[0]};
  more.values_db = {-90, -80};
  EXPECT_THROW(pred.AddMeasurements(more), std::invalid_argument);
  EXPECT_EQ(pred.num_measurements(), 5);
  EXPECT_EQ(pred.alpha(), alpha);
  ChannelParameters bad_p;
  bad_p.rho = 0.0;
  EXPECT_THROW(GpChannelPredictor(bad_p, set), std::invalid_argument);
}

}  // namespace
}  // namespace ocpb
