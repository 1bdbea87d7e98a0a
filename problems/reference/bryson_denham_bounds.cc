#include "problems/reference/bryson_denham_bounds.h"

#include <limits>
#include <memory>

#include "problems/reference/bryson_denham.h"

namespace ocpb {

std::vector<ParameterSpec> BrysonDenhamBounds::ParameterSpecs() {
  return {
      {"C", {1e4}, "terminal penalty weight (penalty form)", 0.0, 1e300, true},
  };
}

BrysonDenhamBounds::BrysonDenhamBounds(const Parameters& params) {
  SetHorizon(0.0, 1.0);
  SetInitialState(Eigen::Vector2d(0.0, 1.0));
  SetTerminalWeights(Vec::Constant(2, params.Scalar("C")));
  const double inf = std::numeric_limits<double>::infinity();
  SetStateBounds(Eigen::Vector2d(-inf, -inf), Eigen::Vector2d(BrysonDenham::kDefaultBound, inf));
}

ProblemInfo BrysonDenhamBoundsProblemInfo() {
  ProblemInfo p;
  p.name = "bryson-denham-bounds";
  p.description =
      "bryson-denham with x1 <= l as a state bound (variable bounds in the NLP, not a path row)";
  p.parameters = BrysonDenhamBounds::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<BrysonDenhamBounds>(params);
  };
  p.default_intervals = 100;
  p.reference_value = BrysonDenham::OptimalCost();
  p.reference_source =
      "analytic J* = 4/(9l), l = 1/9 (Bryson, Denham, Dreyfus 1963; Bryson-Ho Sec. 3.11), as "
      "bryson-denham";
  p.hamiltonian_note =
      "not applicable: state bounds (the family takes path rows; bryson-denham poses the same "
      "problem with one)";
  p.tags = {"state-constrained"};
  return p;
}

}  // namespace ocpb
