#include "transcriptions/radau_nodes.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace ocpb {

void LegendreAndDerivative(int n, double x, double* p, double* dp) {
  // (m+1) P_{m+1} = (2m+1) x P_m - m P_{m-1};  P'_{m+1} = P'_{m-1} + (2m+1) P_m.
  double p_prev = 1.0, p_cur = x;      // P_0, P_1
  double dp_prev = 0.0, dp_cur = 1.0;  // P_0', P_1'
  if (n == 0) {
    *p = 1.0;
    *dp = 0.0;
    return;
  }
  for (int m = 1; m < n; ++m) {
    const double p_next = ((2.0 * m + 1.0) * x * p_cur - m * p_prev) / (m + 1.0);
    const double dp_next = dp_prev + (2.0 * m + 1.0) * p_cur;
    p_prev = p_cur;
    p_cur = p_next;
    dp_prev = dp_cur;
    dp_cur = dp_next;
  }
  *p = p_cur;
  *dp = dp_cur;
}

Vec BarycentricWeights(const Vec& x) {
  const int n = static_cast<int>(x.size());
  Vec v(n);
  for (int j = 0; j < n; ++j) {
    double prod = 1.0;
    for (int m = 0; m < n; ++m) {
      if (m != j) prod *= x[j] - x[m];
    }
    v[j] = 1.0 / prod;
  }
  return v / v.cwiseAbs().maxCoeff();
}

void LagrangeBasis(const Vec& x, const Vec& v, double t, VecRef basis) {
  const int n = static_cast<int>(x.size());
  for (int j = 0; j < n; ++j) {
    if (t == x[j]) {
      basis.setZero();
      basis[j] = 1.0;
      return;
    }
  }
  double sum = 0.0;
  for (int j = 0; j < n; ++j) {
    basis[j] = v[j] / (t - x[j]);
    sum += basis[j];
  }
  basis /= sum;
}

RadauNodes ComputeRadauNodes(int K) {
  if (K < 1 || K > kMaxRadauPoints) {
    throw std::invalid_argument("LGR: the number of points per interval (degree) must be in [1, " +
                                std::to_string(kMaxRadauPoints) + "], got " + std::to_string(K));
  }
  RadauNodes r;
  r.K = K;
  r.points.resize(K);
  r.points[0] = -1.0;
  // Interior roots of q(x) = (P_{K-1}(x) + P_K(x)) / (1 + x): Newton on q with the roots already
  // found divided out, x <- x - 1 / (q'/q - sum_j 1/(x - x_j)), where
  // q'/q = (P_{K-1}' + P_K') / (P_{K-1} + P_K) - 1 / (1 + x).
  for (int i = 1; i < K; ++i) {
    double x = -std::cos(2.0 * std::numbers::pi * i / (2.0 * K - 1.0));
    for (int iter = 0; iter < 100; ++iter) {
      double a, da, b, db;
      LegendreAndDerivative(K - 1, x, &a, &da);
      LegendreAndDerivative(K, x, &b, &db);
      double ratio = (da + db) / (a + b) - 1.0 / (1.0 + x);
      for (int j = 1; j < i; ++j) ratio -= 1.0 / (x - r.points[j]);
      const double step = 1.0 / ratio;
      x -= step;
      if (std::abs(step) < 1e-16 * std::max(1.0, std::abs(x))) break;
    }
    r.points[i] = x;
  }
  std::sort(r.points.begin(), r.points.end());
  for (int i = 1; i < K; ++i) {
    if (!(r.points[i] > r.points[i - 1]) || !(r.points[i] < 1.0)) {
      throw std::runtime_error("LGR: Newton's method did not find K distinct points for K = " +
                               std::to_string(K));
    }
  }
  r.weights.resize(K);
  const double k2 = static_cast<double>(K) * K;
  r.weights[0] = 2.0 / k2;
  for (int i = 1; i < K; ++i) {
    double p, dp;
    LegendreAndDerivative(K - 1, r.points[i], &p, &dp);
    r.weights[i] = (1.0 - r.points[i]) / (k2 * p * p);
  }
  r.support.resize(K + 1);
  r.support.head(K) = r.points;
  r.support[K] = 1.0;
  r.support_weights = BarycentricWeights(r.support);
  r.point_weights = BarycentricWeights(r.points);
  r.differentiation.setZero(K, K + 1);
  for (int i = 0; i < K; ++i) {
    double diag = 0.0;
    for (int j = 0; j <= K; ++j) {
      if (j == i) continue;
      const double d =
          (r.support_weights[j] / r.support_weights[i]) / (r.support[i] - r.support[j]);
      r.differentiation(i, j) = d;
      diag -= d;
    }
    r.differentiation(i, i) = diag;
  }
  return r;
}

}  // namespace ocpb
