// The quadrotor point-to-point flight of OptimalControlProblems.jl ("quadrotor", after the FATROP
// example): OCPBench problem "quadrotor".
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    T + int_0^T dc dt,  dc = 1e-8 (at^2 + phi^2 + theta^2 + psi^2) + 1e2 psi^2
/// over the state (p1, p2, p3, v1, v2, v3, phi, theta), the controls (at, dphi, dtheta, psi) and
/// the free final time T >= 0.1:
///   p' = v,  v' = at R(phi, theta, psi) e3 - g e3,  phi' = dphi,  theta' = dtheta,
///   R e3 = (cos psi sin theta cos phi + sin psi sin phi,
///           sin psi sin theta cos phi - cos psi sin phi,  cos theta cos phi),
///   0 <= at <= 9.18 * 5,  |dphi|, |dtheta| <= 3,  psi free,
///   |phi|, |theta| <= pi / 2 (state bounds),  cos(theta) cos(phi) >= cos(0.55) (path),
///   p(0) = (0, 0, 2.5), v(0) = 0, phi(0) = theta(0) = 0,  p(T) = (0.01, 5, 2.5), v(T) = 0,
/// with g = 9.81 (OptimalControlProblems.jl's JuMP model `quadrotor`; Vanroye et al. 2023). The
/// source's cost is T plus the trapezoid sum of dc, which is OCPBench's L = 1 + dc.
class Quadrotor final : public AutoDiffOcp<Quadrotor, 8, 4, 6, 1> {
 public:
  static constexpr double kGravity = 9.81;
  static constexpr double kThrustMax = 9.18 * 5.0;
  static constexpr double kTiltMax = 1.1 / 2.0;
  static constexpr double kTiltRateMax = 6.0 / 2.0;
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit Quadrotor(const Parameters& params);

  std::string name() const override { return "quadrotor"; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 8>& x, const VecT<T, 4>& u, VecT<T, 8>* f) const {
    const T cr = cos(x[6]), sr = sin(x[6]);
    const T cp = cos(x[7]), sp = sin(x[7]);
    const T cy = cos(u[3]), sy = sin(u[3]);
    (*f)[0] = x[3];
    (*f)[1] = x[4];
    (*f)[2] = x[5];
    (*f)[3] = u[0] * (cy * sp * cr + sy * sr);
    (*f)[4] = u[0] * (sy * sp * cr - cy * sr);
    (*f)[5] = u[0] * (cp * cr) - kGravity;
    (*f)[6] = u[1];
    (*f)[7] = u[2];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 8>& x, const VecT<T, 4>& u) const {
    return 1.0 + 1e-8 * (u[0] * u[0] + x[6] * x[6] + x[7] * x[7] + u[3] * u[3]) + 1e2 * u[3] * u[3];
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 8>& x, VecT<T, 6>* psi) const {
    (*psi)[0] = x[0] - 0.01;
    (*psi)[1] = x[1] - 5.0;
    (*psi)[2] = x[2] - 2.5;
    (*psi)[3] = x[3];
    (*psi)[4] = x[4];
    (*psi)[5] = x[5];
  }
  /// cos(theta) cos(phi) >= cos(tilt_max).
  template <class T>
  void EvalPathConstraints(double, const VecT<T, 8>& x, const VecT<T, 4>&, VecT<T, 1>* c) const {
    (*c)[0] = std::cos(kTiltMax) - cos(x[7]) * cos(x[6]);
  }
  /// (at, dphi, dtheta, psi) = (10, 0.1, 0.1, 0.1), the source's start.
  Vec NominalControl() const override {
    Vec u(4);
    u << 10.0, 0.1, 0.1, 0.1;
    return u;
  }
};

/// The registry entry "quadrotor".
ProblemInfo QuadrotorProblemInfo();

}  // namespace ocpb
