// The Jackson catalyst problem of BOCOP / OptimalControlProblems.jl (OCPBench problem
// "jackson").
#pragma once

#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    J = -x3(4)                                  (Mayer: maximize the product)
/// subject to  a' = -u (k1 a - k2 b),
///             b' = u (k1 a - k2 b) - (1 - u) k3 b,
///             x3' = (1 - u) k3 b,
///             (a, b, x3)(0) = (1, 0, 0),  0 <= u <= 1,
///             0 <= a, b, x3 <= 1.1 on (0, 4]   (state bounds, as in the JuMP model),
/// with k1 = 1, k2 = 10, k3 = 1, tf = 4.
///
/// The problem "jackson" of OptimalControlProblems.jl (control-toolbox; JuMP model
/// ext/JuMPModels/jackson.jl, parameters ext/MetaData/jackson.jl), after the BOCOP example and
/// R. Jackson, "Optimal use of mixed catalysts for two successive chemical reactions", J. Optim.
/// Theory Appl. 2(1), 1968: reactions A <-> B -> C on a catalyst mix u. The optimal u is
/// bang-singular-bang (like "catmix"). The state bounds are inactive at the optimum.
class JacksonOcp final : public AutoDiffOcp<JacksonOcp, 3, 1> {
 public:
  static constexpr double kK1 = 1.0;
  static constexpr double kK2 = 10.0;
  static constexpr double kK3 = 1.0;
  static constexpr double kFinalTime = 4.0;
  static constexpr double kStateUpper = 1.1;
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit JacksonOcp(const Parameters& params);

  std::string name() const override { return "jackson"; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 3>& x, const VecT<T, 1>& u, VecT<T, 3>* f) const {
    const T r = kK1 * x[0] - kK2 * x[1];
    (*f)[0] = -u[0] * r;
    (*f)[1] = u[0] * r - (1.0 - u[0]) * kK3 * x[1];
    (*f)[2] = (1.0 - u[0]) * kK3 * x[1];
  }
  template <class T>
  T EvalTerminalCost(const VecT<T, 3>& x) const {
    return -x[2];
  }
  /// The JuMP model's start u = 0.1.
  Vec NominalControl() const override { return Vec::Constant(1, 0.1); }
};

/// The registry entry "jackson".
ProblemInfo JacksonProblemInfo();

}  // namespace ocpb
