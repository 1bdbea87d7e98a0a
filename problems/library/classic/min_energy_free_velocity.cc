#include "problems/library/classic/min_energy_free_velocity.h"

#include <memory>

namespace ocpb {

ProblemInfo MinEnergyFreeVelocityProblemInfo() {
  ProblemInfo p;
  p.name = "min-energy-free-velocity";
  p.description =
      "minimum-energy double integrator (0, 0) -> x1(1) = 1 with a free final velocity "
      "(transversality)";
  p.parameters = MinEnergyFreeVelocity::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<MinEnergyFreeVelocity>(params);
  };
  p.default_intervals = 100;
  p.reference_value = MinEnergyFreeVelocity::kReferenceCost;
  p.reference_source =
      "analytic (Locatelli 2017, section 3.3; PSOPT example mineng_free_vf): u* = 3 - 3t, J* "
      "= 3/2";
  p.origin = "Locatelli 2017, section 3.3; PSOPT example mineng_free_vf";
  p.tags = {"smooth"};
  return p;
}

}  // namespace ocpb
