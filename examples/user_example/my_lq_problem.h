// A problem defined outside OCPBench, written once as templates on the scalar type: OCPBench
// differentiates it (first and second derivatives by forward-mode AD) for every method.
//
//   minimize    J = int_0^1 (x^2 + u^2) dt        (no 1/2)
//   subject to  x' = u,  x(0) = x0 = 1,  |u| <= 2 (never active at the optimum).
//
// The value function is P(t) x^2 with -P' = 1 - P^2, P(1) = 0, so P(t) = tanh(1 - t),
// u*(t) = -P(t) x(t), and J* = tanh(1) x0^2 = 0.7615941559557649.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>

#include "core/autodiff_ocp.h"
#include "problems/registry.h"

namespace my_project {

// The dimensions are stated once, as template arguments (NX, NU, and NPSI = 0 terminal and
// NC = 0 path constraints by default); AutoDiffOcp sets them.
class MyLqProblem final : public ocpb::AutoDiffOcp<MyLqProblem, /*NX=*/1, /*NU=*/1> {
 public:
  explicit MyLqProblem(double x0) {
    SetHorizon(0.0, 1.0);
    SetInitialState(ocpb::Vec::Constant(1, x0));
    SetControlSet(ocpb::ControlSet::Box(ocpb::Vec::Constant(1, -2.0), ocpb::Vec::Constant(1, 2.0)));
  }
  std::string name() const override { return "my-lq"; }

  template <class T>
  void EvalDynamics(double,
                    const ocpb::VecT<T, 1>&,
                    const ocpb::VecT<T, 1>& u,
                    ocpb::VecT<T, 1>* f) const {
    (*f)[0] = u[0];
  }
  template <class T>
  T EvalRunningCost(double, const ocpb::VecT<T, 1>& x, const ocpb::VecT<T, 1>& u) const {
    return x[0] * x[0] + u[0] * u[0];
  }

  // Optional, for the Hamiltonian method: u* = argmin_{|u| <= 2} H = x^2 + u^2 + p u.
  bool HasHamiltonianMinimizer() const override { return true; }
  void MinimizeHamiltonian(double,
                           ocpb::ConstVecRef,
                           ocpb::ConstVecRef p,
                           ocpb::VecRef u) const override {
    u[0] = std::clamp(-0.5 * p[0], -2.0, 2.0);
  }
};

// Its registry entry: name, parameters (validated), factory and reference value.
inline ocpb::ProblemInfo MyLqProblemInfo() {
  ocpb::ProblemInfo info;
  info.name = "my-lq";
  info.description = "user example: x' = u, int_0^1 x^2 + u^2, x(0) = x0";
  info.parameters = {{"x0", {1.0}, "initial state"}};
  info.make = [](const ocpb::Parameters& params, std::uint64_t) -> std::unique_ptr<ocpb::Ocp> {
    return std::make_unique<MyLqProblem>(params.Scalar("x0"));
  };
  info.default_intervals = 50;
  info.reference_value = std::tanh(1.0);  // for x0 = 1
  info.reference_source = "Riccati: P(t) = tanh(1 - t), J* = tanh(1) x0^2";
  return info;
}

}  // namespace my_project
