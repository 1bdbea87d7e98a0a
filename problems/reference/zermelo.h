// Zermelo's navigation problem as a minimum-time problem (OCPBench problem "zermelo").
#pragma once

#include <string>
#include <vector>

#include "problems/reference/scaled_min_time.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    tf
/// subject to  x' = V cos th + c y,  y' = V sin th    (V = 1, current c y with c = -1),
///             (x, y)(0) = (3.5, -1.8),  psi = (x(tf), y(tf)) = 0.
///
/// Posed with time scaling (problems/reference/scaled_min_time.h): state (x, y), control
/// u = (w1, w2, sigma) with w = (cos th, sin th) in the unit disc, horizon s in [0, 1],
/// clock t as the last state, J = tf at the optimum.
///
/// Reference: tf* = 5.26493205 (J. T. Betts, "Practical Methods for Optimal Control and
/// Estimation Using Nonlinear Programming", 2nd ed., 2010, example 10.148); re-derived from the
/// maximum principle (tan th linear in t, th' = -c cos^2 th): 5.2649320661 (project notes 2.11).
///
/// Fit for the Hamiltonian method: switching vector s = V (p_x, p_y), w* = -s/|s|, drift
/// p_x c y; sigma* from the eps terms (default eps = 1). Penalty form: weight C on |psi|^2
/// (default 1e3).
class Zermelo final : public ScaledMinTimeOcp<Zermelo, 3, 2> {
 public:
  static constexpr double kSpeed = 1.0;
  static constexpr double kCurrent = -1.0;
  static constexpr double kReferenceTime = 5.2649320661;
  /// Parameters: C (1e3), eps (1), sigma_min (0.5), sigma_max (20).
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit Zermelo(const Parameters& params);

  std::string name() const override { return "zermelo"; }

  template <class T>
  void EvalPhysical(const VecT<T, 3>& x, const T& w1, const T& w2, VecT<T, 3>* f) const {
    (*f)[0] = kSpeed * w1 + kCurrent * x[1];
    (*f)[1] = kSpeed * w2;
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 3>& x, VecT<T, 2>* psi) const {
    (*psi)[0] = x[0];
    (*psi)[1] = x[1];
  }
};

/// The registry entry "zermelo".
ProblemInfo ZermeloProblemInfo();

}  // namespace ocpb
