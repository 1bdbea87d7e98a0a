#include "problems/library/ctbench_a/truck_trailer.h"

#include <limits>
#include <memory>

#include "problems/reference/free_time_parameters.h"

namespace ocpb {

std::vector<ParameterSpec> TruckTrailer::ParameterSpecs() {
  std::vector<ParameterSpec> specs = FreeFinalTimeParameterSpecs(1000.0);
  for (ParameterSpec& s : specs) {
    if (s.name == "tf") s.default_value = {10.0};  // the source's start
    if (s.name == "tf_min") s.default_value = {1.0};
  }
  return specs;
}

TruckTrailer::TruckTrailer(const Parameters& params) {
  SetHorizon(0.0, params.Scalar("tf"));
  CheckFreeFinalTimeParameters(params);
  SetFreeFinalTime(params.Scalar("tf_min"), params.Scalar("tf_max"));
  const double inf = std::numeric_limits<double>::infinity();
  Vec x0 = Vec::Zero(7);
  x0[5] = 0.1;  // v0 and delta0 start at the source's 0.1
  x0[6] = 0.1;
  SetInitialState(x0);
  Vec lo(7), hi(7);
  lo << -inf, -inf, -0.5 * kPi, -0.5 * kPi, -inf, -0.2, -kPi / 6.0;
  hi << inf, inf, 0.5 * kPi, 0.5 * kPi, inf, 0.2, kPi / 6.0;
  // v0(0) and delta0(0) are free within their bounds; the other states start at 0.
  Vec lo0 = Vec::Zero(7), hi0 = Vec::Zero(7);
  lo0[5] = lo[5];
  hi0[5] = hi[5];
  lo0[6] = lo[6];
  hi0[6] = hi[6];
  SetInitialStateBounds(lo0, hi0);
  SetTerminalWeights(Vec::Constant(5, params.Scalar("C")));
  SetControlSet(
      ControlSet::Box(Eigen::Vector2d(-1.0, -kPi / 10.0), Eigen::Vector2d(1.0, kPi / 10.0)));
  SetStateBounds(lo, hi);
}

ProblemInfo TruckTrailerProblemInfo() {
  ProblemInfo p;
  p.name = "truck-trailer";
  p.description =
      "truck with two trailers parked vertically (OptimalControlProblems.jl): min T + int of "
      "the squared hitch angles";
  p.parameters = TruckTrailer::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<TruckTrailer>(params);
  };
  p.default_intervals = 200;
  p.reference_value = 59.230286794623986;
  p.reference_source =
      "OptimalControlProblems.jl documentation, problem page truck_trailer: Ipopt (tol 1e-8) on "
      "the JuMP trapezoid model at grid_size = 200, objective 59.230286794623986 (the "
      "OptimalControl model of the same page: 59.230286957671595)";
  p.reference_scheme = "trapezoid";
  p.reference_intervals = 200;
  p.origin =
      "OptimalControlProblems.jl truck_trailer (after the FATROP example, Vanroye et al. 2023)";
  p.hamiltonian_note =
      "not applicable: free final time, free initial state, path constraints and state bounds";
  p.tags = {"free-time", "free-initial-state", "state-constrained", "control-constrained"};
  return p;
}

}  // namespace ocpb
