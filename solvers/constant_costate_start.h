// The "constant-costate" start of the Euler polish: the costate of an integrator state (one that
// no dynamics and no running cost depend on: transmitted bits, consumed energy) is constant on
// the grid, and its value follows from that state's terminal condition by a scalar root-finder.
#pragma once

#include "core/ocp.h"
#include "core/time_grid.h"

namespace ocpb {

/// What ConstantCostateStart did.
struct ConstantCostateStartOutcome {
  int candidates = 0;   ///< integrator components found (zero column of f_x and of L_x)
  int solved = 0;       ///< of them, those whose terminal equation was solved (and set)
  int evaluations = 0;  ///< evaluations of the scalar equations (N minimizer calls each)
};

/// In the Euler discrete maximum principle, p_k = p_{k+1} + h_k H_x(t_k, x_k, u_k, p_{k+1}) with
/// u_k = u*(t_k, x_k, p_{k+1}) (Ocp::MinimizeHamiltonian). For a component i with column i of
/// f_x and L_x zero (checked at every (t_k, x_k, u_k) of U and X: the problem's exact
/// derivatives), H_x,i = 0, so p_i is one constant c on the whole grid; u* does not depend on
/// x_i, and with the other states and costates held at X and P,
///
///   x_i(N; c) = x_i(0) + sum_k h_k f_i(t_k, x_k, u*(t_k, x_k, p_{k+1} with p_i = c))
///
/// is a function of c alone. Its terminal condition is then one scalar equation g(c) = 0:
///  - kHard, when exactly one row r of psi_x(x_N) has a nonzero entry in column i and that row
///    depends on x_i alone: g(c) = psi_r(x_N(c)) (the multiplier nu_r then absorbs
///    c - phi_x,i, so the costate condition holds for any c);
///  - kPenalty: g(c) = c - dPhi/dx_i(x_N(c)), Phi the penalized terminal cost.
/// g is bracketed from c0 = P(i, N) by steps of growing length (c0 -/+ |c0| 4^j / 4) and its root
/// refined by the Illinois (modified regula falsi) method; on comm-path2d g is monotone (a more
/// negative costate of the bits gives higher rates at every node, more bits): water-filling of
/// the bit budget along the given path. At the root, row i of P is set to c (every node) and row
/// i of X to x_i(k; c), so that component's dynamics and terminal rows of the Newton residual
/// vanish (the other rows are left as given: u* and hence L_x may have changed). Components are
/// solved one after the other, each with the previous ones' new rows. A component whose equation
/// already holds at c0 (to 1e-13 of its scale) keeps c0 and gets its state row; one whose equation
/// has no bracket (within 4^29 |c0|, |c0| read as 1 when c0 = 0; e.g. f_i does not depend on u)
/// or whose refined point does not solve it to 1e-9 of its scale (g jumps: a bracket closed on a
/// discontinuity) is left unchanged. Throws
/// std::invalid_argument on sizes that do not match (U nu x N, X and P nx x (N+1)).
ConstantCostateStartOutcome ConstantCostateStart(
    const Ocp& ocp, const TimeGrid& grid, TerminalMode mode, const Mat& U, Mat* X, Mat* P);

}  // namespace ocpb
