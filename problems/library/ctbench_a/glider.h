// The hang glider of COPS 3.0 as posed by OptimalControlProblems.jl ("glider"): OCPBench problem
// "glider".
#pragma once

#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// maximize    x(T)  (J = -x(T), T free)
/// subject to  x' = vx,  y' = vy,
///             vx' = -(L w + D vx) / (m v),  vy' = (L vx - D w) / (m v) - g,
///             with the thermal updraft ua(x) = uc (1 - r) exp(-r), r = (x / r0 - 2.5)^2,
///             w = vy - ua, v = sqrt(vx^2 + w^2), D = rho S (c0 + c1 cL^2) v^2 / 2,
///             L = rho S cL v^2 / 2,
///             (x, y, vx, vy)(0) = (0, 1000, 13.23, -1.288),
///             (y, vx, vy)(T) = (900, 13.23, -1.288)  (psi),
///             x >= 0, vx >= 0 (state bounds), 0 <= cL <= 1.4,
/// with uc = 2.5, r0 = 100, m = 100, g = 9.81, c0 = 0.034, c1 = 0.069662, S = 14, rho = 1.13
/// (COPS 3.0 problem `glider`, Dolan, More, Munson 2004; OptimalControlProblems.jl's JuMP model
/// `glider`). A Mayer problem with a free final time.
class Glider final : public AutoDiffOcp<Glider, 4, 1, 3, 0> {
 public:
  static constexpr double kUpdraftMax = 2.5;       // uc
  static constexpr double kUpdraftRadius = 100.0;  // r0
  static constexpr double kMass = 100.0;
  static constexpr double kGravity = 9.81;
  static constexpr double kDrag0 = 0.034;      // c0
  static constexpr double kDrag1 = 0.069662;   // c1
  static constexpr double kWingArea = 14.0;    // S
  static constexpr double kAirDensity = 1.13;  // rho
  static constexpr double kLiftMax = 1.4;      // cL_max
  static constexpr double kFinalHeight = 900.0;
  static constexpr double kSpeedX = 13.23;
  static constexpr double kSpeedY = -1.288;
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit Glider(const Parameters& params);

  std::string name() const override { return "glider"; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 4>& x, const VecT<T, 1>& u, VecT<T, 4>* f) const {
    const T s = x[0] / kUpdraftRadius - 2.5;
    const T r = s * s;
    const T updraft = kUpdraftMax * (1.0 - r) * exp(-r);
    const T w = x[3] - updraft;
    const T v2 = x[2] * x[2] + w * w;
    const T v = sqrt(v2);
    const T drag = 0.5 * (kDrag0 + kDrag1 * u[0] * u[0]) * kAirDensity * kWingArea * v2;
    const T lift = 0.5 * u[0] * kAirDensity * kWingArea * v2;
    (*f)[0] = x[2];
    (*f)[1] = x[3];
    (*f)[2] = -(lift * w + drag * x[2]) / (kMass * v);
    (*f)[3] = (lift * x[2] - drag * w) / (kMass * v) - kGravity;
  }
  template <class T>
  T EvalTerminalCost(const VecT<T, 4>& x) const {
    return -x[0];
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 4>& x, VecT<T, 3>* psi) const {
    (*psi)[0] = x[1] - kFinalHeight;
    (*psi)[1] = x[2] - kSpeedX;
    (*psi)[2] = x[3] - kSpeedY;
  }
  /// cL = cL_max / 2, OptimalControlProblems.jl's start.
  Vec NominalControl() const override { return Vec::Constant(1, 0.5 * kLiftMax); }
};

/// The registry entry "glider".
ProblemInfo GliderProblemInfo();

}  // namespace ocpb
