#include "problems/reference/steering.h"

namespace ocpb {

std::vector<ParameterSpec> Steering::ParameterSpecs() {
  return ScalingParameterSpecs(1e3, 0.05, 5.0);
}

Steering::Steering(const Parameters& params) {
  // Nominal: thrust along x1 (w = (1, 0)), tf about 45 / a = 0.45 s to reach x3 = 45.
  InitializeScaling(params, Eigen::Vector4d::Zero(), Eigen::Vector2d(1.0, 0.0), 45.0 / kThrust);
}

ProblemInfo SteeringProblemInfo() {
  ProblemInfo p;
  p.name = "steering";
  p.description = "linear tangent steering (COPS steering), min tf (time scaling: J = tf)";
  p.parameters = Steering::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<Steering>(params);
  };
  p.default_intervals = 100;
  p.reference_value = Steering::kReferenceTime;
  p.reference_source =
      "continuous optimum by shooting (project notes 1.4; PSOPT lts: 0.5545709); COPS 3.0 "
      "trapezoid nh = 200: 0.554577";
  p.hamiltonian_note =
      "free tf by time scaling (sigma = dt/ds a control, eps Var(sigma) in J: exact), angle as "
      "unit vector w in the disc (the half-disc bound is inactive)";
  p.tags = {"smooth", "free-time"};
  return p;
}

}  // namespace ocpb
