// Costates for given controls on a forward-Euler grid, with the terminal costate fitted so that
// the controls are as stationary as they can be: the start of the Euler polish (Newton on
// PmpResidual::Scheme::kEuler) from a first-order method's controls.
#pragma once

#include "core/ocp.h"
#include "core/time_grid.h"

namespace ocpb {

/// Given controls U (nu x N, piecewise constant) and their Euler states X (nx x N+1) on `grid`,
/// the Euler adjoint recursion p_k = p_{k+1} + h_k H_x(t_k, x_k, u_k, p_{k+1}) is affine in the
/// terminal costate q = p_N: p_k = M_k q + c_k. Returns P (nx x N+1) for the q minimizing
///
///   sum_k h_k |(H_uu,k)_F^-1 (H_u,k)_F|^2 + delta^2 |q - q0|^2,
///   H_u,k = L_u + f_u^T p_{k+1}(q)   at (t_k, x_k, u_k),
///
/// F the components of u_k strictly inside U (box components more than 1e-6 of their range from
/// a bound, ball blocks with |u - c| < (1 - 1e-6) r), q0 = grad Phi(x_N) (grad phi in the hard
/// form), delta = 1e-8 times the largest column norm (q stays q0 where the controls do not
/// determine it). Each term is the Newton step of u_k towards argmin H_k, so u*(x_k, p_{k+1})
/// reproduces u_k as well as a single q allows. This is IndirectNewton::CostatesFromControls'
/// fit (solvers/README-indirect.md explains why the adjoint's own q = grad Phi starts Newton at
/// bang-bang controls after a first-order method) for the Euler pairing of x_k with p_{k+1}; both
/// are FitTerminalCostate (solvers/costate_fit.h).
///
/// A degenerate fit (CostateFit::degenerate: a Mayer cost along the controls, L = 0,
/// where the fit returns costates near zero, not at the adjoint's scale) is replaced by the
/// discrete adjoint sweep of the controls themselves: q = grad Phi(x_N) of the penalty form, in the
/// hard form grad phi + psi_x^T nu with the penalty's multiplier estimate nu = 2 w psi(x_N). Every
/// other fit is kept as it is. *adjoint_fallback (may be null) receives whether the adjoint
/// replaced the fit. Throws std::invalid_argument on sizes that do not match.
Mat FitEulerCostates(const Ocp& ocp,
                     const TimeGrid& grid,
                     TerminalMode mode,
                     const Mat& U,
                     const Mat& X,
                     bool* adjoint_fallback = nullptr);

}  // namespace ocpb
