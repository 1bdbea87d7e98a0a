// The brachistochrone as a minimum-time problem (OCPBench problem "brachistochrone").
#pragma once

#include <string>
#include <vector>

#include "problems/reference/scaled_min_time.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    tf
/// subject to  x' = v sin th,  y' = v cos th,  v' = g cos th    (y points down, g = 9.8),
///             (x, y, v)(0) = (0, 0, 0),  psi = (x(tf) - 2, y(tf) - 2) = 0,  v(tf) free.
///
/// Posed with time scaling (problems/reference/scaled_min_time.h): state (x, y, v), control
/// u = (w1, w2, sigma) with w = (sin th, cos th) in the unit disc, horizon s in [0, 1],
/// clock t as the last state, J = tf at the optimum.
///
/// Reference: the cycloid through (2, 2), x = k (phi - sin phi), y = k (1 - cos phi), reaches it
/// at phi_f = 2.412011143914 with k = 1.145834075064, so tf* = sqrt(k / g) phi_f =
/// 0.824759143157 (re-derived, project notes 2.10; A. E. Bryson, Y.-C. Ho, "Applied Optimal
/// Control", 1975; PSOPT's brac1 example reports 0.8247591). Along the optimum th = phi/2 grows
/// linearly in time from 0 to phi_f/2, and v = sqrt(2 g y).
///
/// Fit for the Hamiltonian method: switching vector s = (p_x v, p_y v + p_v g), w* = -s/|s|;
/// sigma* from the eps terms (default eps = 1). Penalty form: weight C on |psi|^2 (default 1e3).
class Brachistochrone final : public ScaledMinTimeOcp<Brachistochrone, 4, 2> {
 public:
  static constexpr double kGravity = 9.8;
  static constexpr double kReferenceTime = 0.824759143157;
  /// Parameters: C (1e3), eps (1), sigma_min (0.1), sigma_max (5).
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit Brachistochrone(const Parameters& params);

  std::string name() const override { return "brachistochrone"; }

  template <class T>
  void EvalPhysical(const VecT<T, 4>& x, const T& w1, const T& w2, VecT<T, 4>* f) const {
    (*f)[0] = x[2] * w1;
    (*f)[1] = x[2] * w2;
    (*f)[2] = kGravity * w2;
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 4>& x, VecT<T, 2>* psi) const {
    (*psi)[0] = x[0] - 2.0;
    (*psi)[1] = x[1] - 2.0;
  }
};

/// The registry entry "brachistochrone".
ProblemInfo BrachistochroneProblemInfo();

}  // namespace ocpb
