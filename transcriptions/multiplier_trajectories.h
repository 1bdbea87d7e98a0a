// A collocation solution's multipliers as functions of time, to start the multipliers of the NLP
// on another mesh (mesh refinement's multiplier warm start).
#pragma once

#include "core/control_trajectory.h"
#include "core/types.h"

namespace ocpb {

/// The multipliers of one solved collocation NLP, made independent of its mesh
/// (CollocationNlp::MultiplierTrajectoriesAt), and read on another mesh
/// (CollocationNlp::StartingMultipliers). Every trajectory lives on the solution's time axis
/// [t0, T] (T its final time) and is in physical units (the NLP's scaling undone):
///  - costates: p(t), the NLP's costate estimate (TranscribedNlp::Costates) at its state points,
///    interpolated per mesh interval by the Lagrange polynomial through the interval's state
///    points and the next interval's first one (trapezoid: linear; Hermite-Simpson: quadratic;
///    LGR: degree K). The defect multipliers of the other mesh are recovered from it by
///    inverting the same costate relations;
///  - path, balls, control_lower, control_upper: multiplier densities, the multiplier of a
///    point's path constraints (of a control block's ball constraints, or box bounds) divided by
///    the point's quadrature weight (the one its running cost carries, times the final-time
///    ratio), piecewise linear between the points; nu() == 0 when the problem has none;
///  - terminal (hard terminal constraints) and the final time's bound multipliers: as they are.
struct MultiplierTrajectories {
  ControlTrajectory costates;       ///< nx components
  ControlTrajectory path;           ///< Ocp::num_path() components, or none
  ControlTrajectory balls;          ///< one component per ball block of U, or none
  ControlTrajectory control_lower;  ///< nu components (0 where a control has no box bound)
  ControlTrajectory control_upper;  ///< nu components
  Vec terminal;                     ///< multipliers of psi = 0 (TerminalMode::kHard), or empty
  double final_time_lower = 0.0;    ///< bound multipliers of a free final time T
  double final_time_upper = 0.0;
};

}  // namespace ocpb
