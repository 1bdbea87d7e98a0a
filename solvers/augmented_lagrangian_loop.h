// The augmented-Lagrangian outer loop of the Hamiltonian family: multiplier and penalty updates
// around the descent as the inner solver.
#pragma once

#include <string>
#include <vector>

#include "core/solve_result.h"
#include "core/timer.h"
#include "solvers/augmented_lagrangian_ocp.h"
#include "solvers/descent_loop.h"

namespace ocpb {

/// The outer loop's rules. Each outer iteration k minimizes the augmented Lagrangian
/// (AugmentedLagrangianOcp) with the current multipliers and penalty by the descent, to the
/// relative stationarity |theta| <= omega_k (1 + |J_A|), then (Conn, Gould and Toint 1991, and
/// Bertsekas 1982, Sec. 2.2: the standard first-order rules)
///   - if the infeasibility v_k (max |psi_i| and max c_i+ over the grid) <= eta_k:
///       nu <- nu + rho psi, mu <- max(0, mu + rho_c c)  (first-order multiplier update),
///       eta_{k+1} = eta_k min(0.1, rho^-0.9),  omega_{k+1} = omega_k min(0.1, 1/rho);
///   - otherwise rho <- penalty_growth rho (up to max_penalty),
///       eta_{k+1} = eta_0 min(1, rho^-0.1),  omega_{k+1} = omega_0 min(1, 1/rho);
/// (CGT's eta_k / rho^0.9 and omega_k / rho, with the factors capped at 0.1 so that the
/// tolerances also tighten while rho <= 1);
/// omega is clamped below at final_inner_tolerance and eta at feasibility_tolerance. The loop
/// converges when v <= feasibility_tolerance after an inner solve that reached
/// final_inner_tolerance (or stationarity to rounding: theta_at_roundoff, or the Armijo floor
/// with |theta| <= final_inner_tolerance (1 + |J_A|)). theta is quadratic in the gradient, so
/// the multipliers are accurate to about the square root of final_inner_tolerance.
struct AugmentedLagrangianRule {
  double initial_penalty = 1.0;           ///< rho_0 (> 0), times the problem's weights w_i
  double penalty_growth = 10.0;           ///< (> 1)
  double max_penalty = 1e10;              ///< (>= initial_penalty)
  double initial_feasibility = 0.1;       ///< eta_0 (> 0)
  double feasibility_tolerance = 1e-8;    ///< (> 0)
  double initial_inner_tolerance = 1e-2;  ///< omega_0 (> 0), relative to 1 + |J_A|
  double final_inner_tolerance = 1e-10;   ///< (> 0, <= omega_0)
  int max_outer_iterations = 50;          ///< (>= 1)
  int max_inner_iterations = 2000;        ///< descent steps per outer iteration (>= 1)

  bool IsValid(std::string* error) const;
};

/// What the outer loop reports.
struct AugmentedLagrangianOutcome {
  DescentStop stop;                ///< converged, or why not (the inner stop's code when it failed)
  int outer_iterations = 0;        ///< inner solves run
  int descent_iterations = 0;      ///< descent steps over all inner solves
  double terminal_residual = NAN;  ///< max_i |psi_i(x_N)| at the end
  double path_violation = 0.0;     ///< max c_i+ at the end (0 without path constraints)
  double theta = NAN;              ///< the last inner theta
  bool have_costates = false;
};

/// Runs the outer loop from the passes' current iterate. `al` is the problem the passes work on
/// (its multipliers and penalties are set here, starting from zero and rho_0); `inner` gives
/// the descent's Armijo rule, direction and the total iteration and CPU limits (its
/// max_iterations bounds the descent steps of all outer iterations together). History rows are
/// appended as RunDescentLoop does, numbered on across outer iterations.
///
/// `Passes` is DescentPasses or StageDescentPasses (a Runge-Kutta scheme with stage controls: the
/// terminal multipliers only, al's path terms pair with the grid's intervals).
template <class Passes>
AugmentedLagrangianOutcome RunAugmentedLagrangian(const AugmentedLagrangianRule& rule,
                                                  const DescentLoopOptions& inner,
                                                  const Stopwatch& clock,
                                                  AugmentedLagrangianOcp* al,
                                                  Passes* passes,
                                                  std::vector<IterationRecord>* history);

}  // namespace ocpb
