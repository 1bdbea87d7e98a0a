// The electric vehicle of Petit & Sciarretta via OptimalControlProblems.jl (OCPBench problem
// "electric-vehicle").
#pragma once

#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    J = int_0^1 (b1 u v + b2 u^2) dt,  b1 = b2 = 1,
/// subject to  x' = v,  v' = h1 u - h2 v^2 - h0 - road(x),
///             road(x) = a0 + a1 x + a2 x^2 + a3 x^3,
///             (x, v)(0) = (0, 0),  psi = (x(1) - 10, v(1)) = 0,  u unbounded,
/// with h0 = 0.1, h1 = 1, h2 = 1e-3, (a0, a1, a2, a3) = (3, 0.4, -1, 0.1).
///
/// The problem "electric_vehicle" of OptimalControlProblems.jl (control-toolbox; JuMP model
/// ext/JuMPModels/electric_vehicle.jl, parameters ext/MetaData/electric_vehicle.jl), after
/// N. Petit and A. Sciarretta, "Optimal drive of electric vehicles using an inversion-based
/// trajectory generation approach", IFAC Proc. Vol. 44(1), 2011: a car covers 10 length units
/// in unit time on a road with a cubic slope profile, at least electric energy (b1 u v) plus
/// resistive losses (b2 u^2).
class ElectricVehicleOcp final : public AutoDiffOcp<ElectricVehicleOcp, 2, 1, 2, 0> {
 public:
  static constexpr double kB1 = 1.0;
  static constexpr double kB2 = 1.0;
  static constexpr double kH0 = 0.1;
  static constexpr double kH1 = 1.0;
  static constexpr double kH2 = 1e-3;
  static constexpr double kA0 = 3.0;
  static constexpr double kA1 = 0.4;
  static constexpr double kA2 = -1.0;
  static constexpr double kA3 = 0.1;
  static constexpr double kDistance = 10.0;
  /// Parameters: C (terminal penalty weight, default 1e4).
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit ElectricVehicleOcp(const Parameters& params);

  std::string name() const override { return "electric-vehicle"; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 2>& x, const VecT<T, 1>& u, VecT<T, 2>* f) const {
    const T road = kA0 + kA1 * x[0] + kA2 * x[0] * x[0] + kA3 * x[0] * x[0] * x[0];
    (*f)[0] = x[1];
    (*f)[1] = kH1 * u[0] - kH2 * x[1] * x[1] - kH0 - road;
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 2>& x, const VecT<T, 1>& u) const {
    return kB1 * u[0] * x[1] + kB2 * u[0] * u[0];
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 2>& x, VecT<T, 2>* psi) const {
    (*psi)[0] = x[0] - kDistance;
    (*psi)[1] = x[1];
  }
};

/// The registry entry "electric-vehicle".
ProblemInfo ElectricVehicleProblemInfo();

}  // namespace ocpb
