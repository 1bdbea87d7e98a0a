#include "problems/library/ctbench_a/cart_pendulum.h"

#include <limits>
#include <memory>

#include "problems/reference/free_time_parameters.h"

namespace ocpb {

std::vector<ParameterSpec> CartPendulum::ParameterSpecs() {
  return FreeFinalTimeParameterSpecs(100.0);  // tf = 1 (the source's start), tf_min = 0.1
}

CartPendulum::CartPendulum(const Parameters& params) {
  SetHorizon(0.0, params.Scalar("tf"));
  CheckFreeFinalTimeParameters(params);
  SetFreeFinalTime(params.Scalar("tf_min"), params.Scalar("tf_max"));
  const double inf = std::numeric_limits<double>::infinity();
  Vec x0(5);
  x0 << 0.0, 0.1, 0.0, 0.0, 0.1;  // v(0) and ddx start at the source's 0.1
  SetInitialState(x0);
  Vec lo0(5), hi0(5);
  lo0 << 0.0, -2.0, 0.0, 0.0, -inf;
  hi0 << 0.0, 2.0, 0.0, 0.0, inf;
  SetInitialStateBounds(lo0, hi0);
  SetStaticParameters(Vec::Constant(1, -inf), Vec::Constant(1, inf), Vec::Constant(1, 0.1));
  SetTerminalWeights(Vec::Constant(2, params.Scalar("C")));
  SetControlSet(ControlSet::Box(Vec::Constant(1, -5.0), Vec::Constant(1, 5.0)));
  Vec lo(5), hi(5);
  lo << -1.0, -2.0, -inf, -inf, -inf;
  hi << 1.0, 2.0, inf, inf, inf;
  SetStateBounds(lo, hi);
}

ProblemInfo CartPendulumProblemInfo() {
  ProblemInfo p;
  p.name = "cart-pendulum";
  p.description =
      "cart-pendulum swing-up in minimum time (OptimalControlProblems.jl), |F| <= 5, |x| <= 1, "
      "|v| <= 2";
  p.parameters = CartPendulum::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<CartPendulum>(params);
  };
  p.default_intervals = 500;
  p.reference_value = 1.7439655750387701;
  p.reference_source =
      "OptimalControlProblems.jl documentation, problem page cart_pendulum: Ipopt (tol 1e-8) on "
      "the JuMP trapezoid model at grid_size = 500, objective T = 1.7439655750387701";
  p.reference_scheme = "trapezoid";
  p.reference_intervals = 500;
  p.origin =
      "OptimalControlProblems.jl cart_pendulum (after the FATROP example, Vanroye et al. 2023)";
  p.hamiltonian_note =
      "not applicable: free final time, free initial state, static parameter and state bounds";
  p.tags = {"free-time",
            "free-initial-state",
            "static-parameters",
            "state-constrained",
            "control-constrained"};
  return p;
}

}  // namespace ocpb
