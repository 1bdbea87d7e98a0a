#include "problems/library/ctbench_b/beam.h"

#include <limits>
#include <memory>

namespace ocpb {
std::vector<ParameterSpec> BeamOcp::ParameterSpecs() {
  return {
      {"C", {1e4}, "terminal penalty weight (penalty form)", 0.0, 1e300, true},
  };
}

BeamOcp::BeamOcp(const Parameters& params) {
  SetHorizon(0.0, 1.0);
  SetInitialState(Eigen::Vector2d(0.0, 1.0));
  SetTerminalWeights(Vec::Constant(2, params.Scalar("C")));
  const double inf = std::numeric_limits<double>::infinity();
  SetStateBounds(Eigen::Vector2d(0.0, -inf), Eigen::Vector2d(kDeflectionBound, inf));
}

ProblemInfo BeamProblemInfo() {
  ProblemInfo p;
  p.name = "beam";
  p.description =
      "clamped beam (BOCOP, OptimalControlProblems.jl): min int u^2, x1'' = u, 0 <= x1 <= 0.1";
  p.parameters = BeamOcp::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<BeamOcp>(params);
  };
  p.default_intervals = 200;
  p.reference_value = BeamOcp::kOptimalCost;
  p.reference_source =
      "analytic J* = 8/(9a) = 80/9 at a = 0.1: twice the Bryson-Denham optimum 4/(9l) (Bryson, "
      "Denham, Dreyfus, AIAA J. 1(11), 1963; Bryson & Ho 1975, Sec. 3.11)";
  p.additional_references = {
      {8.89133522024639,
       "J",
       "trapezoid",
       200,
       "CTBenchmarks.jl core-ubuntu-latest (2026-01-30), beam, Ipopt + JuMP, trapeze, "
       "grid_size 200, tol 1e-8"},
  };
  p.origin =
      "OptimalControlProblems.jl (control-toolbox) beam, after the BOCOP clamped-beam example";
  p.hamiltonian_note =
      "not applicable: state bounds (the family takes path rows; bryson-denham poses the same "
      "kind of problem with one)";
  p.tags = {"state-constrained"};
  return p;
}

}  // namespace ocpb
