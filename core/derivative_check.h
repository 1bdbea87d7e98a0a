// Finite-difference checks of an Ocp's derivatives (the test every hand-written or AD
// derivative must pass).
#pragma once

#include <functional>
#include <string>

#include "core/ocp.h"

namespace ocpb {

/// Central-difference Jacobian of fn: R^n -> R^m at x, step h_i = step * max(1, |x_i|).
/// Truncation error O(step^2), roundoff O(eps / step): step ~ eps^(1/3) ~ 6e-6 balances them.
Mat CentralJacobian(const std::function<Vec(const Vec&)>& fn, const Vec& x, double step = 6e-6);

/// The outcome of CheckOcpDerivatives.
struct DerivativeCheck {
  /// max over every checked entry of |analytic - fd| / max(1, |fd|).
  double max_error = 0.0;
  /// One line per checked quantity: name and its error.
  std::string log;
};

/// Compares every first and second derivative the Ocp interface provides (f_x, f_u, L_x, L_u,
/// phi_x, psi_x, c_x, c_u, PointHessian, TerminalHessian) with central differences of the
/// corresponding lower-order functions at (t, x, u), with multipliers `lambda` (nx), `mu` (nc)
/// and `nu` (npsi) for the Hessians.
DerivativeCheck CheckOcpDerivatives(const Ocp& ocp, double t, const Vec& x, const Vec& u,
                                    const Vec& lambda, const Vec& mu, const Vec& nu);

}  // namespace ocpb
