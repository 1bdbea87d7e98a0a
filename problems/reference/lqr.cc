#include "problems/reference/lqr.h"

namespace ocpb {

Lqr::Lqr() {
  SetDimensions(2, 1, 0, 0);
  SetHorizon(0.0, 5.0);
  SetInitialState(Eigen::Vector2d(0.0, 1.0));
}

Eigen::Matrix2d Lqr::A() {
  Eigen::Matrix2d a;
  a << 0.0, 1.0, -1.0, 0.0;
  return a;
}

Eigen::Vector2d Lqr::B() { return Eigen::Vector2d(0.0, 1.0); }

void Lqr::MinimizeHamiltonian(double, ConstVecRef, ConstVecRef p, VecRef u) const {
  u[0] = -p[1];  // argmin_u p2 u + u^2/2
}

ProblemInfo LqrProblemInfo() {
  ProblemInfo p;
  p.name = "lqr";
  p.description = "LQR x' = [0 1; -1 0] x + [0; 1] u, 1/2 int_0^5 |x|^2 + u^2, free end";
  p.parameters = Lqr::ParameterSpecs();
  p.make = [](const Parameters&, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<Lqr>();
  };
  p.default_intervals = 100;
  p.reference_value = Lqr::kReferenceCost;
  p.reference_source =
      "1/2 x0' P(0) x0 from the Riccati ODE at rtol 1e-13 (problem: CTProblems.jl lqr_ricatti)";
  return p;
}

}  // namespace ocpb
