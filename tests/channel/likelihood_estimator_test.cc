#include "problems/channel/likelihood_estimator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include <Eigen/Cholesky>
#include <Eigen/LU>

namespace ocpb {
namespace {

// A small problem: m random positions, values from path loss plus a correlated field drawn
// with the exact covariance (Cholesky), so the likelihood has a well-defined optimum.
struct Problem {
  Eigen::MatrixXd distances;
  Eigen::VectorXd x, y;
};

Problem MakeProblem(int m, double eta, double nugget, double sigma2, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(6.0, 30.0);
  std::normal_distribution<double> n;
  Eigen::Matrix2Xd q(2, m);
  for (int i = 0; i < m; ++i) q.col(i) = Eigen::Vector2d(u(rng), u(rng));
  Problem p;
  p.distances.resize(m, m);
  for (int j = 0; j < m; ++j) {
    for (int i = 0; i < m; ++i) p.distances(i, j) = (q.col(i) - q.col(j)).norm();
  }
  Eigen::MatrixXd cov = (1.0 - nugget) * (-p.distances.array() / eta).exp().matrix();
  cov.diagonal().array() = 1.0;
  cov *= sigma2;
  const Eigen::MatrixXd L = cov.llt().matrixL();
  Eigen::VectorXd z(m);
  for (int i = 0; i < m; ++i) z[i] = n(rng);
  p.x.resize(m);
  for (int i = 0; i < m; ++i)
    p.x[i] = -10.0 * std::log10((q.col(i) - Eigen::Vector2d(5, 5)).norm());
  p.y = (-40.0 + 3.5 * p.x.array()).matrix() + L * z;
  return p;
}

// -2 log L from the textbook formula with a dense inverse and determinant (no profiling):
// ML:   m log 2 pi + log det S + r' S^-1 r,
// REML: (m - p) log 2 pi + log det S + log det(H' S^-1 H) + r' S^-1 r,
// S = sigma2 R(eta, f), r = y - H beta, beta the GLS estimate.
double Direct(const Problem& p, double eta, double f, double sigma2, bool restricted) {
  const Eigen::Index m = p.y.size();
  Eigen::MatrixXd S = (1.0 - f) * (-p.distances.array() / eta).exp().matrix();
  S.diagonal().array() = 1.0;
  S *= sigma2;
  const Eigen::MatrixXd Si = S.inverse();
  Eigen::MatrixXd H(m, 2);
  H.col(0).setOnes();
  H.col(1) = p.x;
  const Eigen::Matrix2d A = H.transpose() * Si * H;
  const Eigen::Vector2d beta = A.llt().solve(H.transpose() * Si * p.y);
  const Eigen::VectorXd r = p.y - H * beta;
  const double two_pi = 2.0 * std::numbers::pi;
  double v = std::log(S.determinant()) + r.dot(Si * r);
  v += restricted ? (m - 2) * std::log(two_pi) + std::log(A.determinant()) : m * std::log(two_pi);
  return v;
}

TEST(LikelihoodEstimator, ProfiledLikelihoodMatchesTheTextbookFormula) {
  const Problem p = MakeProblem(40, 3.0, 0.2, 12.0, 1);
  for (bool restricted : {false, true}) {
    for (auto [eta, f] : {std::pair{3.0, 0.2}, std::pair{0.7, 0.05}, std::pair{4.5, 0.8}}) {
      LikelihoodFit fit;
      const double v = ProfiledNeg2LogLikelihood(p.distances, p.x, p.y, eta, f, restricted, &fit);
      // The profiled value is the full -2 log L at the closed-form sigma^2 ...
      EXPECT_NEAR(v, Direct(p, eta, f, fit.sigma2, restricted), 1e-9 * std::abs(v));
      // ... which minimizes it over sigma^2.
      EXPECT_LT(v, Direct(p, eta, f, 1.05 * fit.sigma2, restricted));
      EXPECT_LT(v, Direct(p, eta, f, 0.95 * fit.sigma2, restricted));
      EXPECT_EQ(fit.eta, eta);
      EXPECT_EQ(fit.nugget, f);
    }
  }
}

TEST(LikelihoodEstimator, BobyqaFindsTheMaximumOfTheBox) {
  const Problem p = MakeProblem(80, 3.0, 0.2, 12.0, 2);
  for (bool restricted : {false, true}) {
    LikelihoodFitOptions o;
    o.restricted = restricted;
    const LikelihoodFit fit = FitLikelihood(p.distances, p.x, p.y, 1.0, 0.5, o);
    // A 30 x 30 log grid over the box: no grid point beats the fit.
    double grid_best = HUGE_VAL;
    for (int a = 0; a < 30; ++a) {
      for (int b = 0; b < 30; ++b) {
        const double eta = std::exp(std::log(0.05) + a / 29.0 * std::log(5.0 / 0.05));
        const double f = std::exp(std::log(1e-4) + b / 29.0 * std::log(0.99 / 1e-4));
        grid_best = std::min(grid_best,
                             ProfiledNeg2LogLikelihood(p.distances, p.x, p.y, eta, f, restricted));
      }
    }
    EXPECT_LE(fit.neg2_log_likelihood, grid_best + 1e-3) << restricted;
    EXPECT_GT(fit.evaluations, 5);
    EXPECT_LT(fit.evaluations, o.max_evaluations);
    // Same optimum from a different start, to what the 1e-2 tolerance in log coordinates
    // allows: 0.02 in -2 log L is 2% of one unit of chi-square (the statistical resolution).
    const LikelihoodFit other = FitLikelihood(p.distances, p.x, p.y, 4.0, 0.01, o);
    EXPECT_NEAR(other.neg2_log_likelihood, fit.neg2_log_likelihood, 0.02);
    EXPECT_NEAR(std::log(other.eta), std::log(fit.eta), 0.05);
    // The path loss is the GLS estimate at the optimum: near the truth (-40, 3.5).
    EXPECT_NEAR(fit.n_pl, 3.5, 1.0);
  }
}

TEST(LikelihoodEstimator, BoundsAreRespectedAndReported) {
  // Values without spatial structure (pure noise around the path loss): the likelihood wants
  // all nugget, i.e. the upper bound of f.
  Problem p = MakeProblem(60, 3.0, 0.2, 12.0, 3);
  std::mt19937_64 rng(9);
  std::normal_distribution<double> n;
  for (int i = 0; i < p.y.size(); ++i) p.y[i] = -40.0 + 3.5 * p.x[i] + 2.0 * n(rng);
  LikelihoodFitOptions o;
  const LikelihoodFit fit = FitLikelihood(p.distances, p.x, p.y, 2.0, 0.2, o);
  EXPECT_GE(fit.eta, o.eta_min * (1.0 - 1e-12));
  EXPECT_LE(fit.eta, o.eta_max * (1.0 + 1e-12));
  EXPECT_GE(fit.nugget, o.nugget_min * (1.0 - 1e-12));
  EXPECT_LE(fit.nugget, o.nugget_max * (1.0 + 1e-12));
  EXPECT_TRUE(fit.nugget_at_bound || fit.eta_at_bound);
  EXPECT_NEAR(fit.sigma2, 4.0, 1.5);
}

}  // namespace
}  // namespace ocpb
