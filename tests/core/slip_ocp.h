// A one-state problem with the slips a problem's author makes most easily, selectable: a
// NominalControl of the wrong size, a free final time declared before the horizon.
#pragma once

#include <string>

#include "core/autodiff_ocp.h"

namespace ocpb::testing {

// x' = u on [0, 1], min int u^2, with a nominal control of `nominal_size` components and,
// when free_upper > 0, a free final time in [0.5, free_upper] declared before the horizon
// [0, tf] (the order SetFreeFinalTime's contract forbids).
class SlipOcp final : public AutoDiffOcp<SlipOcp, 1, 1, 0, 0> {
 public:
  explicit SlipOcp(int nominal_size, double free_upper = 0.0, double tf = 1.0)
      : nominal_size_(nominal_size) {
    if (free_upper > 0.0) SetFreeFinalTime(0.5, free_upper);
    SetHorizon(0.0, tf);
    SetInitialState(Vec::Ones(1));
  }
  std::string name() const override { return "slip"; }
  Vec NominalControl() const override { return Vec::Zero(nominal_size_); }
  // H = u^2 + p u: u* = -p / 2 (U is all of R), so the Hamiltonian methods apply too.
  bool HasHamiltonianMinimizer() const override { return true; }
  void MinimizeHamiltonian(double, ConstVecRef, ConstVecRef p, VecRef u) const override {
    u[0] = -0.5 * p[0];
  }
  template <class T>
  void EvalDynamics(double, const VecT<T, 1>&, const VecT<T, 1>& u, VecT<T, 1>* f) const {
    (*f)[0] = u[0];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 1>&, const VecT<T, 1>& u) const {
    return u[0] * u[0];
  }

 private:
  int nominal_size_;
};

}  // namespace ocpb::testing
