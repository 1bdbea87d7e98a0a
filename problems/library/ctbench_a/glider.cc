#include "problems/library/ctbench_a/glider.h"

#include <limits>
#include <memory>

#include "problems/reference/free_time_parameters.h"

namespace ocpb {

std::vector<ParameterSpec> Glider::ParameterSpecs() {
  std::vector<ParameterSpec> specs = FreeFinalTimeParameterSpecs(1000.0);
  for (ParameterSpec& s : specs) {
    if (s.name == "tf") s.default_value = {100.0};
  }
  return specs;
}

Glider::Glider(const Parameters& params) {
  SetHorizon(0.0, params.Scalar("tf"));
  CheckFreeFinalTimeParameters(params);
  SetFreeFinalTime(params.Scalar("tf_min"), params.Scalar("tf_max"));
  SetInitialState(Eigen::Vector4d(0.0, 1000.0, kSpeedX, kSpeedY));
  SetTerminalWeights(Vec::Constant(3, params.Scalar("C")));
  SetControlSet(ControlSet::Box(Vec::Zero(1), Vec::Constant(1, kLiftMax)));
  const double inf = std::numeric_limits<double>::infinity();
  SetStateBounds(Eigen::Vector4d(0.0, -inf, 0.0, -inf), Eigen::Vector4d(inf, inf, inf, inf));
}

}  // namespace ocpb

namespace ocpb {

ProblemInfo GliderProblemInfo() {
  ProblemInfo p;
  p.name = "glider";
  p.description = "COPS hang glider: max x(T) through a thermal updraft, T free, 0 <= cL <= 1.4";
  p.parameters = Glider::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<Glider>(params);
  };
  p.default_intervals = 500;
  p.reference_value = -1247.9784300226354;
  p.reference_source =
      "CTBenchmarks.jl core-ubuntu-latest results (OptimalControlProblems.jl glider, JuMP "
      "trapezoid model, Ipopt tol 1e-8), grid_size = 500: objective -x(T) = -1247.9784300226354";
  p.reference_scheme = "trapezoid";
  p.reference_intervals = 500;
  p.additional_references = {
      {-1248.8963625894698,
       "J",
       "trapezoid",
       200,
       "CTBenchmarks.jl core-ubuntu-latest, glider, JuMP + Ipopt, grid_size = 200"},
      {-1247.986999240766,
       "J",
       "trapezoid",
       2000,
       "CTBenchmarks.jl core-ubuntu-latest, glider, JuMP + Ipopt, grid_size = 2000"},
  };
  p.origin = "COPS 3.0 (Dolan, More, Munson 2004) glider, via OptimalControlProblems.jl";
  p.hamiltonian_note =
      "not applicable: free final time with state bounds, and no pointwise Hamiltonian minimizer";
  p.tags = {"free-time", "mayer", "control-constrained", "aerospace"};
  return p;
}

}  // namespace ocpb
