#include "problems/library/classic/fuller.h"

#include <memory>

namespace ocpb {

std::vector<ParameterSpec> Fuller::ParameterSpecs() {
  return {{"C", {1e3}, "terminal penalty weight (penalty form)", 0.0, 1e300, true}};
}

Fuller::Fuller(const Parameters& params) {
  SetHorizon(0.0, 1.0);
  SetInitialState(Eigen::Vector2d(1.0, 0.0));  // x(0) = (0.01, 0) in units of 0.01
  SetTerminalWeights(Vec::Constant(2, params.Scalar("C")));
  SetControlSet(ControlSet::Box(Vec::Constant(1, -1.0), Vec::Constant(1, 1.0)));
}

ProblemInfo FullerProblemInfo() {
  ProblemInfo p;
  p.name = "fuller";
  p.description =
      "Fuller's problem on [0, 1]: min int x1^2, x'' = u in [-1, 1], from and back to (0.01, 0) "
      "(x in units of 0.01); the optimal control chatters";
  p.parameters = Fuller::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<Fuller>(params);
  };
  p.default_intervals = 100;
  p.reference_value = Fuller::kReferenceCost;
  p.reference_source =
      "computed by OCPBench (Ipopt tol 1e-12: Hermite-Simpson N = 800 and 1600, trapezoid and LGR "
      "N = 1600 give 0.15280353 to 0.15280411), good to about 3e-6 relative; in units 1e4 times "
      "the source's (x in units of 0.01): 1.52804e-5 there";
  p.additional_references = {
      {Fuller::kMintocCost,
       "J",
       "continuous",
       0,
       "mintOC, Fuller's problem (relaxed): 1.5296058259296967e-05 with Optimica and Ipopt on a "
       "grid the page does not state, a discrete optimum 1.0e-3 above the continuous one (here "
       "times 1e4)"}};
  p.origin = "Fuller 1963; mintOC (mintoc.de), Fuller's problem";
  p.hamiltonian_note =
      "not applicable: H is linear in u (bang-bang, chattering) and no minimizer is given";
  p.tags = {"chattering", "bang-bang", "control-constrained"};
  return p;
}

}  // namespace ocpb
