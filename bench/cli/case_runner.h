// One benchmark case: a problem (with parameters and seed) solved by one method, judged by the
// common evaluator, written as one JSON record. `ocpbench solve` runs one; `ocpbench run` many.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/integrator.h"
#include "core/ocp.h"
#include "core/solve_result.h"

namespace ocpb {

/// What to solve and how. Defaults are what `ocpbench solve` uses when an option is omitted.
struct CaseSpec {
  std::string problem;           ///< registry name
  std::vector<std::string> set;  ///< parameter overrides, "key=value" or "key=v1,v2"
  std::uint64_t seed = 1;        ///< channel realization (problems that use one)
  std::string solver;            ///< registry name
  std::string transcription;     ///< NLP solvers only
  std::string algorithm;         ///< NLopt only
  int intervals = 0;             ///< N; 0: the problem's default grid
  int degree = 3;                ///< LGR degree
  TerminalMode terminal = TerminalMode::kPenalty;
  Integrator integrator = Integrator::kEuler;  ///< the method's own integrator (Hamiltonian)
  /// The common evaluator's integrator on the method's grid. Every record also carries the
  /// RK4 evaluation on a 10x finer grid (the "fine" fields).
  Integrator evaluate_with = Integrator::kEuler;
  std::map<std::string, std::string> options;  ///< solver options
  int repeats = 1;              ///< timing repeats; the record keeps the median CPU time
  bool keep_trajectory = true;  ///< store t, x, u in the record (for figures)
  /// A previous `ocpbench solve --json` record whose controls start the solve (empty: the
  /// solver's default start). Read and checked before solving (bench/cli/initial_guess.h).
  std::string initial_guess;
  /// "solve" (one solve, the default) or "online" (re-planning with channel updates, paper
  /// Section IV: `options` are the solver options of every solve, `replan_options` override them
  /// for the re-plans, `online` holds the scenario settings; see bench/cli/online_command.h).
  std::string kind = "solve";
  std::map<std::string, std::string> online;          ///< kind "online": scenario settings
  std::map<std::string, std::string> replan_options;  ///< kind "online": re-plan solver options

  /// A stable identifier of the case (for --resume and shard assignment).
  std::string Key() const;
  /// Throws std::invalid_argument naming the field when a value is out of range.
  void Validate() const;
};

/// Parses one suite case (JSON object) strictly: unknown keys, wrong types and invalid values
/// throw std::invalid_argument "FIELD: rule" prefixed by `where`.
CaseSpec ParseCaseSpec(const nlohmann::json& j, const std::string& where);

/// Statuses that count as failures for the exit code (limits and "not applicable" do not).
bool IsFailure(SolveStatus status);

/// Solves the case and returns its record. Never throws for numerical trouble (that is the
/// record's status); throws std::invalid_argument for an invalid case (unknown names, bad
/// parameters) before any solving.
nlohmann::json RunCase(const CaseSpec& spec);

/// The versions recorded with every result.
nlohmann::json VersionsJson();

}  // namespace ocpb
