// The least-squares terminal costate of a costate start from given controls: the one solve that
// FitEulerCostates (forward Euler, the polish) and IndirectNewton::CostatesFromControls (the
// trapezoid) share.
#pragma once

#include <vector>

#include "core/control_set.h"
#include "core/ocp.h"
#include "core/types.h"

namespace ocpb {

/// The components of u strictly inside U: box components more than 1e-6 of their range (1e-6
/// for an infinite range) from a bound, ball blocks with |u - c| < (1 - 1e-6) r; every component
/// when U is unconstrained. Fills *free (cleared first) in increasing order.
void FreeControlComponents(const ControlSet& set, ConstVecRef u, std::vector<int>* free);

/// The nodes of a costate fit: node i is at time t[i] with state X.col(i), control U.col(i),
/// quadrature weight weight[i] >= 0, and costate p_{costate_offset + i} = M[.] q + c[.] (the
/// affine form of the costate recursion in the terminal costate q).
struct CostateFitNodes {
  std::vector<double> t;
  std::vector<double> weight;
  const Mat* X = nullptr;
  const Mat* U = nullptr;
  int costate_offset = 0;
};

/// What FitTerminalCostate decided.
struct CostateFit {
  Vec q;  ///< the terminal costate
  /// A Mayer cost along the controls: L = 0, L_x = 0, L_u = 0 and L_uu = 0 at every node. The
  /// fit has then nothing to fit: its rows are homogeneous (H_u = f_u^T M q), any multiple of a
  /// fitting q fits as well, and the least-squares q is the ridge's shrinkage of q0 towards its
  /// part in the rows' null space (costates near zero). A constant L (the 1 of a minimum-time
  /// problem) is not counted: the adjoint start did not help there (brachistochrone-free-time,
  /// results/notes/family-round3.md), and such problems keep their fitted start. q is the fitted
  /// one all the same: the caller chooses another start (FitEulerCostates and
  /// IndirectNewton::CostatesFromControls: the adjoint sweep's).
  bool degenerate = false;
  /// Rows of the fit (free components over all nodes); 0: q = q0.
  int rows = 0;
};

/// The terminal costate q minimizing
///
///   sum_i weight_i |(H_uu,i)_F^-1 (H_u,i)_F|^2 + delta^2 |q - q0|^2,
///   H_u,i = L_u + f_u^T p_i(q)   at (t_i, x_i, u_i),   p_i(q) = M[j] q + c[j], j = offset + i,
///
/// F the free components of u_i (FreeControlComponents). Each term is the Newton step of u_i
/// towards argmin H_i (H_uu at p_i(q0); unweighted where that block is not positive definite), so
/// u*(x_i, p_i(q)) reproduces u_i as well as a single q allows. The ridge delta = 1e-8 times the
/// largest column norm of the stacked rows keeps q0 in the directions the controls do not
/// determine; q = q0 when no component is free or the least-squares solve is not finite. Rows
/// are stacked node by node: A = [sqrt(w_i) (H_uu)_F^-1 G_i], b = -[sqrt(w_i) (H_uu)_F^-1 g_i]
/// with H_u,i = G_i q + g_i, then the ridge rows, solved by Householder QR.
CostateFit FitTerminalCostate(const Ocp& ocp,
                              const CostateFitNodes& nodes,
                              const std::vector<Mat>& M,
                              const std::vector<Vec>& c,
                              const Vec& q0);

}  // namespace ocpb
