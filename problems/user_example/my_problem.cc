// A problem defined outside OCPBench, in one file, registered at run time and solved by every
// method. Build it against an installed OCPBench (see README.md in this folder):
//
//   find_package(OCPBench REQUIRED)
//   add_executable(my_problem my_problem.cc)
//   target_link_libraries(my_problem PRIVATE OCPBench::solvers OCPBench::problems)
//
// Exit status 0 when every method comes within its stated tolerance of the known optimum.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/evaluator.h"
#include "problems/registry.h"
#include "solvers/registry.h"

namespace {

// 1. The problem, written once as templates on the scalar type: OCPBench differentiates it
//    (first and second derivatives by forward-mode AD) for every method.
//
//   minimize    J = int_0^1 (x^2 + u^2) dt        (no 1/2)
//   subject to  x' = u,  x(0) = x0 = 1,  |u| <= 2 (never active at the optimum).
//
// The value function is P(t) x^2 with -P' = 1 - P^2, P(1) = 0, so P(t) = tanh(1 - t),
// u*(t) = -P(t) x(t), and J* = tanh(1) x0^2 = 0.7615941559557649.
class MyLqProblem final : public ocpb::AutoDiffOcp<MyLqProblem, /*NX=*/1, /*NU=*/1> {
 public:
  explicit MyLqProblem(double x0) {
    SetDimensions(/*nx=*/1, /*nu=*/1, /*npsi=*/0, /*nc=*/0);
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

  // 2. Optional, for the Hamiltonian method: u* = argmin_{|u| <= 2} H = x^2 + u^2 + p u.
  bool HasHamiltonianMinimizer() const override { return true; }
  void MinimizeHamiltonian(double,
                           ocpb::ConstVecRef,
                           ocpb::ConstVecRef p,
                           ocpb::VecRef u) const override {
    u[0] = std::clamp(-0.5 * p[0], -2.0, 2.0);
  }
};

// 3. Its registry entry: name, parameters (validated), factory and reference value.
ocpb::ProblemInfo MyLqProblemInfo() {
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

struct Method {
  std::string solver, transcription, algorithm;
  int N;
  double tolerance;  // on |Jbar - J*| / J*, Jbar from RK4 on a 10x finer grid
};

}  // namespace

int main() {
  // 4. Register at run time; from here on the problem is known by name, like a built-in one
  //    (`ocpb::MakeProblem("my-lq", {"x0=2"}, 0)`, suites, ...).
  ocpb::RegisterProblem(MyLqProblemInfo());
  const std::unique_ptr<ocpb::Ocp> ocp = ocpb::MakeProblem("my-lq", {}, 0);
  const double reference = *ocpb::FindProblem("my-lq").reference_value;

  // 5. Solve it with every method. Tolerances: the accuracy each scheme has on this grid
  //    (measured errors 1.7e-5, 1.7e-5, 1.2e-6, 2.0e-9, 1.1e-10, 2.0e-9), rounded up.
  const std::vector<Method> methods = {
      {"hamiltonian", "", "", 100, 5e-5},  // forward Euler, the same discrete problem as below
      {"ipopt", "euler", "", 100, 5e-5},
      {"ipopt", "trapezoid", "", 50, 3e-6},
      {"ipopt", "hermite-simpson", "", 20, 1e-8},
      {"ipopt", "lgr", "", 10, 1e-9},
      {"nlopt", "hermite-simpson", "LD_SLSQP", 20, 1e-8},
  };
  int failures = 0;
  std::printf("%-12s %-16s %4s %-22s %-14s %-10s\n",
              "solver",
              "transcription",
              "N",
              "status",
              "Jbar (fine)",
              "rel. error");
  for (const Method& m : methods) {
    ocpb::SolveRequest request;
    request.grid = ocpb::TimeGrid::Uniform(ocp->t0(), ocp->tf(), m.N);
    request.terminal = ocpb::TerminalMode::kPenalty;  // there is no terminal constraint anyway
    request.transcription = m.transcription;
    request.algorithm = m.algorithm;
    if (m.solver == "hamiltonian") request.options = {{"theta_tolerance", "1e-12"}};
    const ocpb::SolveResult result = ocpb::FindSolver(m.solver).make()->Solve(*ocp, request);
    // 6. Judge the controls with the common evaluator, never by the method's own report.
    const ocpb::Evaluation fine =
        ocpb::Evaluate(*ocp, result.controls, request.grid.Refined(10), ocpb::Integrator::kRk4);
    const double error = std::abs(fine.Jbar - reference) / reference;
    const bool ok = ocpb::IsSuccess(result.status) && error < m.tolerance;
    failures += ok ? 0 : 1;
    std::printf("%-12s %-16s %4d %-22s %-14.10f %-10.2e %s\n",
                m.solver.c_str(),
                m.transcription.c_str(),
                m.N,
                result.solver_status.c_str(),
                fine.Jbar,
                error,
                ok ? "ok" : "FAILED");
  }
  return failures == 0 ? 0 : 1;
}
