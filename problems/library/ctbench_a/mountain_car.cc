#include "problems/library/ctbench_a/mountain_car.h"

#include <limits>
#include <memory>

#include "problems/reference/free_time_parameters.h"

namespace ocpb {

std::vector<ParameterSpec> MountainCar::ParameterSpecs() {
  std::vector<ParameterSpec> specs = FreeFinalTimeParameterSpecs(1000.0);
  // OptimalControlProblems.jl: tf_start = 110, tf >= tf_min = 0.1 (no upper bound there).
  for (ParameterSpec& s : specs) {
    if (s.name == "tf") s.default_value = {110.0};
  }
  return specs;
}

MountainCar::MountainCar(const Parameters& params) {
  SetHorizon(0.0, params.Scalar("tf"));
  CheckFreeFinalTimeParameters(params);
  SetFreeFinalTime(params.Scalar("tf_min"), params.Scalar("tf_max"));
  SetInitialState(Eigen::Vector2d(-0.5, 0.0));
  SetTerminalWeights(Vec::Constant(1, params.Scalar("C")));
  SetControlSet(ControlSet::Box(Vec::Constant(1, -1.0), Vec::Constant(1, 1.0)));
  SetStateBounds(Eigen::Vector2d(-1.2, -0.07), Eigen::Vector2d(0.5, 0.07));
  SetBoundaryConstraints(Vec::Zero(1), Vec::Constant(1, std::numeric_limits<double>::infinity()));
}

ProblemInfo MountainCarProblemInfo() {
  ProblemInfo p;
  p.name = "mountain-car";
  p.description =
      "mountain car (OptimalControlProblems.jl): min T, bang-bang |u| <= 1, bounded position and "
      "speed";
  p.parameters = MountainCar::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<MountainCar>(params);
  };
  p.default_intervals = 200;
  p.reference_value = MountainCar::kTrapezoid200;
  p.reference_source =
      "OptimalControlProblems.jl documentation, problem page mountain_car: Ipopt (tol 1e-8) on "
      "the JuMP trapezoid model at grid_size = 200, objective tf = 102.39757015622749";
  p.reference_scheme = "trapezoid";
  p.reference_intervals = 200;
  p.origin = "OptimalControlProblems.jl mountain_car (after the Dymos example and Moore 1990)";
  p.hamiltonian_note =
      "not applicable: free final time with state bounds and a boundary constraint, and no "
      "pointwise Hamiltonian minimizer";
  p.tags = {
      "bang-bang", "free-time", "state-constrained", "control-constrained", "boundary-constraints"};
  return p;
}

}  // namespace ocpb
