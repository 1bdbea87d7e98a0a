#include "problems/reference/vanderpol.h"

namespace ocpb {

VanDerPol::VanDerPol() {
  SetDimensions(2, 1, 0, 0);
  SetHorizon(0.0, 2.0);
  SetInitialState(Eigen::Vector2d(1.0, 0.0));
}

void VanDerPol::MinimizeHamiltonian(double, ConstVecRef, ConstVecRef p, VecRef u) const {
  u[0] = -p[1];  // argmin_u p2 u + u^2/2
}

ProblemInfo VanDerPolProblemInfo() {
  ProblemInfo p;
  p.name = "vanderpol";
  p.description = "Van der Pol oscillator (om = eps = 1), 1/2 int_0^2 |x|^2 + u^2, free end";
  p.parameters = VanDerPol::ParameterSpecs();
  p.make = [](const Parameters&, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<VanDerPol>();
  };
  p.default_intervals = 100;
  p.reference_value = VanDerPol::kReferenceCost;
  p.reference_source =
      "shooting on the optimality conditions (project notes 2.9); Bocop examples list: 1.05 "
      "(midpoint, 100 steps)";
  p.tags = {"smooth"};
  return p;
}

}  // namespace ocpb
