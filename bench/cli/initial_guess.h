// `ocpbench solve --initial-guess FILE`: a previous `ocpbench solve --json` record as the
// starting point of another solve: its controls and, where the record keeps them, the method's
// own states and costates.
#pragma once

#include <optional>
#include <string>

#include "core/control_trajectory.h"
#include "core/ocp.h"

namespace ocpb {

/// What a record offers a new solve (SolveRequest::initial_guess, initial_states,
/// initial_costates).
struct InitialGuess {
  ControlTrajectory controls;
  /// trajectory.own.x: the method's own states on its state grid, piecewise linear (nx rows);
  /// empty when the record has none (a method without states, or a record from before schema
  /// version 3).
  std::optional<ControlTrajectory> states;
  /// trajectory.own.p: the method's costates on the same grid (nx rows), where it had them.
  std::optional<ControlTrajectory> costates;
};

/// Reads the `trajectory` ({t, u, u_rule, own: {t, x, p}}) of an `ocpbench solve --json` record:
/// t holds the N + 1 grid points, u the nu rows of N values (each interval's left end). The
/// controls come back piecewise constant on that grid when the record's `u_rule` says piecewise
/// constant (the Hamiltonian descent, Euler, single shooting: the record's controls exactly),
/// else piecewise linear through the samples (the last one held to tf); each solver samples
/// them onto its own grid. States and costates (trajectory.own) come back piecewise linear on
/// their own grid, which must span the same horizon. Throws std::invalid_argument
/// "--initial-guess FILE: ..." for a missing or unreadable file, malformed JSON, or a record
/// without a well-formed trajectory (for example one written with --no-trajectory, or by a run
/// that was not applicable).
InitialGuess ReadInitialGuess(const std::string& path);

/// Throws std::invalid_argument "--initial-guess FILE: ..." unless the controls have the
/// problem's nu components, the states and costates its nx, and the guess spans the problem's
/// horizon [t0, tf] (for a free final time: [t0, T] with T within the bounds, the previous
/// solution's T, where the solvers that take T then start).
void CheckInitialGuess(const InitialGuess& guess, const Ocp& ocp, const std::string& path);

}  // namespace ocpb
