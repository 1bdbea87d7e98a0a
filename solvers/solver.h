// The interface every method implements, and what a solve is asked to do.
#pragma once

#include <optional>
#include <string>

#include "core/control_trajectory.h"
#include "core/integrator.h"
#include "core/ocp.h"
#include "core/option_value.h"
#include "core/solve_result.h"
#include "core/time_grid.h"

namespace ocpb {

/// One solve request. A solver's own options and its transcription's options come as typed
/// values by name (OptionMap); each owner's OptionSchema (SolverInfo::options,
/// TranscriptionInfo::options) states the keys, defaults and rules, and the solver resolves
/// them before any work, throwing std::invalid_argument naming the key and the rule (unknown
/// keys list the valid ones). Text values ("500") are read by the one option grammar.
struct SolveRequest {
  TimeGrid grid;                                   ///< the method's grid on [t0, tf]
  TerminalMode terminal = TerminalMode::kPenalty;  ///< penalty (paper) or hard psi = 0
  /// For methods that simulate: the Hamiltonian descent's integrator, single shooting's.
  Integrator integrator = Integrator::kEuler;
  std::string transcription;  ///< NLP solvers: "euler", "trapezoid", ... (TranscriptionInfo)
  /// The transcription's options (LGR: "degree"; every collocation scheme: "objective_scale",
  /// "state_scale", "control_scale"); see `ocpbench describe transcription NAME`.
  OptionMap transcription_options;
  std::optional<ControlTrajectory>
      initial_guess;  ///< default: Ocp::NominalControl() projected onto U
  /// The solver's options (NLopt's algorithm is its option "algorithm"); see `ocpbench
  /// describe solver NAME`.
  OptionMap options;
};

/// A method. Solve() never throws for numerical trouble: that is the result's status. It throws
/// std::invalid_argument only for an invalid request.
class Solver {
 public:
  virtual ~Solver() = default;
  virtual std::string name() const = 0;
  virtual SolveResult Solve(const Ocp& ocp, const SolveRequest& request) const = 0;
};

/// For a method that treats the horizon as fixed: when `ocp` has a free final time, the result
/// it returns instead of solving (SolveStatus::kNotApplicable, solver_status "not_applicable",
/// saying which methods solve it and that the time-scaled problems pose free time for every
/// method); nullopt for a fixed horizon.
std::optional<SolveResult> FreeFinalTimeNotApplicable(const Ocp& ocp, const std::string& solver);

/// The default starting controls: Ocp::NominalControl() projected onto U, constant on `grid`.
ControlTrajectory DefaultInitialGuess(const Ocp& ocp, const TimeGrid& grid);

}  // namespace ocpb
