// The Goddard rocket in three phases, the middle one a singular arc (OCPBench problem
// "goddard-three-phase"): Betts' gdrd07, a reference for MultiPhaseOcp.
#pragma once

#include <cmath>
#include <memory>
#include <string>

#include "core/autodiff_ocp.h"
#include "core/multi_phase_ocp.h"
#include "problems/registry.h"

namespace ocpb {

/// maximize h(tF) (J = -h(tF)) of a vertically ascending rocket, states h (ft), v (ft/s), m
/// (slug), drag D = sigma v^2 exp(-h / h0), in three phases whose durations are free:
///   1. maximum thrust T_m:  h' = v, v' = (T_m - D) / m - g, m' = -T_m / c, from (0, 0, 3);
///      at its end the singular surface m g - (1 + v / c) D = 0 (an event);
///   2. the singular arc, thrust T_s(h, v, m) = D + m g + m g / (1 + 4 c/v + 2 c^2/v^2)
///      (c^2 / (h0 g) (1 + v/c) - 1 - 2 c/v): the same dynamics with T_s; at its end m = 1;
///   3. coasting without the mass state (m = 1 from then on): h' = v, v' = -D - g, to v = 0;
/// h and v continuous at both switches, m at the first. No controls: the decisions are the
/// three durations (each in [1, 100] s). (Each phase carries one control fixed at 0 by its
/// bounds, which nothing reads: AutoDiffOcp needs nu >= 1, and Ipopt removes fixed variables.)
/// Constants: T_m = 193.044, g = 32.174, sigma = 5.49153484923381010e-5, c = 1580.9425279876559,
/// h0 = 23800.
///
/// Reference: h(tF) = 18550.872 ft with switch times 13.751270, 21.987363 and tF = 42.887912 s
/// (J. T. Betts, "A Collection of Optimal Control Test Problems", 2015, example 10.47
/// gdrd07, "singular arc problem"; after Bryson's Goddard rocket).
struct GoddardThreePhaseConstants {
  static constexpr double kThrust = 193.044;
  static constexpr double kGravity = 32.174;
  static constexpr double kSigma = 5.49153484923381010e-5;
  static constexpr double kExhaust = 1580.9425279876559;
  static constexpr double kScaleHeight = 23800.0;
  static constexpr double kReferenceAltitude = 18550.872;

  template <class T>
  static T Drag(const T& h, const T& v) {
    return kSigma * v * v * exp(-h / kScaleHeight);
  }
  /// The singular-arc thrust T_s(h, v, m).
  template <class T>
  static T SingularThrust(const T& h, const T& v, const T& m) {
    const double c = kExhaust;
    const T mg = m * kGravity;
    const T denominator = 1.0 + 4.0 * c / v + 2.0 * c * c / (v * v);
    const T bracket = c * c / (kScaleHeight * kGravity) * (1.0 + v / c) - 1.0 - 2.0 * c / v;
    return Drag(h, v) + mg + mg / denominator * bracket;
  }
};

/// Phase 1 (maximum thrust; the singular surface at its end) and phase 2 (the singular arc; m = 1
/// at its end): states (h, v, m), no control.
template <bool kSingular>
class GoddardThrustPhase final : public AutoDiffOcp<GoddardThrustPhase<kSingular>, 3, 1, 1, 0>,
                                 private GoddardThreePhaseConstants {
 public:
  GoddardThrustPhase() {
    // Nominal durations where the solvers start (the optimum: 13.75 and 8.24 s), and phase 2's
    // start guess (its start is set by the links).
    this->SetHorizon(0.0, kSingular ? 10.0 : 12.0);
    this->SetInitialState(kSingular ? Eigen::Vector3d(5000.0, 700.0, 2.3)
                                    : Eigen::Vector3d(0.0, 0.0, 3.0));
    this->SetControlSet(ControlSet::Box(Vec::Zero(1), Vec::Zero(1)));
  }
  std::string name() const override { return kSingular ? "singular-arc" : "maximum-thrust"; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 3>& x, const VecT<T, 1>&, VecT<T, 3>* f) const {
    const T thrust = kSingular ? SingularThrust(x[0], x[1], x[2]) : T(kThrust);
    (*f)[0] = x[1];
    (*f)[1] = (thrust - Drag(x[0], x[1])) / x[2] - kGravity;
    (*f)[2] = -thrust / kExhaust;
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 3>& x, VecT<T, 1>* psi) const {
    if constexpr (kSingular) {
      (*psi)[0] = x[2] - 1.0;
    } else {
      (*psi)[0] = x[2] * kGravity - (1.0 + x[1] / kExhaust) * Drag(x[0], x[1]);
    }
  }
};

/// Phase 3: coasting, states (h, v), to v = 0; J = -h at its end.
class GoddardCoastPhase final : public AutoDiffOcp<GoddardCoastPhase, 2, 1, 1, 0>,
                                private GoddardThreePhaseConstants {
 public:
  GoddardCoastPhase() {
    SetHorizon(0.0, 20.0);
    SetInitialState(Eigen::Vector2d(12000.0, 600.0));
    SetControlSet(ControlSet::Box(Vec::Zero(1), Vec::Zero(1)));
    SetTerminalWeights(Vec::Constant(1, 1.0));
  }
  std::string name() const override { return "coast"; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 2>& x, const VecT<T, 1>&, VecT<T, 2>* f) const {
    (*f)[0] = x[1];
    (*f)[1] = -Drag(x[0], x[1]) - kGravity;  // m = 1
  }
  template <class T>
  T EvalTerminalCost(const VecT<T, 2>& x) const {
    return -x[0];
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 2>& x, VecT<T, 1>* psi) const {
    (*psi)[0] = x[1];
  }
};

/// The three phases with their links.
std::unique_ptr<MultiPhaseOcp> MakeGoddardThreePhase();

/// The registry entry "goddard-three-phase".
ProblemInfo GoddardThreePhaseProblemInfo();

}  // namespace ocpb
