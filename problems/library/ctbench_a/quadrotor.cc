#include "problems/library/ctbench_a/quadrotor.h"

#include <limits>
#include <memory>

#include "problems/reference/free_time_parameters.h"

namespace ocpb {

std::vector<ParameterSpec> Quadrotor::ParameterSpecs() {
  return FreeFinalTimeParameterSpecs(100.0);  // T >= 0.1, starting at T = 1 (the source's)
}

Quadrotor::Quadrotor(const Parameters& params) {
  SetHorizon(0.0, params.Scalar("tf"));
  CheckFreeFinalTimeParameters(params);
  SetFreeFinalTime(params.Scalar("tf_min"), params.Scalar("tf_max"));
  Vec x0 = Vec::Zero(8);
  x0[2] = 2.5;
  SetInitialState(x0);
  SetTerminalWeights(Vec::Constant(6, params.Scalar("C")));
  const double inf = std::numeric_limits<double>::infinity();
  Vec ulo(4), uhi(4);
  ulo << 0.0, -kTiltRateMax, -kTiltRateMax, -inf;
  uhi << kThrustMax, kTiltRateMax, kTiltRateMax, inf;
  SetControlSet(ControlSet::Box(ulo, uhi));
  const double half_pi = 0.5 * 3.14159265358979323846;
  Vec lo = Vec::Constant(8, -inf), hi = Vec::Constant(8, inf);
  lo[6] = lo[7] = -half_pi;
  hi[6] = hi[7] = half_pi;
  SetStateBounds(lo, hi);
}

ProblemInfo QuadrotorProblemInfo() {
  ProblemInfo p;
  p.name = "quadrotor";
  p.description =
      "quadrotor point to point (OptimalControlProblems.jl): min T + small effort, tilt cone, "
      "bounded thrust and tilt rates";
  p.parameters = Quadrotor::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<Quadrotor>(params);
  };
  p.default_intervals = 50;
  p.reference_value = 1.4926817085418598;
  p.reference_source =
      "OptimalControlProblems.jl documentation, problem page quadrotor: Ipopt (tol 1e-8) on the "
      "JuMP trapezoid model at nh = 50, objective T + int dc = 1.4926817085418598";
  p.reference_scheme = "trapezoid";
  p.reference_intervals = 50;
  p.origin = "OptimalControlProblems.jl quadrotor (after the FATROP example, Vanroye et al. 2023)";
  p.hamiltonian_note =
      "not applicable: free final time with a path constraint and state bounds, and no "
      "pointwise Hamiltonian minimizer";
  p.tags = {"free-time", "control-constrained", "state-constrained", "aerospace"};
  return p;
}

}  // namespace ocpb
