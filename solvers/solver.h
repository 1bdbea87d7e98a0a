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
  /// The method's grid on [t0, tf] (required; any strictly increasing points: Uniform or
  /// FromPoints). For a free final time, on the nominal horizon (T starts at tf unless a guess
  /// says otherwise).
  TimeGrid grid;
  /// Default: the penalty form (the paper's), whose answer depends on the problem's terminal
  /// weights (Ocp::terminal_weights_chosen); kHard enforces psi = 0.
  TerminalMode terminal = TerminalMode::kPenalty;
  /// For methods that simulate: the Hamiltonian descent's integrator, single shooting's.
  /// Default: forward Euler (the paper's).
  Integrator integrator = Integrator::kEuler;
  std::string transcription;  ///< NLP solvers: "euler", "trapezoid", ... (TranscriptionInfo)
  /// The transcription's options (LGR: "degree"; every collocation scheme: "objective_scale",
  /// "state_scale", "control_scale"); see `ocpbench describe transcription NAME`.
  OptionMap transcription_options;
  /// The controls to start from; default: Ocp::NominalControl() projected onto U. For a free
  /// final time a guess may end at its own T within the bounds (a previous solution's): methods
  /// that take T start there, reading the guess on that stretched axis.
  std::optional<ControlTrajectory> initial_guess;
  /// States to start from (nx components; a ControlTrajectory serves as any function of time,
  /// usually piecewise linear through a previous solution's states), on the same horizon as
  /// initial_guess. Taken by the methods whose unknowns include states: the collocation
  /// transcriptions (euler, trapezoid, hermite-simpson, lgr) at their state points, and
  /// indirect-newton at its nodes. Ignored by the others, whose states follow from the controls
  /// (the Hamiltonian descent, single shooting). Empty: states by simulating initial_guess.
  std::optional<ControlTrajectory> initial_states;
  /// Costates to start from (nx components, the convention H = p^T f + L), for methods whose
  /// unknowns include them: indirect-newton (without: from its `costates` option). Ignored by
  /// the others.
  std::optional<ControlTrajectory> initial_costates;
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

/// The parts of OCPBench's problem class beyond a fixed horizon, a fixed x(t0) and path rows
/// (Ocp's class comment): which a problem uses (Of), or which a method takes.
struct ProblemFeatures {
  bool free_final_time = false;       ///< Ocp::free_final_time
  bool free_initial_state = false;    ///< Ocp::HasFreeInitialState (with its initial cost)
  bool state_bounds = false;          ///< Ocp::state_bounds
  bool boundary_constraints = false;  ///< Ocp::num_boundary() > 0
  /// Some boundary row has lower < upper (an inequality); Of only (no method's `takes` reads it;
  /// every method that takes boundary constraints takes their inequalities)
  bool boundary_inequalities = false;
  /// The features `ocp` uses.
  static ProblemFeatures Of(const Ocp& ocp);
};
/// The reason `solver` cannot solve `ocp` when the problem uses a feature the method does not
/// take (one line: the feature, the problem, which methods take it); empty when it takes all
/// the problem uses. The free final time's text is FreeFinalTimeNotApplicable's.
std::string UnsupportedFeature(const Ocp& ocp,
                               const std::string& solver,
                               const ProblemFeatures& takes);
/// UnsupportedFeature as the result a method returns instead of solving
/// (SolveStatus::kNotApplicable, solver_status "not_applicable"); nullopt when it applies.
std::optional<SolveResult> FeaturesNotApplicable(const Ocp& ocp,
                                                 const std::string& solver,
                                                 const ProblemFeatures& takes);
/// A result that says `solver` did not run, with `why` as its message (kNotApplicable, no
/// iterations, no time).
SolveResult NotApplicableResult(const std::string& solver, const std::string& why);

/// The default starting controls: Ocp::NominalControl() projected onto U, constant on `grid`.
ControlTrajectory DefaultInitialGuess(const Ocp& ocp, const TimeGrid& grid);

}  // namespace ocpb
