// The finite-dimensional problem in the control samples that one-step integration makes of an Ocp.
#pragma once

#include "core/integrator.h"
#include "core/ocp.h"
#include "core/time_grid.h"

namespace ocpb {

/// With piecewise-constant controls u_k on the grid's intervals, an integrator turns the Ocp into
///
///   J(U) = sum_{k<N} ell_k(x_k, u_k) + Phi(x_N),    x_{k+1} = F_k(x_k, u_k),  x_0 = x0,
///
/// with Phi = phi (+ the terminal penalty in TerminalMode::kPenalty), plus phi0(x_0) where it
/// counts (a free initial state with an initial cost, Ocp::HasInitialCost). x_0 is ocp.x0()
/// unless SetInitialState chose another point of a free initial state's bounds. Euler:
/// F_k = x_k + h_k f(t_k, x_k, u_k), ell_k = h_k L(t_k, x_k, u_k). RK4: the classical stages, with
/// L integrated by the same stages.
///
/// Adjoint() is the exact reverse-mode derivative of this J: costates
///   lambda_N = grad Phi(x_N),  lambda_k = dF_k/dx^T lambda_{k+1} + d ell_k/dx,
/// and the gradient g_k = dJ/du_k = dF_k/du^T lambda_{k+1} + d ell_k/du, all in one backward pass.
/// For Euler this is lambda_k = lambda_{k+1} + h_k (f_x^T lambda_{k+1} + L_x) and
/// g_k = h_k d/du H(t_k, x_k, u_k, lambda_{k+1}), with H = p^T f + L. lambda_0 is the
/// recursion's: dJ/dx_0 = lambda_0 + grad phi0(x_0) for a free initial state.
class DiscreteOcp {
 public:
  DiscreteOcp(const Ocp& ocp, const TimeGrid& grid, Integrator integrator, TerminalMode mode);

  const Ocp& ocp() const { return ocp_; }
  const TimeGrid& grid() const { return grid_; }
  Integrator integrator() const { return integrator_; }
  TerminalMode terminal_mode() const { return mode_; }
  int intervals() const { return grid_.intervals(); }

  /// x_0 of every simulation: ocp.x0() unless SetInitialState set another.
  const Vec& initial_state() const { return x0_; }
  /// Makes x0 (nx entries) the simulations' x_0: a free initial state's current value (the
  /// Hamiltonian family moves it). Throws std::invalid_argument for another length.
  void SetInitialState(ConstVecRef x0);
  /// phi0(x0) when it counts in J (Ocp::HasFreeInitialState and Ocp::HasInitialCost), else 0.
  double InitialObjective(ConstVecRef x0) const;

  /// Simulates from initial_state() with controls U (nu x N). Fills X (nx x (N+1)) when non-null,
  /// and the running part sum ell_k when `running` is non-null. Returns J; NaN or inf when the
  /// trajectory is not finite (callers treat that as a failed evaluation).
  double Simulate(const Mat& U, Mat* X, double* running = nullptr) const;

  /// The states X (nx x (N+1)) of Simulate(U, X) without the cost: for Euler the same
  /// operations, so bitwise the same X (RK4 calls Simulate). Methods that evaluate the cost on
  /// states they already have (an Armijo prefilter, the descent's trials) start here.
  void SimulateStates(const Mat& U, Mat* X) const;
  /// SimulateStates from x0 (nx entries) instead of initial_state().
  void SimulateStatesFrom(ConstVecRef x0, const Mat& U, Mat* X) const;

  /// Costates Lambda (nx x (N+1)) and gradient G = dJ/dU (nu x N) at U, given X from Simulate.
  void Adjoint(const Mat& U, const Mat& X, Mat* Lambda, Mat* G) const;

 private:
  // One RK4 step: x_next and the cost increment; with `bar_x`, `bar_u` non-null also the
  // reverse sweep for the cotangent `bar_next` of x_next (and 1 for the cost increment).
  void Rk4Step(int k, const Vec& x, const Vec& u, Vec* x_next, double* ell) const;
  void Rk4StepAdjoint(
      int k, const Vec& x, const Vec& u, const Vec& bar_next, Vec* bar_x, Vec* bar_u) const;

  const Ocp& ocp_;
  TimeGrid grid_;
  Integrator integrator_;
  TerminalMode mode_;
  Vec x0_;
};

}  // namespace ocpb
