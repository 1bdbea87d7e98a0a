// Helpers shared by the reference-problem tests (tests/problems/reference_*_test.cc): solving a
// registered problem with a registered method, and judging the controls with the common
// evaluator.
#pragma once

#include <cmath>
#include <map>
#include <memory>
#include <string>

#include "core/evaluator.h"
#include "core/ocp.h"
#include "core/solve_result.h"
#include "solvers/registry.h"
#include "solvers/solver.h"

namespace ocpb::reference_testing {

/// |value - reference| / |reference|.
inline double RelativeError(double value, double reference) {
  return std::abs(value - reference) / std::abs(reference);
}

/// A request on N uniform intervals of the problem's horizon.
inline SolveRequest Request(const Ocp& ocp,
                            int N,
                            TerminalMode terminal,
                            const std::string& transcription = "",
                            std::map<std::string, std::string> options = {}) {
  SolveRequest r;
  r.grid = TimeGrid::Uniform(ocp.t0(), ocp.tf(), N);
  r.terminal = terminal;
  r.transcription = transcription;
  r.options = std::move(options);
  return r;
}

/// Solves through the solver registry, as `ocpbench` does.
inline SolveResult SolveWith(const std::string& solver, const Ocp& ocp, const SolveRequest& r) {
  return FindSolver(solver).make()->Solve(ocp, r);
}

/// Ipopt on `transcription` (hard terminal form unless told otherwise).
inline SolveResult SolveWithIpopt(const Ocp& ocp,
                                  const std::string& transcription,
                                  int N,
                                  TerminalMode terminal = TerminalMode::kHard) {
  return SolveWith("ipopt", ocp, Request(ocp, N, terminal, transcription));
}

/// The Hamiltonian descent through the registry, forward Euler on N intervals, penalty terminal
/// form. The solver itself solves the problem's Hamiltonian reformulation when it has one
/// (Ocp::HamiltonianReformulation; options "path_penalty" and "regularization").
inline SolveResult SolveWithHamiltonian(const Ocp& ocp,
                                        int N,
                                        std::map<std::string, std::string> options) {
  return SolveWith(
      "hamiltonian", ocp, Request(ocp, N, TerminalMode::kPenalty, "", std::move(options)));
}

/// The continuous-time judgement of a result: its controls re-simulated with RK4 on the
/// result's control grid refined 10 times, on the ORIGINAL problem (not a reformulation).
inline Evaluation FineEvaluation(const Ocp& ocp, const SolveResult& result, int N) {
  return Evaluate(
      ocp, result.controls, TimeGrid::Uniform(ocp.t0(), ocp.tf(), N).Refined(10), Integrator::kRk4);
}

}  // namespace ocpb::reference_testing
