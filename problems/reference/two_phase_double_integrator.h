// Minimum time for a double integrator as two phases with a free switching time (OCPBench
// problem "two-phase-double-integrator"): the reference for MultiPhaseOcp.
#pragma once

#include <memory>
#include <string>

#include "core/autodiff_ocp.h"
#include "core/multi_phase_ocp.h"
#include "problems/registry.h"

namespace ocpb {

/// Phase 1 accelerates towards the origin (u in [-1, 0]), phase 2 brakes (u in [0, 1]):
///
///   minimize    T1 + T2        (L = 1 in each phase: the total time)
///   subject to  x1' = x2, x2' = u in each phase,
///               x(0) = (1, 0), x continuous at the switch, x(T1 + T2) = (0, 0),
///               T1, T2 in [0.05, 10] free.
///
/// Reference: the minimum-time double integrator from rest at distance d stops at the origin in
/// T* = 2 sqrt(d), switching from u = -1 to u = +1 at sqrt(d) (Bryson and Ho, Applied Optimal
/// Control, 1975, sec. 3.9; the switching curve x1 = x2 |x2| / 2): d = 1 gives J* = 2, T1* =
/// T2* = 1. The phases' control sets make the switch unique.
/// One phase: NPSI = 0 accelerates (u in [-1, 0], no condition at its end: an earlier phase's
/// terminal constraints would be events), NPSI = 2 brakes (u in [0, 1], x(end) = 0).
template <int NPSI>
class DoubleIntegratorPhase final : public AutoDiffOcp<DoubleIntegratorPhase<NPSI>, 2, 1, NPSI, 0> {
 public:
  static constexpr bool kAccelerates = NPSI == 0;
  DoubleIntegratorPhase() {
    // A nominal duration of 1.5 (the optimum is 1): where the solvers start.
    this->SetHorizon(0.0, 1.5);
    this->SetInitialState(kAccelerates ? Eigen::Vector2d(1.0, 0.0) : Eigen::Vector2d(0.5, -1.0));
    this->SetControlSet(kAccelerates ? ControlSet::Box(Vec::Constant(1, -1.0), Vec::Zero(1))
                                     : ControlSet::Box(Vec::Zero(1), Vec::Ones(1)));
    if constexpr (NPSI > 0) this->SetTerminalWeights(Vec::Constant(NPSI, 100.0));
  }

  std::string name() const override { return kAccelerates ? "accelerate" : "brake"; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 2>& x, const VecT<T, 1>& u, VecT<T, 2>* f) const {
    (*f)[0] = x[1];
    (*f)[1] = u[0];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 2>&, const VecT<T, 1>&) const {
    return T(1.0);
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 2>& x, VecT<T, NPSI>* psi) const {
    if constexpr (NPSI == 2) {
      (*psi)[0] = x[0];
      (*psi)[1] = x[1];
    }
  }
};

/// The two phases joined by continuity of both states.
std::unique_ptr<MultiPhaseOcp> MakeTwoPhaseDoubleIntegrator();

/// The registry entry "two-phase-double-integrator".
ProblemInfo TwoPhaseDoubleIntegratorProblemInfo();

}  // namespace ocpb
