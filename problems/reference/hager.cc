#include "problems/reference/hager.h"

#include <cmath>

namespace ocpb {

Hager::Hager() {
  SetDimensions(1, 1, 0, 0);
  SetHorizon(0.0, 1.0);
  SetInitialState(Vec::Ones(1));
}

void Hager::MinimizeHamiltonian(double, ConstVecRef, ConstVecRef p, VecRef u) const {
  u[0] = -p[0];  // argmin_u p u + u^2/2
}

double Hager::OptimalState(double t) {
  const double e3 = std::exp(3.0);
  return (2.0 * std::exp(3.0 * t) + e3) / (std::exp(1.5 * t) * (2.0 + e3));
}

double Hager::OptimalControl(double t) {
  const double e3 = std::exp(3.0);
  return 2.0 * (std::exp(3.0 * t) - e3) / (std::exp(1.5 * t) * (2.0 + e3));
}

ProblemInfo HagerProblemInfo() {
  ProblemInfo p;
  p.name = "hager";
  p.description =
      "Hager's scalar problem x' = x/2 + u, 1/2 int u^2 + 2x^2 (closed-form x*, u*, p*)";
  p.parameters = Hager::ParameterSpecs();
  p.make = [](const Parameters&, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<Hager>();
  };
  p.default_intervals = 100;
  p.reference_value = Hager::kReferenceCost;
  p.reference_source =
      "closed form (Hager, Numer. Math. 87, 2000); quadrature and Riccati agree to 1e-14";
  p.reference_costate = [](double t) { return Vec::Constant(1, Hager::OptimalCostate(t)); };
  p.tags = {"smooth"};
  return p;
}

}  // namespace ocpb
