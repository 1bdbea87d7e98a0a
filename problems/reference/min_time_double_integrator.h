// Minimum time for a double integrator with a bounded control, one phase (OCPBench problem
// "double-integrator-min-time").
#pragma once

#include <memory>
#include <string>

#include "core/autodiff_ocp.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    T = int_0^T 1 dt
/// subject to  x1' = x2, x2' = u, |u| <= 1, x(0) = (1, 0), x(T) = (0, 0), T in [0.5, 10] free.
///
/// Reference: T* = 2 sqrt(d) for a start at rest at distance d, one switch from u = -1 to u = +1
/// at sqrt(d) (Bryson and Ho, Applied Optimal Control, 1975, sec. 3.9): d = 1 gives J* = 2.
/// The bang-bang switch falls inside a grid interval unless the grid happens to put a node on
/// it; two-phase-double-integrator poses the same problem with the switch as a phase boundary.
class MinTimeDoubleIntegrator final : public AutoDiffOcp<MinTimeDoubleIntegrator, 2, 1, 2, 0> {
 public:
  MinTimeDoubleIntegrator() {
    SetHorizon(0.0, 3.0);  // the nominal T where methods start (the optimum is 2)
    SetFreeFinalTime(0.5, 10.0);
    SetInitialState(Eigen::Vector2d(1.0, 0.0));
    SetControlSet(ControlSet::Box(Vec::Constant(1, -1.0), Vec::Constant(1, 1.0)));
    SetTerminalWeights(Vec::Constant(2, 100.0));
  }
  std::string name() const override { return "double-integrator-min-time"; }

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
  void EvalTerminalConstraints(const VecT<T, 2>& x, VecT<T, 2>* psi) const {
    (*psi)[0] = x[0];
    (*psi)[1] = x[1];
  }
  /// u = -1: accelerate towards the origin (at u = 0 nothing moves).
  Vec NominalControl() const override { return Vec::Constant(1, -1.0); }
};

/// The registry entry "double-integrator-min-time".
inline ProblemInfo MinTimeDoubleIntegratorProblemInfo() {
  ProblemInfo p;
  p.name = "double-integrator-min-time";
  p.description = "minimum time from (1, 0) to rest at 0 with |u| <= 1, one phase (bang-bang)";
  p.make = [](const Parameters&, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<MinTimeDoubleIntegrator>();
  };
  p.default_intervals = 50;
  p.reference_value = 2.0;
  p.reference_source =
      "analytic: T* = 2 sqrt(d) with d = 1, one switch at sqrt(d) (Bryson and Ho 1975, sec. 3.9)";
  p.hamiltonian_note = "not applicable: no closed-form Hamiltonian minimizer given (H linear in u)";
  p.tags = {"bang-bang", "free-time", "control-constrained"};
  return p;
}

}  // namespace ocpb
