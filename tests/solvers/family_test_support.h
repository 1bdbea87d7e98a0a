// Requests and reference solves shared by the Hamiltonian family's tests.
#pragma once

#include <cmath>
#include <string>

#include "core/ocp.h"
#include "core/solve_result.h"
#include "solvers/registry.h"

namespace ocpb {

/// A request on N uniform intervals of the problem's horizon, in `mode`.
inline SolveRequest FamilyRequest(const Ocp& ocp,
                                  int N,
                                  TerminalMode mode = TerminalMode::kPenalty) {
  SolveRequest r;
  r.grid = TimeGrid::Uniform(ocp.t0(), ocp.tf(), N);
  r.terminal = mode;
  return r;
}

/// Ipopt on the Euler transcription of the same grid: the NLP whose KKT points the family's
/// polish solves for. `tol` is Ipopt's (0: its default).
inline SolveResult IpoptEuler(const Ocp& ocp, int N, TerminalMode mode, double tol = 0.0) {
  SolveRequest r = FamilyRequest(ocp, N, mode);
  r.transcription = "euler";
  if (tol > 0.0) r.options.Set("tol", tol);
  return FindSolver("ipopt").make()->Solve(ocp, r);
}

/// A solver_stats entry, NaN when absent.
inline double Stat(const SolveResult& r, const std::string& key) {
  const auto it = r.solver_stats.find(key);
  return it == r.solver_stats.end() ? NAN : it->second;
}

}  // namespace ocpb
