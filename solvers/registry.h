// The solvers OCPBench knows by name, with their options.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/option_schema.h"
#include "solvers/solver.h"
#include "transcriptions/registry.h"

namespace ocpb {

/// A registered solver: how to build it, its options, and what the harness needs to know to
/// run and size it. Everything `ocpbench` does with a solver comes from here, so a solver
/// written outside OCPBench and added with RegisterSolver runs through `ocpbench solve` and
/// `ocpbench run` like a built-in one.
struct SolverInfo {
  std::string name;
  std::string description;
  std::function<std::unique_ptr<Solver>()> make;
  /// Solves an NLP from a transcription (SolveRequest::transcription is then required).
  bool uses_transcription = false;
  /// Its options: keys, defaults, rules (`ocpbench describe solver NAME`). Solve() receives
  /// them resolved by this schema; a case is refused before anything runs when one breaks it.
  OptionSchema options;
  /// Cross-field rules beyond single values (for example "hamiltonian.<key> needs warm_start =
  /// hamiltonian"): throws std::invalid_argument "FIELD: rule" for resolved options that break
  /// one. Empty: none.
  std::function<void(const OptionMap& resolved)> check_options;
  /// Options a warm-started re-solve near the previous optimum takes unless told otherwise
  /// (drivers such as online re-planning apply them under the user's options).
  OptionMap replan_defaults;
  /// Factors sparse Jacobian or Hessian matrices (Ipopt, indirect Newton): the memory
  /// estimate then adds their nonzeros and fill-in (see EstimateCaseMemoryBytes in bench/).
  bool factorizes_sparse_matrices = false;
  /// The option whose value stops the solver and so bounds its accuracy (Ipopt's "tol"), and
  /// what it measures; records carry both with the value used (JudgeResult). Empty: none named.
  std::string accuracy_option;
  std::string accuracy_note;
};

/// Every registered solver: the built-in ones, then RegisterSolver's, in that order.
const std::vector<SolverInfo>& Solvers();
/// Throw std::invalid_argument listing the valid names when `name` is unknown.
const SolverInfo& FindSolver(const std::string& name);
/// Adds a solver defined outside OCPBench (see examples/user_example/). Throws
/// std::invalid_argument when the name is empty or taken or `make` is empty. Call it at
/// start-up, before any solving (it invalidates references returned by Solvers() and
/// FindSolver()).
void RegisterSolver(SolverInfo info);

}  // namespace ocpb
