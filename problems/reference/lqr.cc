#include "problems/reference/lqr.h"

#include <unsupported/Eigen/MatrixFunctions>

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

Eigen::Matrix4d Lqr::HamiltonianMatrix() {
  Eigen::Matrix4d m;
  m.topLeftCorner<2, 2>() = A();
  m.topRightCorner<2, 2>() = -B() * B().transpose();
  m.bottomLeftCorner<2, 2>() = -Eigen::Matrix2d::Identity();
  m.bottomRightCorner<2, 2>() = -A().transpose();
  return m;
}

Eigen::Vector4d Lqr::OptimalStateAndCostate(double t) {
  // z(0) = (x0, p0) with p0 chosen so that p(5) = [Phi21 Phi22] z(0) = 0, Phi = exp(5 M):
  // p0 = -Phi22^{-1} Phi21 x0 (Phi22 is invertible: the Riccati solution exists on [0, 5]).
  static const Eigen::Vector4d z0 = [] {
    const Eigen::Matrix4d phi = (5.0 * HamiltonianMatrix()).exp();
    const Eigen::Vector2d x0(0.0, 1.0);
    const Eigen::Vector2d p0 =
        -phi.bottomRightCorner<2, 2>().partialPivLu().solve(phi.bottomLeftCorner<2, 2>() * x0);
    Eigen::Vector4d z;
    z << x0, p0;
    return z;
  }();
  return (t * HamiltonianMatrix()).exp() * z0;
}

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
  p.reference_costate = [](double t) -> Vec { return Lqr::OptimalCostate(t); };
  p.tags = {"smooth"};
  return p;
}

}  // namespace ocpb
