#include "problems/library/ctbench_a/dielectrophoretic_particle.h"

#include <memory>

#include "problems/reference/free_time_parameters.h"

namespace ocpb {

std::vector<ParameterSpec> DielectrophoreticParticle::ParameterSpecs() {
  std::vector<ParameterSpec> specs = FreeFinalTimeParameterSpecs(100.0);
  for (ParameterSpec& s : specs) {
    // The source starts at T = 5 with the states x = y = 1 at every node; from the states
    // simulated under u = 0.1, Ipopt reports local infeasibility at T = 5, 8 and 10 (N = 500)
    // and converges from T = 20.
    if (s.name == "tf") s.default_value = {20.0};
  }
  return specs;
}

DielectrophoreticParticle::DielectrophoreticParticle(const Parameters& params) {
  SetHorizon(0.0, params.Scalar("tf"));
  CheckFreeFinalTimeParameters(params);
  SetFreeFinalTime(params.Scalar("tf_min"), params.Scalar("tf_max"));
  SetInitialState(Eigen::Vector2d(kStart, 0.0));
  SetTerminalWeights(Vec::Constant(1, params.Scalar("C")));
  SetControlSet(ControlSet::Box(Vec::Constant(1, -1.0), Vec::Constant(1, 1.0)));
}

ProblemInfo DielectrophoreticParticleProblemInfo() {
  ProblemInfo p;
  p.name = "dielectrophoretic-particle";
  p.description =
      "dielectrophoretic particle (Chang, Petit, Rouchon): x from 1 to 2 in minimum time, "
      "|u| <= 1";
  p.parameters = DielectrophoreticParticle::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<DielectrophoreticParticle>(params);
  };
  p.default_intervals = 500;
  p.reference_value = 7.8113236810783082;
  p.reference_source =
      "OptimalControlProblems.jl documentation, problem page dielectrophoretic_particle: Ipopt "
      "(tol 1e-8) on the JuMP trapezoid model at grid_size = 500, objective T = "
      "7.8113236810783082";
  p.reference_scheme = "trapezoid";
  p.reference_intervals = 500;
  p.origin =
      "Chang, Petit, Rouchon 2006 (time-optimal dielectrophoretic particle), via "
      "OptimalControlProblems.jl dielectrophoretic_particle";
  p.hamiltonian_note = "not applicable: free final time, and no pointwise Hamiltonian minimizer";
  p.tags = {"free-time", "control-constrained", "singular-arc"};
  return p;
}

}  // namespace ocpb
