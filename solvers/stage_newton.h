// The Hamiltonian family's polish on a Runge-Kutta scheme with stage controls (scheme rk2, rk4):
// a projected truncated Newton method on the scheme's reduced problem, min J(U) over the stage
// controls, with the exact transformed adjoint's gradient. The first-order descent hands over to
// it, as it hands over to Newton on the Euler maximum principle on forward Euler.
#pragma once

#include <cmath>
#include <string>

#include "core/control_set.h"
#include "core/stage_rk_ocp.h"
#include "core/timer.h"

namespace ocpb {

class AugmentedLagrangianOcp;

/// What the Newton iteration does and when it stops (the family's newton_* options).
struct StageNewtonOptions {
  int max_iterations = 100;           ///< Newton steps at most (>= 0)
  double tolerance = 1e-10;           ///< converged when the projected residual is <= this (> 0)
  int max_cg_iterations = 500;        ///< conjugate-gradient steps per Newton step (>= 1)
  double backtrack = 0.5;             ///< line search: steps 1, b, b^2, ... (in (0, 1))
  double sufficient_decrease = 1e-4;  ///< Armijo constant c of the line search (in (0, 1/2))
  double min_step = 1e-12;            ///< the line search fails below this step (> 0)
};

/// How it ended.
struct StageNewtonOutcome {
  bool converged = false;
  int iterations = 0;        ///< Newton steps taken
  int hessian_products = 0;  ///< Hessian-vector products (two gradient sweeps each)
  int cg_iterations = 0;     ///< over all Newton steps
  double residual = NAN;     ///< the projected residual at the end (below)
  double J = NAN;            ///< J(U) at the end
  std::string code;          ///< "converged", "max_iterations", "line_search", "rounding" (J
                             ///< at its rounding for 3 steps), "not_finite", "max_cpu_seconds"
  std::string why;           ///< one sentence for the message
};

/// Minimizes the J of `srk` over the stage controls *U (nu x sN), every column in `controls`
/// (its box and ball blocks), from *U (projected first).
///
/// Scaled by the stage weights w_{k,i} = h_k b_i, the gradient is the stage Hamiltonian's
/// derivative, g_{k,i} = dJ/du_{k,i} / w_{k,i} = H_u(stage k, i), and the stopping measure is the
/// projected residual max |u - P_U(u - g)| (zero exactly at a stationary point of the discrete
/// problem on U, a KKT point of its bounds). Each step (Bertsekas' two-metric projection, SIAM J.
/// Control Optim. 20, 1982): the held directions (within min(1e-2, residual) of U's boundary: a
/// box component at a bound that g pushes through, the radial direction of a ball block on its
/// sphere that g pushes outwards) take the scaled gradient step; the others (for a held ball,
/// its tangent space) a truncated Newton step
/// d = -H_FF^-1 dJ/du_F by conjugate gradients preconditioned by diag(w) (Eisenstat-Walker
/// forcing min(0.1, sqrt(residual)); on negative curvature the last positive-curvature iterate,
/// or the scaled gradient at the first), with Hessian-vector products by central differences of
/// the exact gradient (step 1e-5 max(1, |U|_inf) / |v|_inf); then the projected Armijo search
/// J(P(U + s d)) <= J(U) + c dJ/dU . (P(U + s d) - U), s = 1, b, b^2, ... >= min_step.
StageNewtonOutcome StageNewton(const StageRkOcp& srk,
                               const ControlSet& controls,
                               const StageNewtonOptions& options,
                               const CpuLimit& limit,
                               Mat* U);

/// The projected residual of StageNewton at U (computed by one simulation and adjoint sweep);
/// NaN when J(U) is not finite.
double StageProjectedResidual(const StageRkOcp& srk, const ControlSet& controls, const Mat& U);

/// What the hard terminal form's polish adds: an outer multiplier loop.
struct StageAugmentedLagrangianOutcome {
  StageNewtonOutcome last;  ///< the last inner Newton solve
  int outer_iterations = 0;
  int newton_iterations = 0;  ///< over all inner solves
  int hessian_products = 0;
  int cg_iterations = 0;
  double terminal_residual = NAN;  ///< max_i |psi_i(x_N)| at the end
  Vec multipliers;                 ///< nu + rho psi(x_N) at the end (the hard form's nu)
  bool converged = false;
  std::string code;  ///< "converged", or the inner failure's code, or "max_outer_iterations"
  std::string why;
};

/// One StageNewton solve as the loop's outcome (the penalty form: no outer iteration, no
/// multipliers), so that a caller reads both forms alike.
StageAugmentedLagrangianOutcome SingleSolveOutcome(const StageNewtonOutcome& solve);

/// The hard terminal form psi(x_N) = 0: StageNewton on the augmented Lagrangian `al` (whose
/// terminal multipliers and penalty this sets; `srk` must be built on `al` in
/// TerminalMode::kHard), the multipliers updated nu <- nu + rho psi after each converged inner
/// solve, rho <- penalty_growth rho when max |psi| did not fall to a quarter of its previous
/// value. Starts from nu = 0 and `initial_penalty`; converged when the inner solve converged
/// and max |psi| <= feasibility_tolerance. The multipliers of the solution, nu + rho psi at it,
/// are the outcome's `multipliers`; `al` keeps those of the last inner solve, so that an adjoint
/// sweep of `srk` at the final U gives the hard form's costates (lambda_N = grad phi + psi_x^T
/// multipliers). With Newton the inner solves are exact,
/// so the loop's rate is the multiplier method's (linear, faster as rho grows: Bertsekas 1982,
/// Sec. 2.2).
StageAugmentedLagrangianOutcome StageNewtonAugmentedLagrangian(const StageRkOcp& srk,
                                                               AugmentedLagrangianOcp* al,
                                                               const ControlSet& controls,
                                                               const StageNewtonOptions& options,
                                                               double initial_penalty,
                                                               double penalty_growth,
                                                               double max_penalty,
                                                               double feasibility_tolerance,
                                                               int max_outer_iterations,
                                                               const CpuLimit& limit,
                                                               Mat* U);

}  // namespace ocpb
