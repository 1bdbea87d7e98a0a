#include "solvers/solver.h"

namespace ocpb {

std::optional<SolveResult> FreeFinalTimeNotApplicable(const Ocp& ocp, const std::string& solver) {
  if (!ocp.free_final_time()) return std::nullopt;
  SolveResult r;
  r.solver = solver;
  r.status = SolveStatus::kNotApplicable;
  r.solver_status = "not_applicable";
  r.message =
      "problem '" + ocp.name() + "' has a free final time, which " + solver +
      " does not take (it keeps the horizon fixed): indirect-newton (H(tf) = 0) and the "
      "NLP solvers on a collocation transcription (T a variable) solve it; the "
      "time-scaled problems (brachistochrone, zermelo, steering, goddard, robot-arm) pose free "
      "time on a fixed horizon for every method";
  r.iterations = 0;
  r.cpu_seconds = 0.0;
  r.wall_seconds = 0.0;
  return r;
}

ControlTrajectory DefaultInitialGuess(const Ocp& ocp, const TimeGrid& grid) {
  Vec u = ocp.CheckedNominalControl();
  ocp.control_set().Project(u);
  return ControlTrajectory::Constant(grid, u);
}

}  // namespace ocpb
