#include "problems/library/ctbench_b/balanced_field.h"

#include <limits>
#include <memory>
#include <stdexcept>

namespace ocpb {

std::vector<ParameterSpec> BalancedFieldOcp::ParameterSpecs() {
  return {
      {"C", {1e4}, "terminal penalty weight (penalty form)", 0.0, 1e300, true},
      {"tf", {10.0}, "nominal final time (where methods start; free in [0.1, 100])", 0.1, 100.0},
  };
}

BalancedFieldOcp::BalancedFieldOcp(const Parameters& params) {
  SetHorizon(0.0, params.Scalar("tf"));
  SetFreeFinalTime(0.1, 100.0);
  SetInitialState(Eigen::Vector4d(600.0, 70.0, 0.0, 0.0));
  SetTerminalWeights(Vec::Constant(2, params.Scalar("C")));
  SetControlSet(ControlSet::Box(Vec::Zero(1), Vec::Constant(1, kAlphaUpper)));
  const double inf = std::numeric_limits<double>::infinity();
  SetStateBounds(Eigen::Vector4d(-inf, 1.0, 0.0, -inf), Eigen::Vector4d(inf, inf, inf, inf));
}

ProblemInfo BalancedFieldProblemInfo() {
  ProblemInfo p;
  p.name = "balanced-field";
  p.description =
      "one-engine-out climb to the 35 ft screen (Dymos balanced field, single phase as in "
      "OptimalControlProblems.jl): min range r(tf), tf free";
  p.parameters = BalancedFieldOcp::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<BalancedFieldOcp>(params);
  };
  p.default_intervals = 200;
  p.reference_value = 771.01140030406498;
  p.reference_source =
      "OptimalControlProblems.jl documentation, problem page 'balanced_field' (built 2026-03-10): "
      "JuMP model, trapezoid, grid_size 200, Ipopt tol 1e-8, objective 7.7101140030406498e+02 "
      "(the OptimalControl model: 7.7101140030406475e+02): an optimum of that discrete NLP";
  p.reference_scheme = "trapezoid";
  p.reference_intervals = 200;
  p.origin =
      "OptimalControlProblems.jl (control-toolbox) balanced_field, after the Dymos example "
      "'Aircraft Balanced Field Length Calculation' (climb phase only)";
  p.hamiltonian_note = "not applicable: state bounds (v >= 1, h >= 0) and a free final time";
  p.tags = {"free-time", "aerospace", "mayer"};
  return p;
}

}  // namespace ocpb
