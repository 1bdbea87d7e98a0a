#include "problems/reference/time_parameter_double_integrator.h"

#include <limits>
#include <memory>

#include "problems/reference/free_time_double_integrator.h"

namespace ocpb {

std::vector<ParameterSpec> TimeParameterDoubleIntegrator::ParameterSpecs() {
  return {{"C", {1e3}, "terminal penalty weight (penalty form)", 0.0, 1e300, true}};
}

TimeParameterDoubleIntegrator::TimeParameterDoubleIntegrator(const Parameters& params) {
  SetHorizon(0.0, 1.0);
  SetInitialState(Eigen::Vector3d(-1.0, 0.0, 0.0));
  SetTerminalWeights(Vec::Constant(2, params.Scalar("C")));
  SetStaticParameters(Vec::Constant(1, 0.1), Vec::Constant(1, 100.0), Vec::Constant(1, 1.0));
}

void TimeParameterDoubleIntegrator::MinimizeHamiltonian(double,
                                                        ConstVecRef x,
                                                        ConstVecRef p,
                                                        VecRef u) const {
  u[0] = x[2] > 0.0 ? -p[1] : std::numeric_limits<double>::quiet_NaN();
}

ProblemInfo TimeParameterDoubleIntegratorProblemInfo() {
  ProblemInfo p;
  p.name = "double-integrator-time-parameter";
  p.description =
      "double-integrator-free-time on s in [0, 1] with T a static parameter (x' = T f, L = T (1 "
      "+ u^2/2))";
  p.parameters = TimeParameterDoubleIntegrator::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<TimeParameterDoubleIntegrator>(params);
  };
  p.default_intervals = 50;
  p.reference_value = FreeTimeDoubleIntegrator::OptimalCost();
  p.reference_source =
      "analytic J* = 4 T*/3, T* = 18^(1/4) (as double-integrator-free-time: T + 6/T^3 minimized)";
  p.hamiltonian_note =
      "not applicable: a static parameter (the paper's descent keeps x0 fixed); the family "
      "(hamiltonian-proximal, -al, -polish) on forward Euler takes it (its gradient is T's "
      "adjoint lambda_T(0)), as indirect-newton does (transversality p_T(0) = 0)";
  p.tags = {"smooth", "free-time", "static-parameters"};
  return p;
}

}  // namespace ocpb
