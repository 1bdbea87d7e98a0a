// A local error estimate by explicit simulation: on each mesh interval the dynamics are integrated
// accurately from the collocated start state with the scheme's interpolated control and compared
// with the collocated states (any collocation scheme; transcription option
// mesh_estimate=simulation).
#pragma once

#include "core/control_trajectory.h"
#include "core/ocp.h"
#include "core/time_grid.h"
#include "core/types.h"

namespace ocpb {

/// The estimate on each interval k of `mesh`, in the manner of Haman and Rao ("Adaptive mesh
/// refinement and error estimation method for optimal control using direct collocation",
/// arXiv:2410.07488, 2024: an initial-value problem per interval with the interpolated control;
/// their terminal-value problem is not solved here):
///
///   x_sim' = f(t, x_sim, u~(t)) on [t_k, t_{k+1}],  x_sim(t_k) = X(t_k),
///   eta_k = max_i max_{t_j in (t_k, t_{k+1}]} |x_sim,i(t_j) - X_i(t_j)| / (1 + w_i),
///
/// with X the collocated states at the times `state_times` (every mesh node must be one of them;
/// the points inside an interval count too: Hermite-Simpson's midpoints, LGR's interior points),
/// u~ = `controls` (what the evaluator judges) and Betts' weights w_i = max_j |X_i(t_j)| over
/// every state point. The integration is classical RK4 with m equal substeps between
/// consecutive state points, m doubled from 4 until the scaled change of the simulated states is
/// <= 1e-2 eta_k + 1e-13 (or m = 4096), so the integrator's own error stays two orders below the
/// estimate, also where the projected control has a kink inside an interval.
///
/// What it measures is the local error of the collocated states under the controls the
/// evaluator will judge; on a smooth solution it decreases as h^(q) with q = 3 (trapezoid: its
/// local error), 4 (Hermite-Simpson: its midpoint state, the cubic Hermite value, is O(h^4)
/// locally; the node is O(h^5)) and K + 1 for LGR with K points (the interior points; x(t_k+1)
/// is O(h^(2K))) -- asserted by MeshError.SimulationEstimateDecreasesAtItsOrder.
///
/// `mesh` and `state_times` are on the solution's horizon (stretched to T for a free final time);
/// `states` is nx x state_times.size(). Returns one entry per interval; NaN where the simulation
/// is not finite. Throws std::invalid_argument when a mesh node is not a state time.
Vec IntervalSimulationErrors(const Ocp& ocp,
                             const TimeGrid& mesh,
                             const TimeGrid& state_times,
                             const Mat& states,
                             const ControlTrajectory& controls);

}  // namespace ocpb
