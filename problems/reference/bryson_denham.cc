#include "problems/reference/bryson_denham.h"

#include <cmath>
#include <stdexcept>

#include "problems/reference/path_penalty_ocp.h"

namespace ocpb {

std::vector<ParameterSpec> BrysonDenham::ParameterSpecs() {
  return {
      {"C", {1e4}, "terminal penalty weight (penalty form)", 0.0, 1e300, true},
      {"rho", {1e5}, "path penalty weight of the Hamiltonian reformulation", 0.0, 1e300, true},
  };
}

BrysonDenham::BrysonDenham(const Parameters& params, double l) : l_(l), rho_(params.Scalar("rho")) {
  if (!(l > 0.0) || !std::isfinite(l)) throw std::invalid_argument("bryson-denham: l must be > 0");
  SetDimensions(2, 1, 2, 1);
  SetHorizon(0.0, 1.0);
  SetInitialState(Eigen::Vector2d(0.0, 1.0));
  SetTerminalWeights(Vec::Constant(2, params.Scalar("C")));
}

void BrysonDenham::MinimizeHamiltonian(double, ConstVecRef, ConstVecRef p, VecRef u) const {
  u[0] = -p[1];  // argmin_u p2 u + u^2/2
}

std::unique_ptr<Ocp> BrysonDenham::HamiltonianReformulation(
    const HamiltonianReformulationOptions& options) const {
  // c = x1 - l does not involve u, so the penalized H has the same minimizer u* = -p2.
  return std::make_unique<PathPenaltyOcp>(std::make_unique<BrysonDenham>(*this),
                                          options.path_penalty.value_or(rho_));
}

Eigen::Vector2d BrysonDenham::OptimalState(double t, double l) {
  const double t1 = 3.0 * l;
  if (t > 1.0 - t1) {
    const Eigen::Vector2d m = OptimalState(1.0 - t, l);
    return Eigen::Vector2d(m[0], -m[1]);
  }
  if (t >= t1) return Eigen::Vector2d(l, 0.0);
  const double s = 1.0 - t / t1;
  return Eigen::Vector2d(l * (1.0 - s * s * s), s * s);
}

double BrysonDenham::OptimalControl(double t, double l) {
  const double t1 = 3.0 * l;
  if (t > 1.0 - t1) return OptimalControl(1.0 - t, l);
  if (t >= t1) return 0.0;
  return -2.0 / t1 * (1.0 - t / t1);
}

Eigen::Vector2d BrysonDenham::OptimalCostate(double t, double l) {
  const double t1 = 3.0 * l;
  const double p1 = 2.0 / (9.0 * l * l);
  const double p2 = -OptimalControl(t, l);
  if (t < t1) return Eigen::Vector2d(p1, p2);
  if (t > 1.0 - t1) return Eigen::Vector2d(-p1, p2);
  return Eigen::Vector2d(0.0, 0.0);
}

ProblemInfo BrysonDenhamProblemInfo() {
  ProblemInfo p;
  p.name = "bryson-denham";
  p.description = "double integrator, 1/2 int u^2, fixed endpoints, state bound x1 <= 1/9";
  p.parameters = BrysonDenham::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<BrysonDenham>(params);
  };
  p.default_intervals = 100;
  p.reference_value = BrysonDenham::OptimalCost();
  p.reference_source =
      "analytic J* = 4/(9l), l = 1/9 (Bryson, Denham, Dreyfus 1963; Bryson-Ho Sec. 3.11; "
      "CTProblems.jl double_integrator_energy_state_constraint)";
  p.hamiltonian_note =
      "path constraint x1 <= 1/9 as the penalty rho max(0, x1 - 1/9)^2 in L (parameter rho), "
      "u* = -p2";
  p.tags = {"state-constrained"};
  return p;
}

}  // namespace ocpb
