#include "problems/library/classic/singular_double_integrator.h"

#include <memory>

#include "problems/reference/free_time_parameters.h"

namespace ocpb {

std::vector<ParameterSpec> SingularDoubleIntegrator::ParameterSpecs() {
  return {
      {"C", {1000.0}, "terminal penalty weight (penalty form)", 0.0, 1e300, true},
      {"tf",
       {5.0},
       "nominal final time: where methods start (within [tf_min, tf_max])",
       0.0,
       1e6,
       true},
      {"tf_min", {2.0}, "lower bound of the free final time", 0.0, 1e6, true},
      {"tf_max", {8.0}, "upper bound of the free final time", 0.0, 1e6, true},
  };
}

SingularDoubleIntegrator::SingularDoubleIntegrator(const Parameters& params) {
  SetHorizon(0.0, params.Scalar("tf"));
  CheckFreeFinalTimeParameters(params);
  SetFreeFinalTime(params.Scalar("tf_min"), params.Scalar("tf_max"));
  SetInitialState(Eigen::Vector2d(2.0, 0.0));
  SetTerminalWeights(Vec::Constant(2, params.Scalar("C")));
  ControlSet set;
  set.AddBox(Vec::Constant(1, -1.0), Vec::Constant(1, 1.0));
  SetControlSet(set);
}

ProblemInfo SingularDoubleIntegratorProblemInfo() {
  ProblemInfo p;
  p.name = "singular-double-integrator";
  p.description =
      "double integrator (2, 0) -> (5, 0), |u| <= 1, int (1 + x2^2)/2 over a free T: "
      "bang-singular-bang";
  p.parameters = SingularDoubleIntegrator::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<SingularDoubleIntegrator>(params);
  };
  p.default_intervals = 100;
  p.reference_value = SingularDoubleIntegrator::kReferenceCost;
  p.reference_source =
      "analytic (Locatelli 2017, problem 11.2-1a; PSOPT example singular_di): u = +1 on [0, 1], "
      "0 on [1, 3], -1 on [3, 4]; T* = 4, J* = 10/3";
  p.additional_references = {{SingularDoubleIntegrator::kOptimalTime,
                              "tf",
                              "continuous",
                              0,
                              "analytic (Locatelli 2017, problem 11.2-1a): T* = 4"}};
  p.origin = "Locatelli 2017, problem 11.2-1a; PSOPT example singular_di";
  p.hamiltonian_note =
      "free final time: the descent keeps tf fixed (not applicable); H is linear in u "
      "(singular arc)";
  p.tags = {"singular-arc", "free-time", "control-constrained"};
  return p;
}

}  // namespace ocpb
