#include "problems/library/ctbench_a/moonlander.h"

#include <memory>

#include "problems/reference/free_time_parameters.h"

namespace ocpb {

std::vector<ParameterSpec> Moonlander::ParameterSpecs() {
  return FreeFinalTimeParameterSpecs(1.0);  // 0.1 <= T <= 1, starting at T = 1
}

Moonlander::Moonlander(const Parameters& params) {
  SetHorizon(0.0, params.Scalar("tf"));
  CheckFreeFinalTimeParameters(params);
  SetFreeFinalTime(params.Scalar("tf_min"), params.Scalar("tf_max"));
  SetInitialState(Vec::Zero(6));
  SetTerminalWeights(Vec::Constant(4, params.Scalar("C")));
  SetControlSet(ControlSet::Box(Vec::Zero(2), Vec::Constant(2, 2.0 * kGravity)));
}

ProblemInfo MoonlanderProblemInfo() {
  ProblemInfo p;
  p.name = "moonlander";
  p.description =
      "planar moon lander (OptimalControlProblems.jl): rest to rest at (5, 5) in minimum time, "
      "two thrusters 0 <= F <= 2g";
  p.parameters = Moonlander::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<Moonlander>(params);
  };
  p.default_intervals = 500;
  p.reference_value = 0.96181005310879608;
  p.reference_source =
      "OptimalControlProblems.jl documentation, problem page moonlander: Ipopt (tol 1e-8) on the "
      "JuMP trapezoid model at grid_size = 500, objective T = 0.96181005310879608";
  p.reference_scheme = "trapezoid";
  p.reference_intervals = 500;
  // Measured (results/notes/2026-12-07-ipopt-mumps-scaling.md): with MUMPS's automatic scaling
  // each factorization of this NLP takes seconds (79 iterations in Ipopt's 600 s); without it
  // Ipopt converges in 48 iterations and 0.45 s to 9.3e-10 of the value.
  p.reference_options = {{"mumps_scaling", "0"}};
  p.origin = "OptimalControlProblems.jl moonlander (after the FATROP example, Vanroye et al. 2023)";
  p.hamiltonian_note = "not applicable: free final time, and no pointwise Hamiltonian minimizer";
  p.tags = {"free-time", "bang-bang", "control-constrained"};
  return p;
}

}  // namespace ocpb
