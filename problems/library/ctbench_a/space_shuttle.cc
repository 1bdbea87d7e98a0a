#include "problems/library/ctbench_a/space_shuttle.h"

#include <limits>
#include <memory>

#include "problems/reference/free_time_parameters.h"

namespace ocpb {

std::vector<ParameterSpec> SpaceShuttle::ParameterSpecs() {
  // OptimalControlProblems.jl: 500 * 3.5 <= tf <= 500 * 4.5, starting at their midpoint.
  std::vector<ParameterSpec> specs = FreeFinalTimeParameterSpecs(2250.0);
  for (ParameterSpec& s : specs) {
    if (s.name == "tf") s.default_value = {2000.0};
    if (s.name == "tf_min") s.default_value = {1750.0};
  }
  return specs;
}

SpaceShuttle::SpaceShuttle(const Parameters& params) {
  SetHorizon(0.0, params.Scalar("tf"));
  CheckFreeFinalTimeParameters(params);
  SetFreeFinalTime(params.Scalar("tf_min"), params.Scalar("tf_max"));
  Vec x0(6);
  x0 << 2.6, 0.0, 0.0, 2.56, -1.0 * kDeg, 90.0 * kDeg;
  SetInitialState(x0);
  SetTerminalWeights(Vec::Constant(3, params.Scalar("C")));
  SetControlSet(ControlSet::Box(Eigen::Vector2d(-90.0 * kDeg, -89.0 * kDeg),
                                Eigen::Vector2d(90.0 * kDeg, 1.0 * kDeg)));
  const double inf = std::numeric_limits<double>::infinity();
  const double two_pi = 2.0 * 3.14159265358979323846;
  Vec lo(6), hi(6);
  lo << 0.0, -two_pi, -89.0 * kDeg, 1e-4, -89.0 * kDeg, -two_pi;
  hi << inf, two_pi, 89.0 * kDeg, inf, 89.0 * kDeg, two_pi;
  SetStateBounds(lo, hi);
}

ProblemInfo SpaceShuttleProblemInfo() {
  ProblemInfo p;
  p.name = "space-shuttle";
  p.description =
      "shuttle reentry (Betts ex. 6.1 without heating limit): max crossrange theta(T), T free";
  p.parameters = SpaceShuttle::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<SpaceShuttle>(params);
  };
  p.default_intervals = 500;
  p.reference_value = -0.59587501342513927;
  p.reference_source =
      "OptimalControlProblems.jl documentation, problem page space_shuttle: Ipopt (tol 1e-8) on "
      "the JuMP trapezoid model at grid_size = 500, objective -theta(T) = -0.59587501342513927";
  p.reference_scheme = "trapezoid";
  p.reference_intervals = 500;
  p.origin =
      "Betts 2010, example 6.1 (shuttle reentry, no heating limit), via the JuMP tutorial and "
      "OptimalControlProblems.jl space_shuttle";
  p.hamiltonian_note =
      "not applicable: free final time with state bounds, and no pointwise Hamiltonian minimizer";
  p.tags = {"free-time", "mayer", "aerospace"};
  return p;
}

}  // namespace ocpb
