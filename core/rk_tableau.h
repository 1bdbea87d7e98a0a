// Explicit Runge-Kutta tableaux for optimal control with one control per stage, and Hager's order
// conditions for them.
#pragma once

#include <string>
#include <vector>

namespace ocpb {

/// An explicit s-stage Runge-Kutta scheme (Butcher tableau): stage i of the step from t_k is
///   y_i = x_k + h sum_{j<i} a_ij f(t_k + c_j h, y_j, u_{k,j}),
///   x_{k+1} = x_k + h sum_i b_i f(t_k + c_i h, y_i, u_{k,i}),
/// with its own control u_{k,i} (StageRkOcp). a is s x s row-major and strictly lower
/// triangular (explicit).
struct RkTableau {
  std::string name;
  int stages = 0;
  std::vector<double> a;  ///< a[i * stages + j]
  std::vector<double> b;
  std::vector<double> c;

  double A(int i, int j) const { return a[static_cast<size_t>(i * stages + j)]; }

  /// Forward Euler as a one-stage tableau (b = 1, c = 0).
  static RkTableau ForwardEuler();
  /// Heun's second-order method: c = (0, 1), a_21 = 1, b = (1/2, 1/2).
  static RkTableau Heun();
  /// The classical fourth-order method: c = (0, 1/2, 1/2, 1), a_21 = a_32 = 1/2, a_43 = 1,
  /// b = (1/6, 1/3, 1/3, 1/6).
  static RkTableau Classical4();

  /// Empty when the tableau is usable for StageRkOcp: sizes agree, a is strictly lower
  /// triangular, c_i = sum_j a_ij (to 1e-14), and every b_i > 0 (Hager's assumption: the
  /// transformed adjoint divides by b_i). Otherwise the one-line reason.
  std::string Check() const;
};

/// One of Hager's order conditions for the control problem (W. W. Hager, "Runge-Kutta methods in
/// optimal control and the transformed adjoint system", Numer. Math. 87 (2000), Table 1), with
/// d_j = sum_i b_i a_ij and sums over all indices:
///   order 1: sum b_i = 1
///   order 2: sum d_i = 1/2
///   order 3: sum c_i d_i = 1/6,  sum b_i c_i^2 = 1/3,  sum d_i^2 / b_i = 1/3
///   order 4: sum b_i c_i^3 = 1/4,  sum b_i c_i a_ij c_j = 1/8,  sum d_i c_i^2 = 1/12,
///            sum d_i a_ij c_j = 1/24,  sum c_i d_i^2 / b_i = 1/12,  sum d_i^3 / b_i^2 = 1/4,
///            sum b_i c_i a_ij d_j / b_j = 5/24,  sum d_i a_ij d_j / b_j = 1/8.
/// Order p for the control problem needs every condition of order <= p. Orders 1 and 2 are the
/// ordinary ones (sum b_i c_i = 1/2 is sum d_i = 1/2 when c_i = sum_j a_ij); from order 3 on the
/// conditions with d_i / b_i are the ones the ordinary conditions do not contain.
struct OrderCondition {
  int order = 0;
  std::string formula;
  double value = 0.0;     ///< the sum for the tableau
  double expected = 0.0;  ///< the right-hand side
};

/// Every condition of order <= 4 for `tableau` (which must pass Check()).
std::vector<OrderCondition> HagerOrderConditions(const RkTableau& tableau);

/// The largest p <= 4 such that every condition of order <= p holds to `tolerance`; 0 when
/// the order-1 condition fails.
int HagerOrder(const RkTableau& tableau, double tolerance = 1e-12);

}  // namespace ocpb
