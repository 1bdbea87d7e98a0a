// A C2 interpolant of gridded data with value, gradient and Hessian.
#pragma once

#include <Eigen/Core>

namespace ocpb {

/// Tensor-product cubic B-spline interpolation of values f(i, j) at nodes
/// (x0 + i h, y0 + j h), 0 <= i < nx, 0 <= j < ny (nx, ny >= 4):
///
///   S(x, y) = sum_{a,b} c(a, b) B((x - x0)/h - a) B((y - y0)/h - b),
///
/// B the uniform cubic B-spline, with coefficients c such that S interpolates every node and
/// the third derivative is continuous across the second and second-to-last knots in each
/// direction ("not-a-knot" ends, fourth-order accurate up to the boundary). S is C2: value,
/// gradient and Hessian are continuous, which second-order NLP methods need. Coefficients come
/// from tridiagonal solves along rows then columns (O(nx ny)); an evaluation reads 16
/// coefficients. Points outside the node rectangle use the polynomial of the nearest boundary
/// cell (extrapolation; ChannelMap clamps to the workspace first).
class BicubicSpline {
 public:
  BicubicSpline() = default;
  /// Throws std::invalid_argument if h <= 0, fewer than 4 nodes per side, or a value is not
  /// finite.
  BicubicSpline(double x0, double y0, double h, const Eigen::MatrixXd& values);

  /// Value, gradient and Hessian at (x, y); `grad`/`hess` may be null.
  void Evaluate(
      double x, double y, double* value, Eigen::Vector2d* grad, Eigen::Matrix2d* hess) const;

  int nx() const { return static_cast<int>(coef_.rows()) - 2; }
  int ny() const { return static_cast<int>(coef_.cols()) - 2; }

 private:
  template <int kOrder>
  void EvaluateOrder(
      double x, double y, double* value, Eigen::Vector2d* grad, Eigen::Matrix2d* hess) const;

  double x0_ = 0.0, y0_ = 0.0, h_ = 1.0;
  Eigen::MatrixXd coef_;  // (nx + 2) x (ny + 2); coef_(a + 1, b + 1) multiplies B(. - a) B(. - b)
};

}  // namespace ocpb
