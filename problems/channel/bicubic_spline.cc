#include "problems/channel/bicubic_spline.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace ocpb {
namespace {

// B-spline coefficients c_{-1..n} (returned at offset 1) of the not-a-knot cubic spline
// interpolating f_0..f_{n-1} at integer nodes, n >= 4. The interpolation conditions are
// c_{i-1} + 4 c_i + c_{i+1} = 6 f_i; not-a-knot at knot 1 gives c_1 = (8 f_1 - f_0 - f_2) / 6
// and symmetrically at knot n - 2. The interior c_2..c_{n-3} solve a tridiagonal system.
void SplineCoefficients1d(
    const double* f, int stride, int n, double* c, int c_stride, std::vector<double>* work) {
  auto F = [&](int i) { return f[static_cast<long>(i) * stride]; };
  auto C = [&](int i) -> double& { return c[static_cast<long>(i + 1) * c_stride]; };
  C(1) = (8.0 * F(1) - F(0) - F(2)) / 6.0;
  C(n - 2) = (8.0 * F(n - 2) - F(n - 1) - F(n - 3)) / 6.0;
  const int k = n - 4;  // unknowns c_2..c_{n-3}
  if (k > 0) {
    // Thomas algorithm for rows i = 2..n-3: c_{i-1} + 4 c_i + c_{i+1} = 6 f_i.
    std::vector<double>& cp = *work;
    cp.resize(2 * static_cast<std::size_t>(k));
    double* sup = cp.data();
    double* rhs = cp.data() + k;
    for (int r = 0; r < k; ++r) {
      const int i = r + 2;
      double b = 6.0 * F(i);
      if (r == 0) b -= C(1);
      if (r == k - 1) b -= C(n - 2);
      const double denom = 4.0 - (r > 0 ? sup[r - 1] : 0.0);
      sup[r] = 1.0 / denom;
      rhs[r] = (b - (r > 0 ? rhs[r - 1] : 0.0)) / denom;
    }
    C(k + 1) = rhs[k - 1];
    for (int r = k - 2; r >= 0; --r) C(r + 2) = rhs[r] - sup[r] * C(r + 3);
  }
  C(0) = 6.0 * F(1) - 4.0 * C(1) - C(2);
  C(-1) = 6.0 * F(0) - 4.0 * C(0) - C(1);
  C(n - 1) = 6.0 * F(n - 2) - 4.0 * C(n - 2) - C(n - 3);
  C(n) = 6.0 * F(n - 1) - 4.0 * C(n - 1) - C(n - 2);
}

// Uniform cubic B-spline basis on the cell [0, 1] at t, and its first two derivatives (split so
// that the value-only path, the hot one in the descent, computes only what it needs).
inline void Basis(double t, double b[4]) {
  const double s = 1.0 - t, t2 = t * t, t3 = t2 * t;
  b[0] = s * s * s / 6.0;
  b[1] = (3.0 * t3 - 6.0 * t2 + 4.0) / 6.0;
  b[2] = (-3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0) / 6.0;
  b[3] = t3 / 6.0;
}
inline void BasisDerivative(double t, double d[4]) {
  const double s = 1.0 - t, t2 = t * t;
  d[0] = -0.5 * s * s;
  d[1] = 1.5 * t2 - 2.0 * t;
  d[2] = -1.5 * t2 + t + 0.5;
  d[3] = 0.5 * t2;
}
inline void BasisSecondDerivative(double t, double dd[4]) {
  dd[0] = 1.0 - t;
  dd[1] = 3.0 * t - 2.0;
  dd[2] = 1.0 - 3.0 * t;
  dd[3] = t;
}

}  // namespace

BicubicSpline::BicubicSpline(double x0, double y0, double h, const Eigen::MatrixXd& values)
    : x0_(x0), y0_(y0), h_(h) {
  if (!(h > 0.0) || !std::isfinite(h) || !std::isfinite(x0) || !std::isfinite(y0)) {
    throw std::invalid_argument("spline: origin must be finite and spacing > 0");
  }
  const int nx = static_cast<int>(values.rows()), ny = static_cast<int>(values.cols());
  if (nx < 4 || ny < 4) throw std::invalid_argument("spline: need at least 4 x 4 nodes");
  if (!values.allFinite()) throw std::invalid_argument("spline: values must be finite");
  std::vector<double> work;
  // Along x for every row j: tmp (nx + 2) x ny.
  Eigen::MatrixXd tmp(nx + 2, ny);
  for (int j = 0; j < ny; ++j) {
    SplineCoefficients1d(&values(0, j), 1, nx, &tmp(0, j), 1, &work);
  }
  // Along y for every coefficient row a.
  coef_.resize(nx + 2, ny + 2);
  for (int a = 0; a < nx + 2; ++a) {
    SplineCoefficients1d(&tmp(a, 0), nx + 2, ny, &coef_(a, 0), nx + 2, &work);
  }
}

// The evaluation at one order, known at compile time (0: value, 1: with the gradient, 2: with
// the Hessian): the sums a lower order skips are not even tested for in the loop (the same
// arithmetic, in the same order, as a runtime test of the order would do).
template <int kOrder>
void BicubicSpline::EvaluateOrder(
    double x, double y, double* value, Eigen::Vector2d* grad, Eigen::Matrix2d* hess) const {
  const double u = (x - x0_) / h_, v = (y - y0_) / h_;
  // The cell (clamped to the boundary cells): for u >= 0 truncation is floor, and u < 0 clamps
  // to 0 either way, so this is clamp(floor(u), 0, nx - 2) without floor's rounding sequence.
  const int i = static_cast<int>(std::clamp(u, 0.0, static_cast<double>(nx() - 2)));
  const int j = static_cast<int>(std::clamp(v, 0.0, static_cast<double>(ny() - 2)));
  const double tx = u - i, ty = v - j;
  double bx[4], dx[4], ddx[4], by[4], dy[4], ddy[4];
  Basis(tx, bx);
  Basis(ty, by);
  if constexpr (kOrder >= 1) {
    BasisDerivative(tx, dx);
    BasisDerivative(ty, dy);
  }
  if constexpr (kOrder >= 2) {
    BasisSecondDerivative(tx, ddx);
    BasisSecondDerivative(ty, ddy);
  }
  // Coefficients c_{i-1..i+2} sit at rows i..i+3 of coef_.
  double f = 0.0, fx = 0.0, fy = 0.0, fxx = 0.0, fxy = 0.0, fyy = 0.0;
  for (int b = 0; b < 4; ++b) {
    const double* col = &coef_(i, j + b);
    const double c0 = col[0], c1 = col[1], c2 = col[2], c3 = col[3];
    const double sv = c0 * bx[0] + c1 * bx[1] + c2 * bx[2] + c3 * bx[3];
    f += sv * by[b];
    if constexpr (kOrder >= 1) {
      const double sd = c0 * dx[0] + c1 * dx[1] + c2 * dx[2] + c3 * dx[3];
      fx += sd * by[b];
      fy += sv * dy[b];
      if constexpr (kOrder >= 2) {
        const double sdd = c0 * ddx[0] + c1 * ddx[1] + c2 * ddx[2] + c3 * ddx[3];
        fxx += sdd * by[b];
        fxy += sd * dy[b];
        fyy += sv * ddy[b];
      }
    }
  }
  if (value != nullptr) *value = f;
  if constexpr (kOrder >= 1) {
    const double inv_h = 1.0 / h_;
    if (grad != nullptr) *grad = Eigen::Vector2d(fx * inv_h, fy * inv_h);
    if constexpr (kOrder >= 2) {
      const double s = inv_h * inv_h;
      *hess << fxx * s, fxy * s, fxy * s, fyy * s;
    }
  }
}

void BicubicSpline::Evaluate(
    double x, double y, double* value, Eigen::Vector2d* grad, Eigen::Matrix2d* hess) const {
  if (hess != nullptr) {
    EvaluateOrder<2>(x, y, value, grad, hess);
  } else if (grad != nullptr) {
    EvaluateOrder<1>(x, y, value, grad, hess);
  } else {
    EvaluateOrder<0>(x, y, value, grad, hess);
  }
}

}  // namespace ocpb
