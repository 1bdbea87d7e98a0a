// The truck with two trailers of OptimalControlProblems.jl ("truck_trailer", after the FATROP
// example): OCPBench problem "truck-trailer".
#pragma once

#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    T + int_0^T (b01^2 + b12^2) dt,  b01 = theta0 - theta1, b12 = theta1 - theta2,
/// over the state (x2, y2, theta0, theta1, theta2, v0, delta0), the controls (dv0, ddelta0) and
/// the free final time 1 <= T <= 1000:
///   theta0' = v0 / L0 tan(delta0),
///   theta1' = v0 / L1 sin(b01) - M0 / L1 cos(b01) theta0',
///   v1 = v0 cos(b01) + M0 sin(b01) theta0',
///   theta2' = v1 / L2 sin(b12) - M1 / L2 cos(b12) theta1',
///   v2 = v1 cos(b12) + M1 sin(b12) theta1',
///   x2' = v2 cos(theta2),  y2' = v2 sin(theta2),  v0' = dv0,  delta0' = ddelta0,
/// with (L0, M0) = (0.4, 0.1), (L1, M1) = (1.1, 0.2), L2 = 0.8;
/// |theta0|, |theta1| <= pi/2, |v0| <= 0.2, |delta0| <= pi/6 (state bounds), |dv0| <= 1,
/// |ddelta0| <= pi/10, |b01|, |b12| <= pi/2 (path constraints);
/// x2 = y2 = theta0 = theta1 = theta2 = 0 at t = 0 (v0 and delta0 free there);
/// x2(T) = 0, y2(T) = -2, theta2(T) = pi/2, b01(T) = b12(T) = 0
/// (OptimalControlProblems.jl's JuMP model `truck_trailer`; Vanroye et al. 2023). The source's
/// cost is T plus the trapezoid sum of b01^2 + b12^2, which is OCPBench's L = 1 + b01^2 + b12^2.
class TruckTrailer final : public AutoDiffOcp<TruckTrailer, 7, 2, 5, 4> {
 public:
  static constexpr double kL0 = 0.4, kM0 = 0.1;
  static constexpr double kL1 = 1.1, kM1 = 0.2;
  static constexpr double kL2 = 0.8;
  static constexpr double kPi = 3.14159265358979323846;
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit TruckTrailer(const Parameters& params);

  std::string name() const override { return "truck-trailer"; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 7>& x, const VecT<T, 2>& u, VecT<T, 7>* f) const {
    const T b01 = x[2] - x[3];
    const T b12 = x[3] - x[4];
    const T& v0 = x[5];
    const T dth0 = v0 / kL0 * tan(x[6]);
    const T dth1 = v0 / kL1 * sin(b01) - kM0 / kL1 * cos(b01) * dth0;
    const T v1 = v0 * cos(b01) + kM0 * sin(b01) * dth0;
    const T dth2 = v1 / kL2 * sin(b12) - kM1 / kL2 * cos(b12) * dth1;
    const T v2 = v1 * cos(b12) + kM1 * sin(b12) * dth1;
    (*f)[0] = v2 * cos(x[4]);
    (*f)[1] = v2 * sin(x[4]);
    (*f)[2] = dth0;
    (*f)[3] = dth1;
    (*f)[4] = dth2;
    (*f)[5] = u[0];
    (*f)[6] = u[1];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 7>& x, const VecT<T, 2>&) const {
    const T b01 = x[2] - x[3];
    const T b12 = x[3] - x[4];
    return 1.0 + b01 * b01 + b12 * b12;
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 7>& x, VecT<T, 5>* psi) const {
    (*psi)[0] = x[0];
    (*psi)[1] = x[1] + 2.0;
    (*psi)[2] = x[4] - 0.5 * kPi;
    (*psi)[3] = x[2] - x[3];
    (*psi)[4] = x[3] - x[4];
  }
  /// |b01| <= pi/2 and |b12| <= pi/2 as four rows c <= 0.
  template <class T>
  void EvalPathConstraints(double, const VecT<T, 7>& x, const VecT<T, 2>&, VecT<T, 4>* c) const {
    const T b01 = x[2] - x[3];
    const T b12 = x[3] - x[4];
    (*c)[0] = b01 - 0.5 * kPi;
    (*c)[1] = -b01 - 0.5 * kPi;
    (*c)[2] = b12 - 0.5 * kPi;
    (*c)[3] = -b12 - 0.5 * kPi;
  }
  /// dv0 = ddelta0 = 0.1, the source's start.
  Vec NominalControl() const override { return Vec::Constant(2, 0.1); }
};

/// The registry entry "truck-trailer".
ProblemInfo TruckTrailerProblemInfo();

}  // namespace ocpb
