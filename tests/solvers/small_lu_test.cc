#include "solvers/small_lu.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/LU>
#include <Eigen/QR>

#include "core/types.h"
#include "solvers/all_finite.h"
#include "solvers/small_dims.h"

namespace ocpb {
namespace {

// A random n x n matrix with singular values spread log-uniformly over [1/condition, 1]:
// U diag(s) V^T with U, V the orthogonal factors of random matrices (seeded).
Mat SmallLuTestMatrix(int n, double condition, std::mt19937* rng) {
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  auto random = [&] {
    Mat m(n, n);
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) m(i, j) = uniform(*rng);
    }
    return m;
  };
  const Mat u = Eigen::HouseholderQR<Mat>(random()).householderQ();
  const Mat v = Eigen::HouseholderQR<Mat>(random()).householderQ();
  Vec s(n);
  for (int i = 0; i < n; ++i) s[i] = std::pow(condition, -(n > 1 ? i / (n - 1.0) : 0.0));
  return u * s.asDiagonal() * v.transpose();
}

// Solves a x = b with the small LU at compile-time size kN (0: runtime size) and with Eigen's
// partial-pivoting LU; expects both to succeed, the two solutions to agree to `tolerance`
// relative, and the small LU's residual to be backward stable (|a x - b| <= 1e-13 |a| |x|).
template <int kN>
void ExpectSmallLuSolvesLikeEigen(const Mat& a, const Vec& b, double tolerance) {
  const int n = static_cast<int>(a.rows());
  Mat lu = a;
  std::vector<int> pivot(n);
  ASSERT_TRUE(SmallLuFactor<kN>(lu.data(), pivot.data(), n));
  Vec x = b;
  SmallLuSolve<kN>(lu.data(), pivot.data(), n, x.data());
  const Vec expected = a.partialPivLu().solve(b);
  EXPECT_LE((x - expected).lpNorm<Eigen::Infinity>(),
            tolerance * expected.lpNorm<Eigen::Infinity>());
  const double backward = a.cwiseAbs().rowwise().sum().maxCoeff() * x.lpNorm<Eigen::Infinity>();
  EXPECT_LE((a * x - b).lpNorm<Eigen::Infinity>(), 1e-13 * backward);
}

// Runs ExpectSmallLuSolvesLikeEigen at the compile-time size n (1 .. 10) and at runtime size.
template <int... kSizes>
void ExpectBothKernelsSolveLikeEigen(std::integer_sequence<int, kSizes...>,
                                     const Mat& a,
                                     const Vec& b,
                                     double tolerance) {
  const int n = static_cast<int>(a.rows());
  ((kSizes == n ? ExpectSmallLuSolvesLikeEigen<kSizes>(a, b, tolerance) : void()), ...);
  ExpectSmallLuSolvesLikeEigen<0>(a, b, tolerance);
}

constexpr auto kSmallLuSizes = std::integer_sequence<int, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10>{};

TEST(SmallLu, SolvesLikeEigenOnRandomMatrices) {
  std::mt19937 rng(20261203);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (int n = 1; n <= 10; ++n) {
    for (int trial = 0; trial < 20; ++trial) {
      SCOPED_TRACE("n = " + std::to_string(n) + ", trial " + std::to_string(trial));
      Mat a(n, n);
      for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) a(i, j) = uniform(rng);
      }
      Vec b(n);
      for (int i = 0; i < n; ++i) b[i] = uniform(rng);
      // Condition of a random 10 x 10 matrix: rarely above 1e4; the same pivots as Eigen's.
      ExpectBothKernelsSolveLikeEigen(kSmallLuSizes, a, b, 1e-10);
    }
  }
}

TEST(SmallLu, SolvesNearSingularMatricesToTheirConditioning) {
  std::mt19937 rng(7);
  for (int n = 2; n <= 10; ++n) {
    for (const double condition : {1e6, 1e10}) {
      SCOPED_TRACE("n = " + std::to_string(n) + ", condition " + std::to_string(condition));
      const Mat a = SmallLuTestMatrix(n, condition, &rng);
      const Vec b = Vec::LinSpaced(n, -1.0, 2.0);
      // Forward error of both LUs: up to condition * eps each.
      ExpectBothKernelsSolveLikeEigen(kSmallLuSizes, a, b, condition * 1e-14);
    }
  }
}

TEST(SmallLu, RefusesSingularAndNonFiniteMatrices) {
  std::mt19937 rng(11);
  for (int n = 2; n <= 10; ++n) {
    SCOPED_TRACE("n = " + std::to_string(n));
    // Rank n - 1 in exact arithmetic: the last pivot is rounding noise (about 1e-16 relative).
    Mat a = SmallLuTestMatrix(n, 1e3, &rng);
    a.col(n - 1) = 0.5 * a.col(0) - 2.0 * a.col((n - 1) / 2);
    SmallLu runtime;
    EXPECT_FALSE(runtime.Compute(a.data(), n, n));
    Mat lu = a;
    std::vector<int> pivot(n);
    EXPECT_FALSE(SmallLuFactor<0>(lu.data(), pivot.data(), n));
    // Singular values down to 1e-18 of the largest: numerically singular.
    a = SmallLuTestMatrix(n, 1e18, &rng);
    EXPECT_FALSE(runtime.Compute(a.data(), n, n));
    a = SmallLuTestMatrix(n, 1e3, &rng);
    EXPECT_TRUE(runtime.Compute(a.data(), n, n));
    a(n - 1, 0) = NAN;
    EXPECT_FALSE(runtime.Compute(a.data(), n, n));
    a(n - 1, 0) = INFINITY;
    EXPECT_FALSE(runtime.Compute(a.data(), n, n));
  }
  const Mat zero = Mat::Zero(3, 3);
  SmallLu runtime;
  EXPECT_FALSE(runtime.Compute(zero.data(), 3, 3));
}

TEST(SmallLu, ComputeTakesALeadingDimensionAndSolvesColumns) {
  std::mt19937 rng(3);
  const Mat big = SmallLuTestMatrix(7, 1e2, &rng);
  // The top-left 4 x 4 block of a 7 x 7 matrix, read with leading dimension 7.
  const Mat a = big.topLeftCorner(4, 4);
  SmallLu runtime;
  ASSERT_TRUE(runtime.Compute(big.data(), 4, 7));
  EXPECT_EQ(runtime.size(), 4);
  // Three right-hand sides stored with leading dimension 6.
  Mat x = Mat::Zero(6, 3);
  x.topRows(4) << 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12;
  const Mat b = x.topRows(4);
  runtime.SolveColumns(x.data(), 3, 6);
  EXPECT_LE((a * x.topRows(4) - b).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(x.bottomRows(2).cwiseAbs().maxCoeff(), 0.0);  // rows past n untouched
}

// WithSmallDims passes the compile-time sizes it has and 0 (runtime) otherwise.
TEST(SmallDims, DispatchesCompiledPairsAndFallsBackToRuntime) {
  auto sizes = [](int nx, int nu) {
    return WithSmallDims(nx, nu, []<int kNx, int kNu>() { return std::make_pair(kNx, kNu); });
  };
  EXPECT_EQ(sizes(5, 3), std::make_pair(5, 3));
  EXPECT_EQ(sizes(1, 1), std::make_pair(1, 1));
  EXPECT_EQ(sizes(6, 2), std::make_pair(6, 2));
  EXPECT_EQ(sizes(7, 1), std::make_pair(0, 0));
  EXPECT_EQ(sizes(2, 4), std::make_pair(0, 0));
  EXPECT_EQ(sizes(0, 1), std::make_pair(0, 0));
}

// AllFinite is std::isfinite of every entry: true on finite values of any size (the largest
// included, whose x - x is still 0), false with an infinity or a NaN at any position, for
// lengths 0 .. 70 (the packed turns of four, every tail length, and the 64 entries of a node's
// PointHessian at nx + nu = 8), from an unaligned start as well.
TEST(AllFinite, IsIsFiniteOfEveryEntry) {
  const double inf = std::numeric_limits<double>::infinity();
  const double big = std::numeric_limits<double>::max();
  for (int n = 0; n <= 70; ++n) {
    std::vector<double> v(n);
    for (int i = 0; i < n; ++i) v[i] = (i % 3 == 0 ? big : -0.5 * i) * (i % 2 == 0 ? 1.0 : -1.0);
    EXPECT_TRUE(AllFinite(v.data(), n)) << n;
    for (int i = 0; i < n; ++i) {
      for (const double bad : {inf, -inf, std::numeric_limits<double>::quiet_NaN()}) {
        std::vector<double> w = v;
        w[i] = bad;
        EXPECT_FALSE(AllFinite(w.data(), n)) << n << " " << i << " " << bad;
        std::vector<double> shifted(n + 1, 0.0);  // the same values one double further
        std::copy(w.begin(), w.end(), shifted.begin() + 1);
        EXPECT_FALSE(AllFinite(shifted.data() + 1, n)) << n << " " << i << " " << bad;
      }
    }
  }
}

}  // namespace
}  // namespace ocpb
