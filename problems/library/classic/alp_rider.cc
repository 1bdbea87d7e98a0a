#include "problems/library/classic/alp_rider.h"

#include <cmath>
#include <memory>

namespace ocpb {

std::vector<ParameterSpec> AlpRider::ParameterSpecs() {
  return {{"C", {1000.0}, "terminal penalty weight (penalty form)", 0.0, 1e300, true}};
}

AlpRider::AlpRider(const Parameters& params) {
  SetHorizon(0.0, kHorizon);
  SetInitialState(Eigen::Vector4d(2.0, 1.0, 2.0, 1.0));
  SetTerminalWeights(Vec::Constant(4, params.Scalar("C")));
}

double AlpRider::Floor(double t) {
  auto bump = [t](double a, double b) { return std::exp(-b * (t - a) * (t - a)); };
  return 3.0 * bump(3.0, 12.0) + 3.0 * bump(6.0, 10.0) + 3.0 * bump(10.0, 6.0) +
         8.0 * bump(15.0, 4.0) + 0.01;
}

ProblemInfo AlpRiderProblemInfo() {
  ProblemInfo p;
  p.name = "alp-rider";
  p.description =
      "Betts' Alp rider: 4 stiff linear states forced over four bumps of |y|^2 >= floor(t), "
      "int 100 |y|^2 + 0.01 |u|^2 on [0, 20]";
  p.parameters = AlpRider::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<AlpRider>(params);
  };
  p.default_intervals = 400;
  p.reference_value = AlpRider::kReferenceCost;
  p.reference_source =
      "Betts 2010 (Practical Methods for Optimal Control and Estimation Using Nonlinear "
      "Programming, 2nd ed.), example 10.1 (Alp rider, section 4.11.7): J* = 2030.85609";
  p.origin = "Betts 2010 example 10.1; PSOPT example alpine";
  p.hamiltonian_note =
      "not applicable: a pure state path constraint |y|^2 >= floor(t) (no reformulation "
      "provided)";
  p.tags = {"state-constrained", "stiff"};
  return p;
}

}  // namespace ocpb
