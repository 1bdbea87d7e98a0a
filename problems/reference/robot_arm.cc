#include "problems/reference/robot_arm.h"

#include <cmath>

namespace ocpb {

std::vector<ParameterSpec> RobotArm::ParameterSpecs() {
  // eps = 100: with T about 9.14, sigma is constant to 6e-6 relative on the trapezoid at nh = 200
  // (eps = 1: 6e-4), so that the transcription is COPS' constant-step scheme.
  return ScalingParameterSpecs(1e3, 100.0, 1.0, 30.0);
}

RobotArm::RobotArm(const Parameters& params) {
  // Nominal: no torque for T = 9 (the arm rests at its start; the NLP's states start there).
  Vec y0 = Vec::Zero(6);
  y0[0] = 4.5;
  y0[2] = M_PI / 4.0;
  InitializeScaling(params, y0, {-1.0, -1.0, -1.0}, {1.0, 1.0, 1.0}, Vec::Zero(3), 9.0);
}

ProblemInfo RobotArmProblemInfo() {
  ProblemInfo p;
  p.name = "robot-arm";
  p.description = "COPS robot arm: min T, bang-bang torques (time scaling: J = T)";
  p.parameters = RobotArm::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<RobotArm>(params);
  };
  p.default_intervals = RobotArm::kCopsIntervals;
  p.reference_value = RobotArm::kCopsReferenceTime;
  p.reference_source =
      "COPS 3.0 (Dolan, More, Munson 2004) robot, trapezoid nh = 200: T = 9.14138, an optimum of "
      "that discrete NLP";
  p.reference_scheme = "trapezoid";
  p.reference_intervals = RobotArm::kCopsIntervals;
  p.hamiltonian_note =
      "free T by time scaling (sigma = dt/ds a control, eps Var(sigma) in J: exact), torques as "
      "v = sigma w in the cone |v_i| <= sigma, penalized in the Hamiltonian reformulation (rho "
      "dist^2, parameter rho)";
  p.tags = {"bang-bang", "free-time", "control-constrained"};
  return p;
}

}  // namespace ocpb
