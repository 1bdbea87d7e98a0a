#include "solvers/solver.h"

namespace ocpb {

ControlTrajectory DefaultInitialGuess(const Ocp& ocp, const TimeGrid& grid) {
  Vec u = Vec::Zero(ocp.nu());
  ocp.control_set().Project(u);
  return ControlTrajectory::Constant(grid, u);
}

}  // namespace ocpb
