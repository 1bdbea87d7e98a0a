// A problem defined outside OCPBench (my_lq_problem.h), registered at run time and solved by
// every method through the library API. Build it against an installed OCPBench (see README.md
// in this folder):
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

#include "my_lq_problem.h"
#include "problems/registry.h"
#include "solvers/judge.h"
#include "solvers/registry.h"

namespace {

struct Method {
  std::string solver, transcription, algorithm;
  int N;
  double tolerance;  // on |Jbar - J*| / J*, Jbar from RK4 on a 10x finer grid
};

}  // namespace

int main() {
  // 1. Register at run time; from here on the problem is known by name, like a built-in one
  //    (`ocpb::MakeProblem("my-lq", {"x0=2"}, 0)`, suites, ...).
  ocpb::RegisterProblem(my_project::MyLqProblemInfo());
  const std::unique_ptr<ocpb::Ocp> ocp = ocpb::MakeProblem("my-lq", {}, 0);
  const double reference = *ocpb::FindProblem("my-lq").reference_value;

  // 2. Solve it with every method. Tolerances: the accuracy each scheme has on this grid
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
    if (!m.algorithm.empty()) request.options.Set("algorithm", m.algorithm);
    if (m.solver == "hamiltonian") request.options.Set("theta_tolerance", 1e-12);
    const ocpb::SolveResult result = ocpb::FindSolver(m.solver).make()->Solve(*ocp, request);
    // 3. Judge the controls with the common evaluator, never by the method's own report.
    //    JudgeResult takes the result itself (a free final time is judged on the solution's own
    //    horizon) and warns about what the status does not say.
    const ocpb::Judgement judged = ocpb::JudgeResult(*ocp, request, result);
    const double error = std::abs(judged.fine.Jbar - reference) / reference;
    const bool ok = result.status == ocpb::SolveStatus::kConverged && judged.judged &&
                    judged.warnings.empty() && error < m.tolerance;
    for (const ocpb::JudgeWarning& w : judged.warnings) {
      std::printf("  warning (%s): %s\n", w.code.c_str(), w.message.c_str());
    }
    failures += ok ? 0 : 1;
    std::printf("%-12s %-16s %4d %-22s %-14.10f %-10.2e %s\n",
                m.solver.c_str(),
                m.transcription.c_str(),
                m.N,
                result.solver_status.c_str(),
                judged.fine.Jbar,
                error,
                ok ? "ok" : "FAILED");
  }
  return failures == 0 ? 0 : 1;
}
