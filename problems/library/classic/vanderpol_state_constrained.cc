#include "problems/library/classic/vanderpol_state_constrained.h"

#include <limits>
#include <memory>

namespace ocpb {

VanDerPolStateConstrained::VanDerPolStateConstrained(const Parameters&) {
  SetHorizon(0.0, 5.0);
  SetInitialState(Eigen::Vector2d(1.0, 0.0));
  const double inf = std::numeric_limits<double>::infinity();
  SetStateBounds(Eigen::Vector2d(-inf, kLowerVelocity), Eigen::Vector2d(inf, inf));
}

ProblemInfo VanDerPolStateConstrainedProblemInfo() {
  ProblemInfo p;
  p.name = "vanderpol-state-constrained";
  p.description =
      "Betts' Van der Pol oscillator: int_0^5 y1^2 + y2^2 + u^2 (no 1/2), state bound y2 >= -0.4";
  p.parameters = VanDerPolStateConstrained::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<VanDerPolStateConstrained>(params);
  };
  p.default_intervals = 200;
  p.reference_value = VanDerPolStateConstrained::kReferenceCost;
  p.reference_source =
      "Betts 2010 (Practical Methods for Optimal Control and Estimation Using Nonlinear "
      "Programming, 2nd ed.), example 10.144 (section 4.14, example 4.11): J* = 2.95369916";
  p.origin = "Betts 2010 examples 10.144 / 10.145";
  p.hamiltonian_note = "not applicable: a state bound y2 >= -0.4 (no reformulation provided)";
  p.tags = {"state-constrained"};
  return p;
}

}  // namespace ocpb
