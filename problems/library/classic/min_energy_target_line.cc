#include "problems/library/classic/min_energy_target_line.h"

#include <memory>

namespace ocpb {

ProblemInfo MinEnergyTargetLineProblemInfo() {
  ProblemInfo p;
  p.name = "min-energy-target-line";
  p.description = "minimum-energy double integrator from rest to the line x1 - 2 x2 = 1 at t = 1";
  p.parameters = MinEnergyTargetLine::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<MinEnergyTargetLine>(params);
  };
  p.default_intervals = 100;
  p.reference_value = MinEnergyTargetLine::kReferenceCost;
  p.reference_source =
      "analytic (Locatelli 2017, chapter 6; PSOPT example mineng_target_set): u* = -(3/7)(1 "
      "+ t), J* = 3/14";
  p.origin = "Locatelli 2017, chapter 6; PSOPT example mineng_target_set";
  p.tags = {"smooth"};
  return p;
}

}  // namespace ocpb
