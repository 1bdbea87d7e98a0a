// The common evaluator: every method's controls are judged here, never by the method's own report.
#pragma once

#include "core/control_trajectory.h"
#include "core/integrator.h"
#include "core/ocp.h"
#include "core/time_grid.h"

namespace ocpb {

/// What re-simulating a control trajectory says about it.
struct Evaluation {
  double J = -1.0;                   ///< penalized cost: Jbar + sum w_i psi_i^2
  double Jbar = -1.0;                ///< unpenalized cost: int L + phi (+ phi0(x(t0)) when
                                     ///< the initial state is free and has a cost)
  double running_cost = -1.0;        ///< int L
  double initial_cost = 0.0;         ///< phi0(x(t0)) (Ocp::InitialCost) with a free initial
                                     ///< state; 0 otherwise
  double terminal_cost = -1.0;       ///< phi(x(tf))
  double terminal_penalty = -1.0;    ///< sum w_i psi_i(x(tf))^2
  Vec terminal_residual;             ///< psi(x(tf))
  double terminal_violation = -1.0;  ///< max_i |psi_i(x(tf))|
  double control_violation = -1.0;   ///< max over the controls the integrator used (Euler:
                                     ///< u(t_k+); RK4 also u(t_k + h/2) and u(t_{k+1}-)) of
                                     ///< the distance-like violation of U (ControlSet::Violation)
  double path_violation = -1.0;      ///< max over grid nodes t_k and i of
                                     ///< max(c_i(t_k, x_k, u(t_k+)), 0) (at tf: u(tf-)); the
                                     ///< constraints are judged where NLPs enforce them
  /// The state bounds (Ocp::state_bounds) at every grid node after t0 and the initial-state
  /// bounds at t0 (a fixed x0: the distance from it), max over nodes and components of the
  /// distance outside; 0 when everything is inside.
  double state_bound_violation = -1.0;
  Vec boundary_residual;             ///< b(x(t0), x(tf)) (size Ocp::num_boundary())
  double boundary_violation = -1.0;  ///< max_i of how far b_i lies outside its bounds (0 when
                                     ///< inside, and without boundary constraints)

  Mat X;  ///< states on the grid (nx x (N+1))
  TimeGrid grid;
  Integrator integrator = Integrator::kRk4;
  bool finite = false;  ///< false when the trajectory or the cost is NaN/inf
};

/// Simulates x' = f(t, x, u(t)), x(t0) = x0, on `grid` with `integrator`, where u(t) comes from
/// `controls` with one-sided limits inside each step (see ControlTrajectory), and integrates L with
/// the same scheme. For piecewise-constant controls on the same grid with kEuler this is exactly
/// DiscreteOcp::Simulate. Throws std::invalid_argument (one line) when the controls do not have
/// the problem's nu components, when `grid` does not span the problem's horizon [t0, tf] (for a
/// free final time: [t0, T] with T within its bounds, Ocp::AdmitsFinalTime; the trajectory is
/// then judged on [t0, T]), when the controls' own grid does not cover `grid`, or, for a free
/// final time, when the controls go on past the grid's end (they end at the solution's T: a
/// shorter grid would judge a truncated trajectory). To judge a solver's result, JudgeResult
/// (solvers/judge.h) picks the grids from the result itself.
Evaluation Evaluate(const Ocp& ocp,
                    const ControlTrajectory& controls,
                    const TimeGrid& grid,
                    Integrator integrator);
/// The same from x(t0) = initial_state (nx components, else std::invalid_argument): for a
/// problem with a free initial state, the x(t0) a method chose (SolveResult::initial_state). J
/// then includes phi0(x(t0)).
Evaluation Evaluate(const Ocp& ocp,
                    const ControlTrajectory& controls,
                    const TimeGrid& grid,
                    Integrator integrator,
                    ConstVecRef initial_state);

/// The honest "does this control really do it" check for methods that carry their own states
/// (collocation): re-simulates `controls` with RK4 on `state_grid` refined `refine` times and
/// returns max_k |x_sim(t_k) - X.col(k)|_inf over the nodes of `state_grid`, from x0() (from
/// X.col(0) for a free initial state). NaN if not finite.
double ResimulationDefect(const Ocp& ocp,
                          const ControlTrajectory& controls,
                          const TimeGrid& state_grid,
                          const Mat& X,
                          int refine = 10);

}  // namespace ocpb
