#include "solvers/hamiltonian_target.h"

#include <stdexcept>

namespace ocpb {

HamiltonianTarget ResolveHamiltonianTarget(const Ocp& original,
                                           const HamiltonianReformulationOptions& options,
                                           bool reformulate) {
  HamiltonianTarget t;
  if (reformulate) t.reformulated = original.HamiltonianReformulation(options);
  t.ocp = t.reformulated ? t.reformulated.get() : &original;
  if (!t.reformulated) return t;
  t.note = "solved the problem's Hamiltonian reformulation '" + t.ocp->name() + "'";
  // The initial state's freedom too: indirect-newton's transversality rows read it from the
  // reformulation, which must not fix what the problem leaves free (or the reverse).
  if (t.ocp->nx() != original.nx() || t.ocp->nu() != original.nu() ||
      t.ocp->free_final_time().has_value() != original.free_final_time().has_value() ||
      t.ocp->HasFreeInitialState() != original.HasFreeInitialState() ||
      (original.HasFreeInitialState() && t.ocp->HasInitialCost() != original.HasInitialCost())) {
    throw std::logic_error("problem '" + original.name() +
                           "': its Hamiltonian reformulation changed nx, nu, the free final "
                           "time or the free initial state");
  }
  return t;
}

}  // namespace ocpb
