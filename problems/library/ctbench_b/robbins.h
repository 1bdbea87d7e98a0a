// The Robbins problem of BOCOP / OptimalControlProblems.jl (OCPBench problem "robbins").
#pragma once

#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    J = int_0^10 (alpha x1 + beta x1^2 + gamma u^2) dt,  alpha = 3, beta = 0,
///             gamma = 1/2,
/// subject to  x1' = x2,  x2' = x3,  x3' = u,  x(0) = (1, -2, 0),  psi = x(10) = 0,
///             x1(t) >= 0 on (0, 10]  (state bound),  u unbounded.
///
/// The problem "robbins" of OptimalControlProblems.jl (control-toolbox; JuMP model
/// ext/JuMPModels/robbins.jl, parameters ext/MetaData/robbins.jl), after the BOCOP example and
/// H. M. Robbins, "Junction phenomena for optimal control with state-variable inequality
/// constraints of third order", J. Optim. Theory Appl. 31(1), 1980: a third-order state
/// constraint whose optimal trajectory touches x1 = 0 at infinitely many points accumulating at
/// the entry of a boundary arc (no closed-form optimum).
class RobbinsOcp final : public AutoDiffOcp<RobbinsOcp, 3, 1, 3, 0> {
 public:
  static constexpr double kAlpha = 3.0;
  static constexpr double kBeta = 0.0;
  static constexpr double kGamma = 0.5;
  static constexpr double kFinalTime = 10.0;
  /// Parameters: C (terminal penalty weight, default 1e4).
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit RobbinsOcp(const Parameters& params);

  std::string name() const override { return "robbins"; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 3>& x, const VecT<T, 1>& u, VecT<T, 3>* f) const {
    (*f)[0] = x[1];
    (*f)[1] = x[2];
    (*f)[2] = u[0];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 3>& x, const VecT<T, 1>& u) const {
    return kAlpha * x[0] + kBeta * x[0] * x[0] + kGamma * u[0] * u[0];
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 3>& x, VecT<T, 3>* psi) const {
    (*psi)[0] = x[0];
    (*psi)[1] = x[1];
    (*psi)[2] = x[2];
  }
};

/// The registry entry "robbins".
ProblemInfo RobbinsProblemInfo();

}  // namespace ocpb
