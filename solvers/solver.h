// The interface every method implements, and what a solve is asked to do.
#pragma once

#include <map>
#include <optional>
#include <string>

#include "core/control_trajectory.h"
#include "core/integrator.h"
#include "core/ocp.h"
#include "core/solve_result.h"
#include "core/time_grid.h"

namespace ocpb {

/// One solve request. Solver-specific options come as strings ("max_iter" -> "500"); each
/// solver parses them into its typed Options struct and rejects unknown keys or bad values with
/// std::invalid_argument naming the key and the rule.
struct SolveRequest {
  TimeGrid grid;                                   ///< the method's grid on [t0, tf]
  TerminalMode terminal = TerminalMode::kPenalty;  ///< penalty (paper) or hard psi = 0
  Integrator integrator = Integrator::kEuler;      ///< for methods that simulate (Hamiltonian)
  std::string transcription;                       ///< NLP solvers: "euler", "trapezoid", ...
  std::string algorithm;                           ///< NLopt: "LD_SLSQP", ...
  int degree = 3;                                  ///< LGR collocation degree
  std::optional<ControlTrajectory>
      initial_guess;  ///< default: Ocp::NominalControl() projected onto U
  std::map<std::string, std::string> options;
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
