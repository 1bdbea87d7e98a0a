// An Ocp that forwards every function to another one: the base of problems that change one
// part of a problem (its terminal cost, its running cost) and keep the rest.
#pragma once

#include <string>

#include "core/ocp.h"

namespace ocpb {

/// Forwards every Ocp function to `inner` (not owned; it must outlive this object) and copies
/// its dimensions, horizon, initial state, terminal weights, control set, free final time, state
/// bounds, initial-state bounds, static parameters and boundary constraints' bounds.
/// A subclass overrides what it changes and documents it. HamiltonianReformulation() is not
/// forwarded (it returns nullptr): a reformulation of `inner` would drop the subclass's change,
/// so callers resolve reformulations before wrapping. MinimizeHamiltonianWithGradients() is not
/// forwarded either: Ocp's default composes it from this object's own (forwarded or overridden)
/// three functions, so a subclass that changes one of them stays consistent. Interfaces a problem
/// implements next to Ocp (EulerStageModel) are not forwarded either: a wrapper only offers what it
/// implements, which is also how tests run a problem without its fast paths.
class ForwardingOcp : public Ocp {
 public:
  explicit ForwardingOcp(const Ocp& inner) : ForwardingOcp(inner, true) {}

  const Ocp& inner() const { return inner_; }
  std::string name() const override { return inner_.name(); }

 protected:
  /// With keep_path_constraints = false the wrapper has num_path() == 0 and its
  /// PathConstraints* functions must not be called (a subclass that folds the constraints into
  /// L overrides them).
  ForwardingOcp(const Ocp& inner, bool keep_path_constraints) : inner_(inner) {
    SetDimensions(
        inner.nx(), inner.nu(), inner.num_terminal(), keep_path_constraints ? inner.num_path() : 0);
    SetHorizon(inner.t0(), inner.tf());
    SetInitialState(inner.x0());
    if (inner.num_terminal() > 0) SetTerminalWeights(inner.terminal_weights());
    SetControlSet(inner.control_set());
    if (inner.free_final_time()) {
      SetFreeFinalTime(inner.free_final_time()->lower, inner.free_final_time()->upper);
    }
    if (inner.state_bounds()) {
      SetStateBounds(inner.state_bounds()->lower, inner.state_bounds()->upper);
    }
    if (inner.initial_state_bounds()) {
      SetInitialStateBounds(inner.initial_state_bounds()->lower,
                            inner.initial_state_bounds()->upper);
    }
    if (const int np = inner.num_static_parameters(); np > 0) {
      SetStaticParameters(inner.initial_state_bounds()->lower.tail(np),
                          inner.initial_state_bounds()->upper.tail(np),
                          inner.x0().tail(np));
    }
    if (inner.num_boundary() > 0) {
      SetBoundaryConstraints(inner.boundary_bounds().lower, inner.boundary_bounds().upper);
    }
  }

 public:
  void Dynamics(double t, ConstVecRef x, ConstVecRef u, VecRef f) const override {
    inner_.Dynamics(t, x, u, f);
  }
  double RunningCost(double t, ConstVecRef x, ConstVecRef u) const override {
    return inner_.RunningCost(t, x, u);
  }
  double TerminalCost(ConstVecRef x) const override { return inner_.TerminalCost(x); }
  bool HasInitialCost() const override { return inner_.HasInitialCost(); }
  void BoundaryConstraints(ConstVecRef x0, ConstVecRef xf, VecRef b) const override {
    inner_.BoundaryConstraints(x0, xf, b);
  }
  void BoundaryConstraintsJacobian(
      ConstVecRef x0, ConstVecRef xf, VecRef b, MatRef b_x0, MatRef b_xf) const override {
    inner_.BoundaryConstraintsJacobian(x0, xf, b, b_x0, b_xf);
  }
  void BoundaryHessian(ConstVecRef x0, ConstVecRef xf, ConstVecRef mu, MatRef hess) const override {
    inner_.BoundaryHessian(x0, xf, mu, hess);
  }
  double InitialCost(ConstVecRef x0) const override { return inner_.InitialCost(x0); }
  void InitialCostGradient(ConstVecRef x0, double* phi0, VecRef grad) const override {
    inner_.InitialCostGradient(x0, phi0, grad);
  }
  void InitialCostHessian(ConstVecRef x0, double sigma, MatRef hess) const override {
    inner_.InitialCostHessian(x0, sigma, hess);
  }
  void TerminalConstraints(ConstVecRef x, VecRef psi) const override {
    inner_.TerminalConstraints(x, psi);
  }
  void PathConstraints(double t, ConstVecRef x, ConstVecRef u, VecRef c) const override {
    inner_.PathConstraints(t, x, u, c);
  }
  void DynamicsJacobian(
      double t, ConstVecRef x, ConstVecRef u, VecRef f, MatRef fx, MatRef fu) const override {
    inner_.DynamicsJacobian(t, x, u, f, fx, fu);
  }
  void RunningCostGradient(
      double t, ConstVecRef x, ConstVecRef u, double* L, VecRef Lx, VecRef Lu) const override {
    inner_.RunningCostGradient(t, x, u, L, Lx, Lu);
  }
  void TerminalCostGradient(ConstVecRef x, double* phi, VecRef phix) const override {
    inner_.TerminalCostGradient(x, phi, phix);
  }
  void TerminalConstraintsJacobian(ConstVecRef x, VecRef psi, MatRef psix) const override {
    inner_.TerminalConstraintsJacobian(x, psi, psix);
  }
  void PathConstraintsJacobian(
      double t, ConstVecRef x, ConstVecRef u, VecRef c, MatRef cx, MatRef cu) const override {
    inner_.PathConstraintsJacobian(t, x, u, c, cx, cu);
  }
  void PointHessian(double t,
                    ConstVecRef x,
                    ConstVecRef u,
                    double sigma,
                    ConstVecRef lambda,
                    ConstVecRef mu,
                    MatRef hess) const override {
    inner_.PointHessian(t, x, u, sigma, lambda, mu, hess);
  }
  void TerminalHessian(ConstVecRef x, double sigma, ConstVecRef nu, MatRef hess) const override {
    inner_.TerminalHessian(x, sigma, nu, hess);
  }
  bool HasHamiltonianMinimizer() const override { return inner_.HasHamiltonianMinimizer(); }
  void MinimizeHamiltonian(double t, ConstVecRef x, ConstVecRef p, VecRef u) const override {
    inner_.MinimizeHamiltonian(t, x, p, u);
  }
  void MinimizeAndCompareHamiltonian(double t,
                                     ConstVecRef x,
                                     ConstVecRef p,
                                     ConstVecRef u,
                                     VecRef u_star,
                                     double* h_star,
                                     double* h_now,
                                     VecRef f) const override {
    inner_.MinimizeAndCompareHamiltonian(t, x, p, u, u_star, h_star, h_now, f);
  }
  std::optional<double> RunningCostLowerBound() const override {
    return inner_.RunningCostLowerBound();
  }
  bool HasAffineDynamics() const override { return inner_.HasAffineDynamics(); }
  Vec NominalControl() const override { return inner_.NominalControl(); }
  std::optional<ControlTrajectory> BaselinePlan(const TimeGrid& grid,
                                                std::string* why_not) const override {
    return inner_.BaselinePlan(grid, why_not);
  }

 private:
  const Ocp& inner_;
};

}  // namespace ocpb
