// A case resolved and checked once, before anything is solved: what RunCase
// (bench/cli/case_runner.h) runs, and what `ocpbench solve`, `online` and `run` build from a
// CaseSpec.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "bench/cli/case_spec.h"
#include "bench/cli/initial_guess.h"
#include "core/ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"
#include "solvers/registry.h"

namespace ocpb {

struct OnlineScenario;  // drivers/online/online_scenario.h

/// What the checks estimated for a valid case.
struct CaseEstimate {
  double memory_bytes = 0.0;  ///< EstimateCaseMemoryBytes plus the problem's own
  double record_bytes = 0.0;  ///< EstimateRecordBytes
};

/// Everything about a case that is known before solving, found once (ResolveAndValidate): the
/// registry entries, the typed options by owner, the parameters, the grid, the problem's sizes
/// and the memory estimates. The registry pointers are valid while nothing new is registered
/// (as FindProblem's references).
struct ResolvedCase {
  /// The case in canonical form (ResolveCase): typed options, with `algorithm` and `degree`
  /// among them; spec.Key() is the case's key.
  CaseSpec spec;
  const ProblemInfo* problem = nullptr;
  const SolverInfo* solver = nullptr;
  /// The transcription whose options the case gives; nullptr for a method without one.
  const TranscriptionInfo* transcription = nullptr;
  /// The case's options by owner, typed: what the solve gets over the schemas' defaults.
  MethodOptions options;
  /// Kind "solve": the problem's parameters with the case's `set` applied. Kind "online": the
  /// scenario resolves its own (left empty here).
  Parameters parameters;
  /// N: the case's, or the problem's default grid (kind "solve").
  int intervals = 0;
  /// Kind "solve": the problem's state and control dimensions.
  int nx = 0;
  int nu = 0;
  /// The problem as built for the checks when that build is the real one (a problem without
  /// ProblemInfo::make_for_checks): the solve uses it instead of building it again. Empty
  /// otherwise (the channel problems: their channel is simulated only when the case runs).
  std::shared_ptr<const Ocp> built_problem;
  /// Kind "online": the scenario, resolved and checked (CheckOnlineCase); nullptr otherwise.
  std::shared_ptr<const OnlineScenario> online;
  /// The --initial-guess record, read and checked against the problem; empty without one.
  std::optional<InitialGuess> initial_guess;
  /// The memory the solve and its record take (ValidateCase's answer).
  CaseEstimate estimate;
};

/// Resolves `spec` (ResolveCase) and runs every check that needs no solving, each once: the
/// spec's own rules, the names, the options by their schemas and their owners' cross-field
/// rules, the parameters and the problem's own rules (ProblemInfo::make_for_checks, or make),
/// the initial-guess file, the output files the options name, the grid against the horizon
/// (CheckHorizonSteps), and the memory estimates against the budget. Throws
/// std::invalid_argument "FIELD: rule" for the first rule broken. Nothing is solved and no
/// channel is simulated.
ResolvedCase ResolveAndValidate(const CaseSpec& spec);

/// Everything about a case that can be checked before solving, cheaply (no channel is
/// simulated): ResolveAndValidate(spec).estimate (bench/cli/resolved_case.h). Throws
/// std::invalid_argument "FIELD: rule". `ocpbench run` calls it for every case of a suite
/// before running any.
CaseEstimate ValidateCase(const CaseSpec& spec);

/// The rules of the case's transcription options that depend on the problem (a state_scale
/// or control_scale of nx or nu entries), checked before solving; the transcription checks
/// them again when it builds its NLP. Throws std::invalid_argument "options: SCHEME scaling:
/// ...". Nothing for a case without a transcription.
void CheckTranscriptionFits(const CaseSpec& spec, int nx, int nu);

/// The memory one case's record takes while `ocpbench run` holds it for the summary (its
/// SummaryPart, bench/cli/run_outputs.h: trajectories and maps are dropped once the record's
/// line is written): 2 kB of fields and 64 bytes per history row, one row per iteration up to
/// the iteration limit the options give (max_iterations, max_iter), 1000 rows when they give
/// none.
double EstimateRecordBytes(const CaseSpec& spec, int nx, int nu, int intervals);

/// OCPBench's rough, deliberately generous estimate of the memory one case needs, in bytes.
/// With m the transcription's points per interval (TranscriptionInfo::PointsPerInterval: 1,
/// 2 for hermite-simpson, the degree for lgr; 1 without a transcription), nodes = N m + 1 and
/// w = nx + nu:
///   vectors: 64 doubles per node and component (iterates, bounds, multipliers, the solvers'
///            copies, the evaluator's 10x finer re-simulation, the record's trajectory),
///            512 w bytes per node;
///   sparse:  solvers that factor sparse matrices (SolverInfo::factorizes_sparse_matrices:
///            ipopt, indirect-newton) add 320 bytes per Jacobian and Hessian nonzero (16 bytes
///            per stored entry, times 20 for copies and the factorization's fill-in), with
///            nnz = nodes w (w + (m + 1) nx): a Hessian block per node and defect rows that
///            couple m + 1 nodes.
/// NLopt's dense algorithms refuse large problems themselves (NloptOptions' limits); a channel's
/// fixed memory is not counted. Measured peaks (max RSS, double integrator, Release) against the
/// estimate: hamiltonian N = 1e6 657 MB (estimate 1.54 GB), ipopt + euler N = 1e5 355 MB
/// (826 MB), ipopt + hermite-simpson N = 1e5 905 MB (2.04 GB): about 2.3 times generous.
double EstimateCaseMemoryBytes(const CaseSpec& spec, int nx, int nu, int intervals);

/// The one check that a horizon [t0, tf] is long enough for a grid of N intervals on it (every
/// command that solves: solve, run, online): a tenth of each step (tf - t0) / N (the judge's
/// finer grid) must be a normal double and at least 1e-12 max(|t0|, |tf|), so that the grids
/// resolve next to the horizon's ends. Throws std::invalid_argument "tf: the horizon ... is too
/// short for WHICH = N intervals ..." (WHICH: "N", or "mesh_max_nodes" for refined meshes).
void CheckHorizonSteps(double t0, double tf, int N, const std::string& which);

/// The same estimate from its parts: the solver's name, the transcription's points per
/// interval (1 without one), nx, nu and N (online re-plans, whose transcription options are
/// their scenario's).
double EstimateMethodMemoryBytes(
    const std::string& solver, double points_per_interval, int nx, int nu, int intervals);

/// The memory one case may use: half the physical memory (sysconf), 4 GiB when unknown
/// (MemoryBudgetBytes, core/memory_budget.h).
double CaseMemoryBudgetBytes();

}  // namespace ocpb
