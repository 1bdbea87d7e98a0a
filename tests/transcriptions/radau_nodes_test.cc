#include "transcriptions/radau_nodes.h"

#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

namespace ocpb {
namespace {

// Integral of tau^p over [-1, 1].
double MonomialIntegral(int p) { return p % 2 == 1 ? 0.0 : 2.0 / (p + 1); }

TEST(RadauNodes, KnownSmallCases) {
  const RadauNodes r1 = ComputeRadauNodes(1);
  EXPECT_EQ(r1.points[0], -1.0);
  EXPECT_DOUBLE_EQ(r1.weights[0], 2.0);
  // K = 2: (P1 + P2)/(1 + x) = (3x - 1)/2, root 1/3; weights 1/2 and 3/2.
  const RadauNodes r2 = ComputeRadauNodes(2);
  EXPECT_NEAR(r2.points[1], 1.0 / 3.0, 1e-15);
  EXPECT_NEAR(r2.weights[0], 0.5, 1e-15);
  EXPECT_NEAR(r2.weights[1], 1.5, 1e-15);
  // K = 3: roots (1 -+ sqrt 6)/5, weights 2/9, (16 + sqrt 6)/18, (16 - sqrt 6)/18.
  const RadauNodes r3 = ComputeRadauNodes(3);
  const double s6 = std::sqrt(6.0);
  EXPECT_NEAR(r3.points[1], (1.0 - s6) / 5.0, 1e-15);
  EXPECT_NEAR(r3.points[2], (1.0 + s6) / 5.0, 1e-15);
  EXPECT_NEAR(r3.weights[0], 2.0 / 9.0, 1e-15);
  EXPECT_NEAR(r3.weights[1], (16.0 + s6) / 18.0, 1e-14);
  EXPECT_NEAR(r3.weights[2], (16.0 - s6) / 18.0, 1e-14);
}

// The quadrature is exact exactly up to degree 2K - 2 (Radau), and the points are roots of
// P_{K-1} + P_K.
TEST(RadauNodes, QuadratureExactToDegree2KMinus2AndNotBeyond) {
  for (int K = 1; K <= kMaxRadauPoints; K += (K < 12 ? 1 : 7)) {
    const RadauNodes r = ComputeRadauNodes(K);
    ASSERT_EQ(r.points.size(), K);
    EXPECT_EQ(r.points[0], -1.0);
    for (int i = 1; i < K; ++i) {
      EXPECT_GT(r.points[i], r.points[i - 1]);
      double a, da, b, db;
      LegendreAndDerivative(K - 1, r.points[i], &a, &da);
      LegendreAndDerivative(K, r.points[i], &b, &db);
      EXPECT_NEAR(a + b, 0.0, 1e-13) << "K " << K << " i " << i;
    }
    EXPECT_LT(r.points[K - 1], 1.0);
    for (int p = 0; p <= 2 * K - 2; ++p) {
      const double q = (r.weights.array() * r.points.array().pow(p)).sum();
      EXPECT_NEAR(q, MonomialIntegral(p), 1e-13) << "K " << K << " degree " << p;
    }
    if (K <= 10) {  // beyond, the error on tau^(2K-1) drops below what a test can tell from 0
      const int p = 2 * K - 1;
      const double q = (r.weights.array() * r.points.array().pow(p)).sum();
      EXPECT_GT(std::abs(q - MonomialIntegral(p)), 1e-6) << "K " << K << " should not be exact";
    }
  }
}

// D differentiates every polynomial of degree <= K exactly at the LGR points.
TEST(RadauNodes, DifferentiationMatrixIsExactForDegreeK) {
  for (int K : {1, 2, 3, 5, 8, 15}) {
    const RadauNodes r = ComputeRadauNodes(K);
    ASSERT_EQ(r.differentiation.rows(), K);
    ASSERT_EQ(r.differentiation.cols(), K + 1);
    for (int p = 0; p <= K; ++p) {
      const Vec values = r.support.array().pow(p);
      const Vec expected = p == 0 ? Vec::Zero(K) : Vec(p * r.points.array().pow(p - 1));
      EXPECT_LT((r.differentiation * values - expected).cwiseAbs().maxCoeff(), 1e-11 * (1 + K * K))
          << "K " << K << " degree " << p;
    }
  }
}

TEST(RadauNodes, LagrangeBasisInterpolatesAndIsExactAtNodes) {
  const RadauNodes r = ComputeRadauNodes(4);
  Vec basis(4);
  LagrangeBasis(r.points, r.point_weights, r.points[2], basis);
  EXPECT_EQ(basis, Vec::Unit(4, 2));
  // A cubic is reproduced anywhere in [-1, 1] (the control polynomial has degree K - 1 = 3).
  const auto cubic = [](double t) { return 0.3 - t + 2.0 * t * t - 0.7 * t * t * t; };
  Vec values(4);
  for (int i = 0; i < 4; ++i) values[i] = cubic(r.points[i]);
  for (double t : {-0.95, -0.2, 0.41, 0.99, 1.0}) {
    LagrangeBasis(r.points, r.point_weights, t, basis);
    EXPECT_NEAR(basis.dot(values), cubic(t), 1e-13);
    EXPECT_NEAR(basis.sum(), 1.0, 1e-14);
  }
}

TEST(RadauNodes, RejectsBadDegree) {
  EXPECT_THROW(ComputeRadauNodes(0), std::invalid_argument);
  EXPECT_THROW(ComputeRadauNodes(kMaxRadauPoints + 1), std::invalid_argument);
}

}  // namespace
}  // namespace ocpb
