// The brachistochrone with an explicitly free final time (OCPBench problem
// "brachistochrone-free-time").
#pragma once

#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    J = int_0^T 1 dt = T                 over w and the final time T (free),
/// subject to  x' = v w1,  y' = v w2,  v' = g w2    (y points down, g = 9.8),
///             (x, y, v)(0) = 0,  psi = (x(T) - 2, y(T) - 2) = 0,  v(T) free,  |w| <= 1,
///
/// the problem "brachistochrone" (problems/reference/brachistochrone.h) on the physical time axis:
/// w = (sin th, cos th) relaxed to the unit disc (H is linear in w, so its minimizer lies on the
/// circle wherever the switching vector s = (p_x v, p_y v + p_v g) is nonzero), and T a decision
/// variable in [tf_min, tf_max] instead of a time dilation. Reference T* = 0.824759143157 (the
/// cycloid; see brachistochrone.h). Along the optimum H = 1 - |s| = 0.
///
/// Minimizer: w* = -s / |s| (w* = 0 where s = 0, where u* is not differentiable); the ball's
/// multiplier |s| makes its derivative exist (MinimizerDerivative). Autonomous, as Ocp's free
/// final time requires. Parameters: C (penalty weight on |psi|^2, 1e3), tf (nominal T, where
/// methods start, 1), tf_min (0.1), tf_max (10). Start (NominalControl): w = (1, 1)/sqrt(2),
/// straight at the target.
class FreeTimeBrachistochrone final : public AutoDiffOcp<FreeTimeBrachistochrone, 3, 2, 2, 0> {
 public:
  static constexpr double kGravity = 9.8;
  static constexpr double kReferenceTime = 0.824759143157;
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit FreeTimeBrachistochrone(const Parameters& params);

  std::string name() const override { return "brachistochrone-free-time"; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 3>& x, const VecT<T, 2>& u, VecT<T, 3>* f) const {
    (*f)[0] = x[2] * u[0];
    (*f)[1] = x[2] * u[1];
    (*f)[2] = kGravity * u[1];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 3>&, const VecT<T, 2>&) const {
    return T(1.0);
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 3>& x, VecT<T, 2>* psi) const {
    (*psi)[0] = x[0] - 2.0;
    (*psi)[1] = x[1] - 2.0;
  }

  bool HasHamiltonianMinimizer() const override { return true; }
  void MinimizeHamiltonian(double t, ConstVecRef x, ConstVecRef p, VecRef u) const override;
  Vec NominalControl() const override;
};

/// The registry entry "brachistochrone-free-time".
ProblemInfo FreeTimeBrachistochroneProblemInfo();

}  // namespace ocpb
