// The clamped beam of BOCOP / OptimalControlProblems.jl (OCPBench problem "beam").
#pragma once

#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    J = int_0^1 u^2 dt                       (no factor 1/2)
/// subject to  x1' = x2,  x2' = u,  x(0) = (0, 1),  psi = (x1(1), x2(1) + 1) = 0,
///             0 <= x1(t) <= a on (0, 1]  (state bounds, a = 0.1),  u unbounded.
///
/// The problem "beam" of OptimalControlProblems.jl (control-toolbox; JuMP model
/// ext/JuMPModels/beam.jl, parameters ext/MetaData/beam.jl: t0 = 0, tf = 1, x1 in [0, 0.1],
/// x(0) = (0, 1), x(1) = (0, -1)), after the BOCOP clamped-beam example. It is the
/// Bryson-Denham problem ("bryson-denham") with the bound a = 0.1 instead of 1/9, the cost
/// doubled and the (inactive) lower bound x1 >= 0 added. Earlier versions of the JuMP model
/// bounded u to [-10, 5] (or [-10, 10]); the optimal u lies in [-2/(3a), 0] = [-6.67, 0], so
/// those bounds are inactive and are left out, as in the current model.
///
/// Reference (a <= 1/6): J* = 2 * 4/(9a) = 8/(9a) = 80/9 (Bryson, Denham, Dreyfus 1963; Bryson &
/// Ho 1975, Sec. 3.11), with a boundary arc x1 = a on [3a, 1 - 3a].
class BeamOcp final : public AutoDiffOcp<BeamOcp, 2, 1, 2, 0> {
 public:
  static constexpr double kDeflectionBound = 0.1;  // a
  static constexpr double kOptimalCost = 8.0 / (9.0 * kDeflectionBound);
  /// Parameters: C (terminal penalty weight, default 1e4).
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit BeamOcp(const Parameters& params);

  std::string name() const override { return "beam"; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 2>& x, const VecT<T, 1>& u, VecT<T, 2>* f) const {
    (*f)[0] = x[1];
    (*f)[1] = u[0];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 2>&, const VecT<T, 1>& u) const {
    return u[0] * u[0];
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 2>& x, VecT<T, 2>* psi) const {
    (*psi)[0] = x[0];
    (*psi)[1] = x[1] + 1.0;
  }
};

/// The registry entry "beam".
ProblemInfo BeamProblemInfo();

}  // namespace ocpb
