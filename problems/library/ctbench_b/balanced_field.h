// The climb segment of the Dymos balanced-field-length problem, single phase, as posed by
// OptimalControlProblems.jl (OCPBench problem "balanced-field").
#pragma once

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    J = r(tf)                                   (Mayer, tf free in [0.1, 100])
/// subject to  r' = v cos g,  v' = (T cos a - D)/m - g0 sin g,  h' = v sin g,
///             g' = (T sin a + L)/(m v) - g0 cos g / v,
///             q = rho v^2 / 2,  CL = CL0 + (a / a_max) (CL_max - CL0),  L = q S CL,
///             D = q S (CD0 + K CL^2),  K = K_nom k / (1 + k),  k = 33 ((h + h_w) / b)^1.5,
///             K_nom = 1 / (pi AR e),  b = span / 2,
///             (r, v, h, g)(0) = (600, 70, 0, 0),  psi = (h(tf) - 10.668, g(tf) - 0.0873) = 0,
///             0 <= a <= 0.2618,  v >= 1, h >= 0 (state bounds),
/// with m = 79015.8, g0 = 9.80665, rho = 1.225, S = 124.7, CD0 = 0.03, AR = 9.45, e = 0.801,
/// CL0 = 0.5, CL_max = 2, h_w = 1, span = 35.7, a_max = 0.1745, T = 120102 (SI units).
///
/// The problem "balanced_field" of OptimalControlProblems.jl (control-toolbox; JuMP model
/// ext/JuMPModels/balanced_field.jl, parameters ext/MetaData/balanced_field.jl): the
/// one-engine-out climb from V1 to the 35 ft screen height of the Dymos "Aircraft Balanced Field
/// Length Calculation" example, taken alone (Dymos' full problem has five phases; this is the
/// single phase the Julia suite publishes). The angle of attack a is the control; the ground
/// effect reduces the induced drag near the runway. tf is native free final time (the JuMP
/// model's uniform step (tf - t0)/N, which OCPBench's free-time transcriptions share).
class BalancedFieldOcp final : public AutoDiffOcp<BalancedFieldOcp, 4, 1, 2, 0> {
 public:
  static constexpr double kMass = 79015.8;
  static constexpr double kGravity = 9.80665;
  static constexpr double kRho = 1.225;
  static constexpr double kSurface = 124.7;
  static constexpr double kCD0 = 0.03;
  static constexpr double kAspectRatio = 9.45;
  static constexpr double kOswald = 0.801;
  static constexpr double kCL0 = 0.5;
  static constexpr double kCLMax = 2.0;
  static constexpr double kWingHeight = 1.0;
  static constexpr double kSpan = 35.7;
  static constexpr double kAlphaAtCLMax = 0.1745;
  static constexpr double kThrust = 120102.0;
  static constexpr double kScreenHeight = 10.668;
  static constexpr double kFinalGamma = 0.0873;
  static constexpr double kAlphaUpper = 0.2618;
  /// Parameters: C (terminal penalty weight, default 1e4), tf (nominal final time, 10).
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit BalancedFieldOcp(const Parameters& params);

  std::string name() const override { return "balanced-field"; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 4>& x, const VecT<T, 1>& u, VecT<T, 4>* f) const {
    const T& v = x[1];
    const T& h = x[2];
    const T& gam = x[3];
    const T& alpha = u[0];
    const double k_nom = 1.0 / (std::numbers::pi * kAspectRatio * kOswald);
    const T q = 0.5 * kRho * v * v;
    const T cl = kCL0 + (alpha / kAlphaAtCLMax) * (kCLMax - kCL0);
    const T lift = q * kSurface * cl;
    const T ground = 33.0 * pow((h + kWingHeight) / (0.5 * kSpan), 1.5);
    const T k = k_nom * ground / (1.0 + ground);
    const T drag = q * kSurface * (kCD0 + k * cl * cl);
    (*f)[0] = v * cos(gam);
    (*f)[1] = (kThrust * cos(alpha) - drag) / kMass - kGravity * sin(gam);
    (*f)[2] = v * sin(gam);
    (*f)[3] = (kThrust * sin(alpha) + lift) / (kMass * v) - kGravity * cos(gam) / v;
  }
  template <class T>
  T EvalTerminalCost(const VecT<T, 4>& x) const {
    return x[0];
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 4>& x, VecT<T, 2>* psi) const {
    (*psi)[0] = x[2] - kScreenHeight;
    (*psi)[1] = x[3] - kFinalGamma;
  }
  /// The JuMP model's start a = 0.1.
  Vec NominalControl() const override { return Vec::Constant(1, 0.1); }
};

/// The registry entry "balanced-field".
ProblemInfo BalancedFieldProblemInfo();

}  // namespace ocpb
