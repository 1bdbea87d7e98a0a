#include "problems/library/classic/f8_aircraft.h"

#include <memory>

#include "problems/reference/free_time_parameters.h"

namespace ocpb {

std::vector<ParameterSpec> F8Aircraft::ParameterSpecs() {
  return {
      {"C", {1000.0}, "terminal penalty weight (penalty form)", 0.0, 1e300, true},
      {"tf",
       {4.0},
       "nominal final time: where methods start (within [tf_min, tf_max])",
       0.0,
       1e6,
       true},
      {"tf_min", {1.0}, "lower bound of the free final time", 0.0, 1e6, true},
      {"tf_max", {8.0}, "upper bound of the free final time", 0.0, 1e6, true},
  };
}

F8Aircraft::F8Aircraft(const Parameters& params) {
  SetHorizon(0.0, params.Scalar("tf"));
  CheckFreeFinalTimeParameters(params);
  SetFreeFinalTime(params.Scalar("tf_min"), params.Scalar("tf_max"));
  SetInitialState(Eigen::Vector3d(0.4655, 0.0, 0.0));
  SetTerminalWeights(Vec::Constant(3, params.Scalar("C")));
  ControlSet set;
  set.AddBox(Vec::Constant(1, 0.0), Vec::Constant(1, 1.0));
  SetControlSet(set);
}

ProblemInfo F8AircraftProblemInfo() {
  ProblemInfo p;
  p.name = "f8-aircraft";
  p.description =
      "F-8 aircraft minimum time to the origin, tail deflection +-0.05236 relaxed by outer "
      "convexification (mintOC)";
  p.parameters = F8Aircraft::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<F8Aircraft>(params);
  };
  p.default_intervals = 200;
  p.reference_value = F8Aircraft::kReferenceTime;
  p.reference_source =
      "mintOC (mintoc.de, F-8 aircraft; Kaya & Noakes 2003, Sager 2005): best known T* = 3.78086 "
      "(also PSOPT example f8)";
  p.origin = "Kaya & Noakes 2003 / mintOC; PSOPT example f8";
  p.hamiltonian_note = "free final time: the descent keeps tf fixed (not applicable)";
  p.tags = {"bang-bang", "free-time", "control-constrained", "aerospace"};
  return p;
}

}  // namespace ocpb
