// One benchmark case: a problem (with parameters and seed) solved by one method, judged by the
// common evaluator, written as one JSON record. `ocpbench solve` runs one; `ocpbench run` many.
#pragma once

#include <cstdint>
#include <functional>
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
  /// The spec's own fields: throws std::invalid_argument naming the field when a value is out
  /// of range. ValidateCase checks everything else that can be checked without solving.
  void Validate() const;
};

/// Everything about a case that can be checked before solving, cheaply (no channel is
/// simulated): Validate(); the problem, solver and transcription names; the parameters and the
/// problem's own cross-field rules (ProblemInfo::make_for_checks, or make); the solver's options
/// through its own parser (unknown keys, bad values, NLopt's algorithm name); and the memory
/// the grid needs (EstimateCaseMemoryBytes against CaseMemoryBudgetBytes). Throws
/// std::invalid_argument "FIELD: rule". `ocpbench run` calls it for every case of a suite
/// before running any; RunCase calls it first.
void ValidateCase(const CaseSpec& spec);

/// OCPBench's rough, deliberately generous estimate of the memory one case needs, in bytes.
/// With m the points per interval (hermite-simpson 2, lgr `degree`, otherwise 1), nodes =
/// N m + 1 and w = nx + nu:
///   vectors: 64 doubles per node and component (iterates, bounds, multipliers, the solvers'
///            copies, the evaluator's 10x finer re-simulation, the record's trajectory),
///            512 w bytes per node;
///   sparse:  solvers that factor sparse matrices (ipopt, indirect-newton) add 320 bytes per
///            Jacobian and Hessian nonzero (16 bytes per stored entry, times 20 for copies and
///            the factorization's fill-in), with nnz = nodes w (w + (m + 1) nx): a Hessian block
///            per node and defect rows that couple m + 1 nodes.
/// NLopt's dense algorithms refuse large problems themselves (NloptOptions' limits); a channel's
/// fixed memory is not counted. Measured peaks (max RSS, double integrator, Release) against the
/// estimate: hamiltonian N = 1e6 657 MB (estimate 1.54 GB), ipopt + euler N = 1e5 355 MB
/// (826 MB), ipopt + hermite-simpson N = 1e5 905 MB (2.04 GB): about 2.3 times generous.
double EstimateCaseMemoryBytes(const CaseSpec& spec, int nx, int nu, int intervals);

/// The memory one case may use: half the physical memory (sysconf), 4 GiB when unknown.
double CaseMemoryBudgetBytes();

/// Parses one suite case (JSON object) strictly: unknown keys, wrong types and invalid values
/// throw std::invalid_argument "FIELD: rule" prefixed by `where`.
CaseSpec ParseCaseSpec(const nlohmann::json& j, const std::string& where);

/// Statuses that count as failures for the exit code (limits and "not applicable" do not).
bool IsFailure(SolveStatus status);
/// The same for a record's status name (ToString of a SolveStatus).
bool IsFailure(const std::string& status);

/// Solves the case and returns its record. Never throws for numerical trouble (that is the
/// record's status); throws std::invalid_argument for an invalid case (ValidateCase) before
/// any solving.
nlohmann::json RunCase(const CaseSpec& spec);

/// `run` (RunCase by default) with every exception turned into the case's record, so that one
/// case never stops a suite: std::invalid_argument gives status invalid_input, any other
/// std::exception status error (solver_status "exception"); the message is kept.
nlohmann::json RunCaseRecordingFailures(
    const CaseSpec& spec, const std::function<nlohmann::json(const CaseSpec&)>& run = RunCase);

/// The versions recorded with every result.
nlohmann::json VersionsJson();

}  // namespace ocpb
