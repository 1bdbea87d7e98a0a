// The planar moon lander of OptimalControlProblems.jl ("moonlander", after the FATROP example):
// OCPBench problem "moonlander".
#pragma once

#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    T  (free final time, 0.1 <= T <= 1)
/// subject to  p1' = dp1,  p2' = dp2,  theta' = dtheta,
///             dp1' = -sin(theta) (F1 + F2) / m,  dp2' = cos(theta) (F1 + F2) / m - g,
///             dtheta' = (D / 2) (F2 - F1) / I,
///             with m = 1, g = 9.81, I = 0.1, D = 1, 0 <= F1, F2 <= 2 g;
///             all six states 0 at t = 0, (p1, p2, dp1, dp2)(T) = (5, 5, 0, 0)
/// (OptimalControlProblems.jl's JuMP model `moonlander`; Vanroye et al. 2023). The cost is the
/// running cost L = 1 over the free horizon. The thrusts are bang-bang.
class Moonlander final : public AutoDiffOcp<Moonlander, 6, 2, 4, 0> {
 public:
  static constexpr double kMass = 1.0;
  static constexpr double kGravity = 9.81;
  static constexpr double kInertia = 0.1;
  static constexpr double kArm = 1.0;  // D
  static constexpr double kTarget = 5.0;
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit Moonlander(const Parameters& params);

  std::string name() const override { return "moonlander"; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 6>& x, const VecT<T, 2>& u, VecT<T, 6>* f) const {
    const T thrust = u[0] + u[1];
    (*f)[0] = x[2];
    (*f)[1] = x[3];
    (*f)[2] = -sin(x[4]) * thrust / kMass;
    (*f)[3] = cos(x[4]) * thrust / kMass - kGravity;
    (*f)[4] = x[5];
    (*f)[5] = (kArm / 2.0) * (u[1] - u[0]) / kInertia;
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 6>&, const VecT<T, 2>&) const {
    return T(1.0);
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 6>& x, VecT<T, 4>* psi) const {
    (*psi)[0] = x[0] - kTarget;
    (*psi)[1] = x[1] - kTarget;
    (*psi)[2] = x[2];
    (*psi)[3] = x[3];
  }
  /// F1 = F2 = 5, the source's start.
  Vec NominalControl() const override { return Vec::Constant(2, 5.0); }
};

/// The registry entry "moonlander".
ProblemInfo MoonlanderProblemInfo();

}  // namespace ocpb
