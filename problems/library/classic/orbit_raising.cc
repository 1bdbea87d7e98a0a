#include "problems/library/classic/orbit_raising.h"

#include <memory>
#include <numbers>

namespace ocpb {

std::vector<ParameterSpec> OrbitRaising::ParameterSpecs() {
  return {{"C", {100.0}, "terminal penalty weight (penalty form)", 0.0, 1e300, true}};
}

OrbitRaising::OrbitRaising(const Parameters& params) {
  SetHorizon(0.0, kFinalTime);
  SetInitialState(Eigen::Vector4d(1.0, 0.0, 0.0, 1.0));
  SetTerminalWeights(Vec::Constant(2, params.Scalar("C")));
  SetControlSet(ControlSet::Box(Vec::Constant(2, -1.1), Vec::Constant(2, 1.1)));
  const double pi = std::numbers::pi;
  SetStateBounds(Eigen::Vector4d(1.0, -pi, -10.0, -10.0), Eigen::Vector4d(10.0, pi, 10.0, 10.0));
}

ProblemInfo OrbitRaisingProblemInfo() {
  ProblemInfo p;
  p.name = "orbit-raising";
  p.description =
      "maximum-radius low-thrust orbit transfer in a fixed time, circular to circular (Bryson "
      "and Ho 1975)";
  p.parameters = OrbitRaising::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<OrbitRaising>(params);
  };
  p.default_intervals = 100;
  p.reference_value = -OrbitRaising::kReferenceRadius;
  p.reference_source =
      "YAPSS (S. R. Hall), the test of example orbit_raising: r(tf) = 1.5252777 at relative "
      "tolerance 1e-7";
  p.origin = "Bryson and Ho, Applied Optimal Control, 1975, section 2.5";
  p.hamiltonian_note =
      "not applicable: state bounds (inactive at the optimum) and the path constraint |u|^2 <= "
      "1 on the controls";
  p.tags = {"control-constrained", "mayer", "aerospace"};
  return p;
}

}  // namespace ocpb
