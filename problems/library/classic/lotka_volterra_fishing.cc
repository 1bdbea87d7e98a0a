#include "problems/library/classic/lotka_volterra_fishing.h"

#include <memory>

namespace ocpb {

LotkaVolterraFishing::LotkaVolterraFishing(const Parameters&) {
  SetHorizon(0.0, 12.0);
  SetInitialState(Eigen::Vector2d(0.5, 0.7));
  ControlSet set;
  set.AddBox(Vec::Constant(1, 0.0), Vec::Constant(1, 1.0));
  SetControlSet(set);
}

ProblemInfo LotkaVolterraFishingProblemInfo() {
  ProblemInfo p;
  p.name = "lotka-volterra-fishing";
  p.description =
      "Sager's Lotka-Volterra fishing problem, relaxed w in [0, 1]: steer prey/predator to (1, 1), "
      "int |x - 1|^2 over [0, 12]";
  p.parameters = LotkaVolterraFishing::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<LotkaVolterraFishing>(params);
  };
  p.default_intervals = 200;
  p.reference_value = LotkaVolterraFishing::kReferenceCost;
  p.reference_source =
      "mintOC (mintoc.de, Lotka Volterra fishing problem; Sager 2005): relaxed optimum 1.34408 "
      "(also PSOPT example lotka)";
  p.origin = "Sager 2005 / mintOC; PSOPT example lotka";
  p.hamiltonian_note =
      "not applicable: H is linear in w with a singular arc (no exact minimizer provided)";
  p.tags = {"singular-arc", "control-constrained"};
  return p;
}

}  // namespace ocpb
