// The mountain car of OptimalControlProblems.jl ("mountain_car"): OCPBench problem
// "mountain-car".
#pragma once

#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    T  (free final time)
/// subject to  pos' = vel,  vel' = a u - b cos(c pos),  a = 0.001, b = 0.0025, c = 3,
///             (pos, vel)(0) = (-0.5, 0),  pos(T) = 0.5 (psi),  vel(T) >= 0 (boundary
///             constraint), -1.2 <= pos <= 0.5, -0.07 <= vel <= 0.07 (state bounds),
///             -1 <= u <= 1,  T >= 0.1,
/// as in OptimalControlProblems.jl's JuMP model `mountain_car` (the Dymos example after Moore
/// 1990). The cost is the running cost L = 1 over the free horizon, so every quadrature gives
/// T exactly. The optimal control is bang-bang (the car rocks back once before climbing).
/// Hamiltonian method: not applicable (free final time with state bounds and a boundary
/// constraint; no pointwise minimizer is offered).
class MountainCar final : public AutoDiffOcp<MountainCar, 2, 1, 1, 0> {
 public:
  static constexpr double kPower = 0.001;     // a
  static constexpr double kGravity = 0.0025;  // b
  static constexpr double kFrequency = 3.0;   // c
  static constexpr double kTargetPosition = 0.5;
  /// The JuMP model's trapezoid optimum at N = 200 (OptimalControlProblems.jl docs, Ipopt).
  static constexpr double kTrapezoid200 = 102.39757015622749;
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit MountainCar(const Parameters& params);

  std::string name() const override { return "mountain-car"; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 2>& x, const VecT<T, 1>& u, VecT<T, 2>* f) const {
    (*f)[0] = x[1];
    (*f)[1] = kPower * u[0] - kGravity * cos(kFrequency * x[0]);
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 2>&, const VecT<T, 1>&) const {
    return T(1.0);
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 2>& x, VecT<T, 1>* psi) const {
    (*psi)[0] = x[0] - kTargetPosition;
  }
  /// b = vel(T) in [0, inf).
  template <class T>
  void EvalBoundaryConstraints(const VecT<T, 2>&,
                               const VecT<T, 2>& xf,
                               VecT<T, Eigen::Dynamic>* b) const {
    (*b)[0] = xf[1];
  }
};

/// The registry entry "mountain-car".
ProblemInfo MountainCarProblemInfo();

}  // namespace ocpb
