#include "problems/library/ctbench_b/jackson.h"

#include <memory>

namespace ocpb {
std::vector<ParameterSpec> JacksonOcp::ParameterSpecs() { return {}; }

JacksonOcp::JacksonOcp(const Parameters&) {
  SetHorizon(0.0, kFinalTime);
  SetInitialState(Eigen::Vector3d(1.0, 0.0, 0.0));
  SetControlSet(ControlSet::Box(Vec::Zero(1), Vec::Ones(1)));
  SetStateBounds(Vec::Zero(3), Vec::Constant(3, kStateUpper));
}

ProblemInfo JacksonProblemInfo() {
  ProblemInfo p;
  p.name = "jackson";
  p.description =
      "Jackson mixed-catalyst reactor (BOCOP, OptimalControlProblems.jl): max x3(4), u in "
      "[0, 1] (bang-singular-bang)";
  p.parameters = JacksonOcp::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<JacksonOcp>(params);
  };
  p.default_intervals = 200;
  p.reference_value = -0.1918612972717779;
  p.reference_source =
      "CTBenchmarks.jl core-ubuntu-latest (2026-01-30), jackson, Ipopt + JuMP, trapeze, "
      "grid_size 200, tol 1e-8 (objective reported as -x3(4)): an optimum of that discrete NLP";
  p.reference_scheme = "trapezoid";
  p.reference_intervals = 200;
  // Measured: with the default monotone barrier Ipopt stops at its acceptable level here; the
  // adaptive barrier of the peer's run reproduces the value (docs/problems/ctbench_b.md).
  p.reference_options = {{"mu_strategy", "adaptive"}};
  p.additional_references = {
      {-0.19182194736952385,
       "J",
       "trapezoid",
       500,
       "CTBenchmarks.jl core-ubuntu-latest (2026-01-30), jackson, Ipopt + JuMP, trapeze, "
       "grid_size 500, tol 1e-8 (objective reported as -x3(4))",
       // Measured as at N = 200: the monotone barrier stops at Ipopt's acceptable level 5.5e-7
       // from this value, the adaptive one reproduces it to 1.6e-12 (tol 1e-10).
       {{"mu_strategy", "adaptive"}}},
      {-0.19181482186966448,
       "J",
       "trapezoid",
       2000,
       "CTBenchmarks.jl core-ubuntu-latest (2026-01-30), jackson, Ipopt + JuMP, trapeze, "
       "grid_size 2000, tol 1e-8 (objective reported as -x3(4))"},
  };
  p.origin =
      "OptimalControlProblems.jl (control-toolbox) jackson, after the BOCOP example and Jackson, "
      "JOTA 2(1), 1968";
  p.hamiltonian_note = "not applicable: state bounds (0 <= a, b, x3 <= 1.1)";
  p.tags = {"singular-arc", "control-constrained", "mayer"};
  return p;
}

}  // namespace ocpb
