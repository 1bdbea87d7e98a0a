#include "problems/library/ctbench_b/chain.h"

#include <memory>

namespace ocpb {

std::vector<ParameterSpec> HangingChainOcp::ParameterSpecs() {
  return {
      {"C", {1e4}, "terminal penalty weight (penalty form)", 0.0, 1e300, true},
  };
}

HangingChainOcp::HangingChainOcp(const Parameters& params) {
  SetHorizon(0.0, 1.0);
  SetInitialState(Eigen::Vector3d(kLeftHeight, 0.0, 0.0));
  SetTerminalWeights(Vec::Constant(2, params.Scalar("C")));
}

double HangingChainOcp::CatenaryOptimum() {
  const double c = kCatenaryC, m = kCatenaryM, d = kCatenaryD;
  const double s0 = -m / c, s1 = (1.0 - m) / c;
  return c * c * (0.5 * (s1 - s0) + 0.25 * (std::sinh(2.0 * s1) - std::sinh(2.0 * s0))) +
         d * kLength;
}

ProblemInfo HangingChainProblemInfo() {
  ProblemInfo p;
  p.name = "chain";
  p.description =
      "COPS hanging chain: min potential energy x2(1) of a chain of length 4 from (0, 1) to "
      "(1, 3)";
  p.parameters = HangingChainOcp::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<HangingChainOcp>(params);
  };
  p.default_intervals = 200;
  p.reference_value = HangingChainOcp::CatenaryOptimum();
  p.reference_source =
      "closed form: the catenary through (0, 1), (1, 3) of length 4 (c, m, d solved to 30 "
      "digits with mpmath), J* = c^2 ((s1 - s0)/2 + (sinh 2s1 - sinh 2s0)/4) + d L = "
      "5.068480110993416 (derivation in problems/library/ctbench_b/chain.h)";
  p.additional_references = {
      {5.068917341242299,
       "J",
       "trapezoid",
       200,
       "CTBenchmarks.jl core-ubuntu-latest (2026-01-30), chain, Ipopt + JuMP, trapeze, "
       "grid_size 200, tol 1e-8"},
      {5.068577790026832,
       "J",
       "trapezoid",
       500,
       "CTBenchmarks.jl core-ubuntu-latest (2026-01-30), chain, Ipopt + JuMP, trapeze, "
       "grid_size 500, tol 1e-8"},
      {5.068510095825627,
       "J",
       "trapezoid",
       1000,
       "CTBenchmarks.jl core-ubuntu-latest (2026-01-30), chain, Ipopt + JuMP, trapeze, "
       "grid_size 1000, tol 1e-8"},
      {5.068488912144199,
       "J",
       "trapezoid",
       2000,
       "CTBenchmarks.jl core-ubuntu-latest (2026-01-30), chain, Ipopt + JuMP, trapeze, "
       "grid_size 2000, tol 1e-8"},
  };
  p.origin =
      "COPS 3.0 (Dolan, More, Munson 2004) chain, as posed by OptimalControlProblems.jl "
      "(control-toolbox)";
  p.hamiltonian_note =
      "not applicable: no closed-form minimizer of H = p1 u + (p2 x1 + p3) sqrt(1 + u^2) over "
      "an unbounded u (the method needs one)";
  p.tags = {"smooth", "mayer"};
  return p;
}

}  // namespace ocpb
