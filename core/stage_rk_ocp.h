// The finite-dimensional problem an explicit Runge-Kutta scheme with one control per stage makes
// of an Ocp, and its exact discrete adjoint (Hager's transformed adjoint system).
#pragma once

#include "core/ocp.h"
#include "core/rk_tableau.h"
#include "core/time_grid.h"

namespace ocpb {

/// With an explicit s-stage tableau (a, b, c) and controls u_{k,i} at every stage of every
/// interval (U: nu x sN, column k s + i), the Ocp becomes
///
///   y_{k,i} = x_k + h_k sum_{j<i} a_ij f(t_{k,i}, y_{k,j}, u_{k,j}),  t_{k,i} = t_k + c_i h_k,
///   x_{k+1} = x_k + h_k sum_i b_i f(t_{k,i}, y_{k,i}, u_{k,i}),        x_0 = x0,
///   J(U)    = sum_k h_k sum_i b_i L(t_{k,i}, y_{k,i}, u_{k,i}) + Phi(x_N)
///
/// (the running cost as an extra state integrated by the same stages; Phi = phi, + the terminal
/// penalty in TerminalMode::kPenalty). The one-stage tableau (b = 1, c = 0) is forward Euler.
///
/// Adjoint() is the exact reverse-mode derivative of this J, written as Hager's transformed
/// adjoint system (Numer. Math. 87, 2000) with stage costates lambda_{k,i}:
///   lambda_N      = grad Phi(x_N),
///   lambda_{k,i}  = lambda_{k+1} + h_k sum_{l>i} (b_l a_li / b_i) H_x(t_{k,l}, y_{k,l}, u_{k,l},
///   lambda_{k,l}), lambda_k      = lambda_{k+1} + h_k sum_i b_i H_x(t_{k,i}, y_{k,i}, u_{k,i},
///   lambda_{k,i}), dJ/du_{k,i}   = h_k b_i H_u(t_{k,i}, y_{k,i}, u_{k,i}, lambda_{k,i}),
/// with H = p^T f + L (so every b_i must be > 0: RkTableau::Check). The last stage's costate is
/// lambda_{k+1} when no later stage uses it (a_li = 0 for l > i).
class StageRkOcp {
 public:
  /// Throws std::invalid_argument when tableau.Check() fails.
  StageRkOcp(const Ocp& ocp, const TimeGrid& grid, RkTableau tableau, TerminalMode mode);

  const Ocp& ocp() const { return ocp_; }
  const TimeGrid& grid() const { return grid_; }
  const RkTableau& tableau() const { return tableau_; }
  TerminalMode terminal_mode() const { return mode_; }
  int stages() const { return tableau_.stages; }
  int intervals() const { return grid_.intervals(); }
  /// The number of control columns, s N.
  int controls() const { return tableau_.stages * grid_.intervals(); }
  /// t_{k,i} = t_k + c_i h_k.
  double StageTime(int k, int i) const;
  /// h_k b_i: the weight of stage (k, i) in the running cost and in dJ/du_{k,i}.
  double StageWeight(int k, int i) const;

  /// Simulates from x0 with stage controls U (nu x sN). Fills X (nx x (N+1)) and the stage
  /// states Y (nx x sN) when non-null, the running part when `running` is non-null. Returns J;
  /// NaN when the trajectory or J is not finite.
  double Simulate(const Mat& U, Mat* X, Mat* Y = nullptr, double* running = nullptr) const;

  /// At U with X from Simulate: node costates Lambda (nx x (N+1)), stage states Y and stage
  /// costates P (nx x sN each) and the gradient G = dJ/dU (nu x sN). With `dJdh` non-null also
  /// the derivative of J with respect to each step length h_k (size N) for an autonomous
  /// problem (f, L without t, as a free final time requires; the stage times are not
  /// differentiated):
  ///   dJ/dh_k = sum_i b_i [lambda_{k+1}^T f_{k,i} + L_{k,i} + H_x(stage i)^T (y_{k,i} - x_k) /
  ///   h_k]
  /// (the last term is h_k-free: y_{k,i} - x_k = h_k sum_j a_ij f_{k,j}); for Euler it is
  /// H(x_k, u_k, lambda_{k+1}).
  void Adjoint(
      const Mat& U, const Mat& X, Mat* Lambda, Mat* Y, Mat* P, Mat* G, Vec* dJdh = nullptr) const;

 private:
  const Ocp& ocp_;
  TimeGrid grid_;
  RkTableau tableau_;
  TerminalMode mode_;
};

}  // namespace ocpb
