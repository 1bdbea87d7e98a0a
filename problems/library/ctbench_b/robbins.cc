#include "problems/library/ctbench_b/robbins.h"

#include <limits>
#include <memory>

namespace ocpb {
std::vector<ParameterSpec> RobbinsOcp::ParameterSpecs() {
  return {
      {"C", {1e4}, "terminal penalty weight (penalty form)", 0.0, 1e300, true},
  };
}

RobbinsOcp::RobbinsOcp(const Parameters& params) {
  SetHorizon(0.0, kFinalTime);
  SetInitialState(Eigen::Vector3d(1.0, -2.0, 0.0));
  SetTerminalWeights(Vec::Constant(3, params.Scalar("C")));
  const double inf = std::numeric_limits<double>::infinity();
  SetStateBounds(Eigen::Vector3d(0.0, -inf, -inf), Eigen::Vector3d(inf, inf, inf));
}

ProblemInfo RobbinsProblemInfo() {
  ProblemInfo p;
  p.name = "robbins";
  p.description =
      "Robbins (BOCOP, OptimalControlProblems.jl): third-order state constraint x1 >= 0, min "
      "int 3 x1 + u^2/2";
  p.parameters = RobbinsOcp::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<RobbinsOcp>(params);
  };
  p.default_intervals = 200;
  p.reference_value = 19.626260124545624;
  p.reference_source =
      "CTBenchmarks.jl core-ubuntu-latest (2026-01-30), robbins, Ipopt + JuMP, trapeze, "
      "grid_size 200, tol 1e-8: an optimum of that discrete NLP";
  p.reference_scheme = "trapezoid";
  p.reference_intervals = 200;
  p.origin =
      "OptimalControlProblems.jl (control-toolbox) robbins, after the BOCOP example and Robbins, "
      "JOTA 31(1), 1980";
  p.hamiltonian_note = "not applicable: state bounds (x1 >= 0)";
  p.tags = {"state-constrained"};
  return p;
}

}  // namespace ocpb
