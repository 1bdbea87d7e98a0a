#include "problems/reference/free_time_double_integrator.h"

#include <memory>

#include "problems/reference/free_time_parameters.h"

namespace ocpb {

std::vector<ParameterSpec> FreeTimeDoubleIntegrator::ParameterSpecs() {
  return FreeFinalTimeParameterSpecs(100.0);
}

FreeTimeDoubleIntegrator::FreeTimeDoubleIntegrator(const Parameters& params) {
  SetDimensions(2, 1, 2, 0);
  SetHorizon(0.0, params.Scalar("tf"));
  CheckFreeFinalTimeParameters(params);
  SetFreeFinalTime(params.Scalar("tf_min"), params.Scalar("tf_max"));
  SetInitialState(Eigen::Vector2d(-1.0, 0.0));
  SetTerminalWeights(Vec::Constant(2, params.Scalar("C")));
}

void FreeTimeDoubleIntegrator::MinimizeHamiltonian(double,
                                                   ConstVecRef,
                                                   ConstVecRef p,
                                                   VecRef u) const {
  u[0] = -p[1];
}

ProblemInfo FreeTimeDoubleIntegratorProblemInfo() {
  ProblemInfo p;
  p.name = "double-integrator-free-time";
  p.description = "double integrator, (-1, 0) to rest at 0, int (1 + u^2/2) over a free final time";
  p.parameters = FreeTimeDoubleIntegrator::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<FreeTimeDoubleIntegrator>(params);
  };
  p.default_intervals = 100;
  p.reference_value = FreeTimeDoubleIntegrator::OptimalCost();
  p.reference_source =
      "analytic: J(T) = T + 6/T^3, T* = 18^(1/4) = 2.0597671, J* = 4 T*/3 (maximum principle, "
      "H(T) = 0)";
  p.hamiltonian_note =
      "free final time: the descent keeps tf fixed (not applicable); indirect-newton (H(T) = 0) "
      "and the NLP solvers on a collocation transcription (T a variable) take it";
  p.tags = {"smooth", "free-time"};
  return p;
}

}  // namespace ocpb
