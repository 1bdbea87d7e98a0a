#include "problems/reference/rayleigh.h"

#include "problems/reference/path_penalty_ocp.h"

namespace ocpb {

std::vector<ParameterSpec> Rayleigh::ParameterSpecs() {
  return {{"rho", {1e3}, "path penalty weight of the Hamiltonian reformulation", 0.0, 1e300, true}};
}

Rayleigh::Rayleigh(const Parameters& params) : rho_(params.Scalar("rho")) {
  SetDimensions(2, 1, 0, 1);
  SetHorizon(0.0, 4.5);
  SetInitialState(Eigen::Vector2d(-5.0, -5.0));
}

void Rayleigh::MinimizeHamiltonian(double, ConstVecRef, ConstVecRef p, VecRef u) const {
  u[0] = -2.0 * p[1];  // argmin_u u^2 + 4 p2 u
}

double Rayleigh::PenalizedMinimizer(double rho, double x1, double p2) {
  const double u0 = -2.0 * p2;
  if (u0 + x1 / 6.0 <= 0.0) return u0;
  return (u0 - rho * x1 / 6.0) / (1.0 + rho);
}

std::unique_ptr<Ocp> Rayleigh::HamiltonianReformulation(
    const HamiltonianReformulationOptions& options) const {
  const double rho = options.path_penalty.value_or(rho_);
  return std::make_unique<PathPenaltyOcp>(std::make_unique<Rayleigh>(*this),
                                          rho,
                                          [rho](double, ConstVecRef x, ConstVecRef p, VecRef u) {
                                            u[0] = PenalizedMinimizer(rho, x[0], p[1]);
                                          });
}

ProblemInfo RayleighProblemInfo() {
  ProblemInfo p;
  p.name = "rayleigh";
  p.description =
      "Rayleigh oscillator, int_0^4.5 x1^2 + u^2 (no 1/2), mixed constraint u + x1/6 <= 0";
  p.parameters = Rayleigh::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<Rayleigh>(params);
  };
  p.default_intervals = 100;
  p.reference_value = Rayleigh::kReferenceCost;
  p.reference_source = "Betts 2010, example 10.113 (Maurer & Augustin); PMP-BVP 44.80444491";
  p.hamiltonian_note =
      "mixed constraint u + x1/6 <= 0 as the penalty rho max(0, u + x1/6)^2 in L (parameter rho), "
      "exact piecewise minimizer";
  p.tags = {"mixed-constraint"};
  return p;
}

}  // namespace ocpb
