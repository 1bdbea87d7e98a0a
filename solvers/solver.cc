#include "solvers/solver.h"

namespace ocpb {

ControlTrajectory DefaultInitialGuess(const Ocp& ocp, const TimeGrid& grid) {
  Vec u = ocp.NominalControl();
  ocp.control_set().Project(u);
  return ControlTrajectory::Constant(grid, u);
}

}  // namespace ocpb
