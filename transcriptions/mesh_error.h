// The local error estimate of a collocation solution on each mesh interval (Betts' defect
// estimate), for the trapezoidal and Hermite-Simpson transcriptions' h-refinement.
#pragma once

#include "core/control_trajectory.h"
#include "core/ocp.h"
#include "core/time_grid.h"
#include "core/types.h"

namespace ocpb {

/// The state interpolant a scheme implies between its mesh nodes t_k (h = t_{k+1} - t_k,
/// f_k = f(t_k, x_k, u(t_k))):
///  - kTrapezoid: the quadratic with x(t_k) = x_k, x'(t_k) = f_k, x'(t_{k+1}) = f_{k+1} (it ends
///    at x_{k+1} by the trapezoidal defect); its derivative is linear from f_k to f_{k+1};
///  - kHermiteSimpson: the cubic Hermite interpolant through (x_k, f_k) and (x_{k+1}, f_{k+1});
///    at a solution it also passes through (x_m, f_m) at the midpoint by the two defects.
enum class CollocationInterpolant { kTrapezoid, kHermiteSimpson };

/// The interpolant x~ and its time derivative dx~/dt on interval k of `nodes` at
/// s = (t - t_k) / h_k in [0, 1], from the node states X and node derivatives F (nx x nodes,
/// F_k = f(t_k, x_k, u(t_k))).
void InterpolateState(CollocationInterpolant scheme,
                      const TimeGrid& nodes,
                      const Mat& X,
                      const Mat& F,
                      int k,
                      double s,
                      VecRef x,
                      VecRef xdot);

/// The exponent q with which the estimate below decreases on one interval as its length h goes
/// to 0 on a smooth solution: estimate = O(h^q).
///  - trapezoid: q = 3. The defect x~' - f(x~, u~) is the linear interpolation error of
///    g(t) = f(x~(t), u~(t)), O(h^2), integrated over h (the scheme's order 2, plus 1).
///  - Hermite-Simpson: q = 4. The defect is the quadratic interpolation error of g through t_k,
///    the midpoint and t_{k+1}, O(h^3) (cubic g''' (t - t_k)(t - t_m)(t - t_{k+1}) / 6). Its
///    signed integral cancels to O(h^5) (Simpson's order 4, plus 1), but the integral of its
///    absolute value does not cancel: O(h^4).
int DefectEstimateOrder(CollocationInterpolant scheme);

/// Betts' estimate of the local error on each mesh interval k ("Practical Methods for Optimal
/// Control and Estimation Using Nonlinear Programming", 2nd ed., SIAM 2010, Sec. 4.7.2):
///
///   eta_k = max_i  1 / (1 + w_i)  int_{t_k}^{t_{k+1}} | x~_i'(t) - f_i(t, x~(t), u~(t)) | dt,
///   w_i = max_j |x_i(t_j)|  (over every mesh node j),
///
/// with x~ the scheme's state interpolant (CollocationInterpolant) through the node states
/// and u~ = `controls` (the scheme's own control interpolation: what the evaluator judges). The
/// integral is a 5-point Gauss-Legendre rule on each piece between the scheme's collocation
/// points (trapezoid: the whole interval; Hermite-Simpson: each half), where the defect vanishes
/// at the ends and, asymptotically, keeps one sign, so |defect| is smooth inside each piece and
/// the rule integrates it accurately (Betts uses Romberg quadrature instead).
///
/// `nodes` is the mesh (on the solution's own horizon: stretched to T for a free final time,
/// where f is then the physical-time dynamics), `node_states` nx x nodes.size() (x_k at t_k).
/// Returns eta (nodes.intervals() entries); NaN entries where f is not finite.
Vec IntervalDefectErrors(const Ocp& ocp,
                         CollocationInterpolant scheme,
                         const TimeGrid& nodes,
                         const Mat& node_states,
                         const ControlTrajectory& controls);

/// The scheme's state interpolant x~(t) on `nodes` as a function of time (nx components), for
/// warm-starting a solve on another mesh from this one's states. f_k from `controls` at the
/// nodes, as in IntervalDefectErrors.
ControlTrajectory StateInterpolant(const Ocp& ocp,
                                   CollocationInterpolant scheme,
                                   const TimeGrid& nodes,
                                   const Mat& node_states,
                                   const ControlTrajectory& controls);

}  // namespace ocpb
