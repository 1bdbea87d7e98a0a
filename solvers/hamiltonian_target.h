// The problem a Hamiltonian-based method works on: the original problem, or the Hamiltonian
// reformulation the problem offers (Ocp::HamiltonianReformulation: path constraints folded into
// L as a penalty, a regularization where H is linear in u). The descent, the Hamiltonian family
// and the indirect method share it; each adds its own applicability checks.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "core/ocp.h"
#include "core/solve_result.h"

namespace ocpb {

struct HamiltonianTarget {
  /// The reformulated problem, or null when the original is solved as it is.
  std::unique_ptr<Ocp> reformulated;
  /// The problem solved: reformulated.get(), or the original.
  const Ocp* ocp = nullptr;
  /// "solved the problem's Hamiltonian reformulation 'NAME'" when reformulated, else empty.
  std::string note;
  /// Set by the method's checks: the not-applicable result to return instead of solving.
  std::optional<SolveResult> not_applicable;

  /// The note followed by "; " (the start of a message), or empty.
  std::string NotePrefix() const { return note.empty() ? note : note + "; "; }
};

/// The problem's reformulation with these options when `reformulate` and the problem offers
/// one, else the original. Throws std::logic_error when a reformulation changes nx, nu or
/// whether the final time is free (a broken Ocp implementation, not a user input).
HamiltonianTarget ResolveHamiltonianTarget(const Ocp& original,
                                           const HamiltonianReformulationOptions& options,
                                           bool reformulate = true);

}  // namespace ocpb
