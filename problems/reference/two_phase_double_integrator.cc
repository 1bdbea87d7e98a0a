#include "problems/reference/two_phase_double_integrator.h"

#include <vector>

namespace ocpb {

std::unique_ptr<MultiPhaseOcp> MakeTwoPhaseDoubleIntegrator() {
  std::vector<PhaseSpec> phases = {
      {std::make_shared<DoubleIntegratorPhase<0>>(), 0.05, 10.0},
      {std::make_shared<DoubleIntegratorPhase<2>>(), 0.05, 10.0},
  };
  return std::make_unique<MultiPhaseOcp>(
      "two-phase-double-integrator",
      std::move(phases),
      std::vector<std::vector<PhaseLink>>{MultiPhaseOcp::Continuity(2)});
}

ProblemInfo TwoPhaseDoubleIntegratorProblemInfo() {
  ProblemInfo p;
  p.name = "two-phase-double-integrator";
  p.description =
      "minimum time from (1, 0) to rest at 0 in two phases (accelerate, brake) with a free "
      "switching time";
  p.make = [](const Parameters&, std::uint64_t) -> std::unique_ptr<Ocp> {
    return MakeTwoPhaseDoubleIntegrator();
  };
  p.default_intervals = 50;
  p.reference_value = 2.0;
  p.reference_source =
      "analytic: T* = 2 sqrt(d) with d = 1, switch at sqrt(d) (Bryson and Ho 1975, sec. 3.9)";
  p.hamiltonian_note =
      "not applicable: several phases (free initial state of the later phases, linkage "
      "boundary constraints)";
  p.tags = {"multi-phase", "free-time", "bang-bang", "control-constrained"};
  return p;
}

}  // namespace ocpb
