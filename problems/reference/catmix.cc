#include "problems/reference/catmix.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ocpb {

std::vector<ParameterSpec> Catmix::ParameterSpecs() {
  return {
      {"eps",
       {0.0},
       "control regularization eps int u^2 in the cost (0: COPS' problem)",
       0.0,
       1e300},
      {"hamiltonian_eps",
       {1e-4},
       "eps of the Hamiltonian reformulation when eps = 0",
       0.0,
       1e300,
       true},
  };
}

Catmix::Catmix(const Parameters& params)
    : Catmix(params.Scalar("eps"), params.Scalar("hamiltonian_eps")) {}

Catmix::Catmix(double eps, double hamiltonian_eps) : eps_(eps), hamiltonian_eps_(hamiltonian_eps) {
  if (!std::isfinite(eps) || eps < 0.0) throw std::invalid_argument("catmix: eps must be >= 0");
  if (!std::isfinite(hamiltonian_eps) || hamiltonian_eps <= 0.0) {
    throw std::invalid_argument("catmix: hamiltonian_eps must be > 0");
  }
  SetDimensions(2, 1, 0, 0);
  SetHorizon(0.0, 1.0);
  SetInitialState(Eigen::Vector2d(1.0, 0.0));
  SetControlSet(ControlSet::Box(Vec::Zero(1), Vec::Ones(1)));
}

double Catmix::SwitchingFunction(ConstVecRef x, ConstVecRef p) {
  return p[0] * (10.0 * x[1] - x[0]) + p[1] * (x[0] - 9.0 * x[1]);
}

void Catmix::MinimizeHamiltonian(double, ConstVecRef x, ConstVecRef p, VecRef u) const {
  const double s = SwitchingFunction(x, p);
  if (eps_ > 0.0) {
    u[0] = std::clamp(-s / (2.0 * eps_), 0.0, 1.0);
  } else {
    u[0] = s < 0.0 ? 1.0 : 0.0;
  }
}

std::unique_ptr<Ocp> Catmix::HamiltonianReformulation(
    const HamiltonianReformulationOptions& options) const {
  if (eps_ > 0.0) return nullptr;  // already regularized: fits as stated
  const double eps = options.regularization.value_or(hamiltonian_eps_);
  if (!std::isfinite(eps) || eps <= 0.0) {
    throw std::invalid_argument("catmix: the regularization eps must be finite and > 0");
  }
  return std::make_unique<Catmix>(eps, hamiltonian_eps_);
}

ProblemInfo CatmixProblemInfo() {
  ProblemInfo p;
  p.name = "catmix";
  p.description = "COPS catalyst mixing: min -1 + x1(1) + x2(1), u in [0, 1] (bang-singular-bang)";
  p.parameters = Catmix::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<Catmix>(params);
  };
  p.default_intervals = Catmix::kCopsIntervals;
  p.reference_value = Catmix::kCopsReferenceCost;
  p.reference_source =
      "COPS 3.0 (Dolan, More, Munson 2004), nh = 100, 3-point Gauss collocation: an optimum of "
      "that discrete NLP, not of the continuous problem";
  // 3-point Gauss-Legendre collocation, which OCPBench has no transcription for (the test
  // rebuilds it): no record matches it.
  p.reference_scheme = "gauss-legendre-3";
  p.reference_intervals = Catmix::kCopsIntervals;
  p.hamiltonian_note =
      "singular arc: eps int u^2 added to the cost (parameter hamiltonian_eps), u* = clip(-s/(2 "
      "eps), 0, 1)";
  p.tags = {"singular-arc", "control-constrained"};
  return p;
}

}  // namespace ocpb
