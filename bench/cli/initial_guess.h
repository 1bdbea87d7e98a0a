// `ocpbench solve --initial-guess FILE`: the controls of a previous `ocpbench solve --json` record
// as the starting point of another solve.
#pragma once

#include <string>

#include "core/control_trajectory.h"
#include "core/ocp.h"

namespace ocpb {

/// Reads the `trajectory` ({t, x, u}) of an `ocpbench solve --json` record: t holds the N + 1
/// grid points, u the nu rows of N values (each interval's left end). The controls come back
/// piecewise constant on that grid when the record's `u_rule` says piecewise constant (the
/// Hamiltonian descent, Euler, single shooting: the record's controls exactly), else piecewise
/// linear through the samples (the last one held to tf); each solver samples them onto its own
/// grid. Throws std::invalid_argument "--initial-guess FILE: ..." for a missing or unreadable file,
/// malformed JSON, or a record without a well-formed trajectory (for example one written with
/// --no-trajectory, or by a run that was not applicable).
ControlTrajectory ReadInitialGuess(const std::string& path);

/// Throws std::invalid_argument "--initial-guess FILE: ..." unless `guess` has the problem's
/// control dimension and spans the problem's horizon [t0, tf].
void CheckInitialGuess(const ControlTrajectory& guess, const Ocp& ocp, const std::string& path);

}  // namespace ocpb
