// The mechanical double oscillator of Coudurier, Lepreux & Petit via OptimalControlProblems.jl
// (OCPBench problem "double-oscillator").
#pragma once

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    J = 1/2 int_0^{2 pi} (x1^2 + x2^2 + u^2) dt
/// subject to  x1' = x3,  x2' = x4,
///             x3' = -(k1 + k2)/m1 x1 + k2/m1 x2 + F(t)/m1,   F(t) = sin(2 pi t / tf),
///             x4' = k2/m2 x1 - k2/m2 x2 - c (1 - u)/m2 x4,
///             x1(0) = x2(0) = 0,  x3(0), x4(0) free,  -1 <= u <= 1,  tf = 2 pi,
/// with m1 = 100, m2 = 2, c = 0.5, k1 = 100, k2 = 3.
///
/// The problem "double_oscillator" of OptimalControlProblems.jl (control-toolbox; JuMP model
/// ext/JuMPModels/double_oscillator.jl, parameters ext/MetaData/double_oscillator.jl), after
/// C. Coudurier, O. Lepreux, N. Petit, "Optimal bang-bang control of a mechanical double
/// oscillator using averaging methods", IFAC-PapersOnLine 51(2), 2018: a primary mass m1 forced
/// by F and a secondary mass m2 whose damping c (1 - u) the control modulates. The initial
/// velocities are decisions (the JuMP model fixes only the positions), so the problem has a
/// partly free initial state. The dynamics depend on t through F.
class DoubleOscillatorOcp final : public AutoDiffOcp<DoubleOscillatorOcp, 4, 1> {
 public:
  static constexpr double kM1 = 100.0;
  static constexpr double kM2 = 2.0;
  static constexpr double kDamping = 0.5;
  static constexpr double kK1 = 100.0;
  static constexpr double kK2 = 3.0;
  static constexpr double kFinalTime = 2.0 * std::numbers::pi;
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit DoubleOscillatorOcp(const Parameters& params);

  std::string name() const override { return "double-oscillator"; }

  template <class T>
  void EvalDynamics(double t, const VecT<T, 4>& x, const VecT<T, 1>& u, VecT<T, 4>* f) const {
    const double force = std::sin(2.0 * std::numbers::pi * t / kFinalTime);
    (*f)[0] = x[2];
    (*f)[1] = x[3];
    (*f)[2] = -(kK1 + kK2) / kM1 * x[0] + kK2 / kM1 * x[1] + force / kM1;
    (*f)[3] = kK2 / kM2 * x[0] - kK2 / kM2 * x[1] - kDamping * (1.0 - u[0]) / kM2 * x[3];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 4>& x, const VecT<T, 1>& u) const {
    return 0.5 * (x[0] * x[0] + x[1] * x[1] + u[0] * u[0]);
  }
};

/// The registry entry "double-oscillator".
ProblemInfo DoubleOscillatorProblemInfo();

}  // namespace ocpb
