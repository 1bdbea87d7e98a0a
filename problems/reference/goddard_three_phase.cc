#include "problems/reference/goddard_three_phase.h"

#include <vector>

namespace ocpb {

std::unique_ptr<MultiPhaseOcp> MakeGoddardThreePhase() {
  std::vector<PhaseSpec> phases = {
      {std::make_shared<GoddardThrustPhase<false>>(), 1.0, 100.0},
      {std::make_shared<GoddardThrustPhase<true>>(), 1.0, 100.0},
      {std::make_shared<GoddardCoastPhase>(), 1.0, 100.0},
  };
  // h, v and m continue into the singular arc; h and v into the coast (m = 1 there).
  std::vector<std::vector<PhaseLink>> links = {MultiPhaseOcp::Continuity(3),
                                               MultiPhaseOcp::Continuity(2)};
  return std::make_unique<MultiPhaseOcp>(
      "goddard-three-phase", std::move(phases), std::move(links));
}

ProblemInfo GoddardThreePhaseProblemInfo() {
  ProblemInfo p;
  p.name = "goddard-three-phase";
  p.description =
      "Goddard rocket in three phases (maximum thrust, singular arc, coast), max h(tF), free "
      "switching times (Betts gdrd07)";
  p.make = [](const Parameters&, std::uint64_t) -> std::unique_ptr<Ocp> {
    return MakeGoddardThreePhase();
  };
  p.default_intervals = 50;
  p.reference_value = -GoddardThreePhaseConstants::kReferenceAltitude;
  p.reference_source =
      "Betts, A Collection of Optimal Control Test Problems (2015), example 10.47 gdrd07: "
      "h(tF) = 18550.872 ft, switches 13.751270, 21.987363 s, tF = 42.887912 s";
  p.origin = "Betts' collection (gdrd07); Bryson's Goddard rocket";
  p.hamiltonian_note =
      "not applicable: several phases and no controls (the decisions are the phase durations)";
  p.tags = {"multi-phase", "singular-arc", "free-time", "mayer", "aerospace"};
  return p;
}

}  // namespace ocpb
