// The dielectrophoretic particle of Chang, Petit and Rouchon as posed by OptimalControlProblems.jl
// ("dielectrophoretic_particle"): OCPBench problem "dielectrophoretic-particle".
#pragma once

#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    T  (free final time)
/// subject to  x' = y u + alpha u^2,  y' = -c y + u,  alpha = -0.75, c = 1,
///             x(0) = 1, y(0) = 0, x(T) = 2,  -1 <= u <= 1
/// (Chang, Petit, Rouchon 2006; OptimalControlProblems.jl's JuMP model
/// `dielectrophoretic_particle`). The cost is L = 1 over the free horizon. The time-optimal
/// control saturates at the bounds with a singular arc in between.
class DielectrophoreticParticle final : public AutoDiffOcp<DielectrophoreticParticle, 2, 1, 1, 0> {
 public:
  static constexpr double kAlpha = -0.75;
  static constexpr double kDamping = 1.0;  // c
  static constexpr double kStart = 1.0;
  static constexpr double kTarget = 2.0;
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit DielectrophoreticParticle(const Parameters& params);

  std::string name() const override { return "dielectrophoretic-particle"; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 2>& x, const VecT<T, 1>& u, VecT<T, 2>* f) const {
    (*f)[0] = x[1] * u[0] + kAlpha * u[0] * u[0];
    (*f)[1] = -kDamping * x[1] + u[0];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 2>&, const VecT<T, 1>&) const {
    return T(1.0);
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 2>& x, VecT<T, 1>* psi) const {
    (*psi)[0] = x[0] - kTarget;
  }
  /// u = 0.1, the source's start.
  Vec NominalControl() const override { return Vec::Constant(1, 0.1); }
};

/// The registry entry "dielectrophoretic-particle".
ProblemInfo DielectrophoreticParticleProblemInfo();

}  // namespace ocpb
