// Linear tangent steering (COPS "steering") as a minimum-time problem (OCPBench problem
// "steering").
#pragma once

#include <string>
#include <vector>

#include "problems/reference/scaled_min_time.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    tf
/// subject to  x1' = x3,  x2' = x4,  x3' = a cos th,  x4' = a sin th    (a = 100),
///             x(0) = 0,  psi = (x2(tf) - 5, x3(tf) - 45, x4(tf)) = 0   (x1(tf) free),
///             th in [-pi/2, pi/2].
///
/// Posed with time scaling (problems/reference/scaled_min_time.h): control u = (w1, w2, sigma)
/// with w = (cos th, sin th), horizon s in [0, 1], clock t as the last state, J = tf at the
/// optimum. The bound th in [-pi/2, pi/2] (w1 >= 0, a half disc) is inactive at the optimum (th
/// runs from about 54.6 to -54.9 degrees), so U uses the whole disc; tests check w1 > 0 along the
/// optimum.
///
/// References: continuous tf* = 0.5545708783 (project notes 1.4, re-derived by shooting on
/// tan th = tan th0 + k t with th0 = 0.9534097564, k = -5.0796333191; PSOPT's lts example:
/// 0.5545709). COPS 3.0 (Dolan, Moré, Munson 2004) reports 0.554577 for its trapezoid scheme at
/// nh = 200 with a constant step tf/nh: an optimum of that discrete problem.
///
/// Fit for the Hamiltonian method: switching vector s = a (p3, p4), w* = -s/|s|, drift
/// p1 x3 + p2 x4; sigma* from the eps terms (default eps = 1). Penalty form: weight C on
/// |psi|^2 (default 1e3).
class Steering final : public ScaledMinTimeOcp<Steering, 5, 3> {
 public:
  static constexpr double kThrust = 100.0;
  static constexpr double kReferenceTime = 0.5545708783;
  static constexpr double kCopsReferenceTime = 0.554577;
  static constexpr int kCopsIntervals = 200;
  /// Parameters: C (1e3), eps (1), sigma_min (0.05), sigma_max (5).
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit Steering(const Parameters& params);

  std::string name() const override { return "steering"; }

  template <class T>
  void EvalPhysical(const VecT<T, 5>& x, const T& w1, const T& w2, VecT<T, 5>* f) const {
    (*f)[0] = x[2];
    (*f)[1] = x[3];
    (*f)[2] = kThrust * w1;
    (*f)[3] = kThrust * w2;
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 5>& x, VecT<T, 3>* psi) const {
    (*psi)[0] = x[1] - 5.0;
    (*psi)[1] = x[2] - 45.0;
    (*psi)[2] = x[3];
  }
};

/// The registry entry "steering".
ProblemInfo SteeringProblemInfo();

}  // namespace ocpb
