// One benchmark case solved by one method, judged by the common evaluator, written as one
// record. `ocpbench solve` runs one; `ocpbench run` many.
#pragma once

#include <functional>
#include <string>

#include "bench/cli/case_spec.h"
#include "bench/cli/output_place.h"
#include "bench/cli/record.h"
#include "core/solve_result.h"

namespace ocpb {

/// What ValidateCase estimated for a valid case.
struct CaseEstimate {
  double memory_bytes = 0.0;  ///< EstimateCaseMemoryBytes plus the problem's own
  double record_bytes = 0.0;  ///< EstimateRecordBytes
};

/// Everything about a case that can be checked before solving, cheaply (no channel is
/// simulated): Validate(); the problem, solver and transcription names; the method's options
/// by their schemas (ResolveMethodOptions); the parameters and the problem's own cross-field
/// rules (ProblemInfo::make_for_checks, or make); the initial-guess file; and the memory the
/// grid needs (EstimateCaseMemoryBytes against CaseMemoryBudgetBytes). Throws
/// std::invalid_argument "FIELD: rule". `ocpbench run` calls it for every case of a suite
/// before running any; RunCase calls it first.
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

/// The files a case reads and writes beside its record, added to `plan` with `where` (the
/// case's place in its suite, or "" for `solve` and `online`) in their names: its
/// --initial-guess file (an input) and every solver option that names a file the solve writes
/// (FilePlan::IsOutputFileOption: Ipopt's output_file; of the re-plans too), an output that the
/// cases of one run may share (each case's log replaces the one before).
void AddCaseFiles(const CaseSpec& spec, const std::string& where, FilePlan* plan);

/// Statuses that count as failures for the exit code (limits and "not applicable" do not).
bool IsFailure(SolveStatus status);
/// The same for a record's status name (ToString of a SolveStatus).
bool IsFailure(const std::string& status);

/// Whether a judged case whose re-simulation on the method's grid (`own`, the record's J) is not
/// finite is recorded as numerical_failure, whatever its solver said: when the fine RK4
/// re-simulation is not finite either, or when the method's own scheme is the judge's integrator
/// (`spec.transcription` is `spec.evaluate_with`'s name, or the method has no transcription, as
/// the Hamiltonian family on Euler). Otherwise (Euler diverging on a trapezoid solution's coarse
/// grid) the solver's status stands, with the judge's warning not_finite. False when `own` is
/// finite.
bool NotFiniteIsNumericalFailure(const CaseSpec& spec, bool own_finite, bool fine_finite);

/// Solves the case and returns its record. Never throws for numerical trouble (that is the
/// record's status); throws std::invalid_argument for an invalid case (ValidateCase) before
/// any solving.
Record RunCase(const CaseSpec& spec);

/// `run` (RunCase by default) with every exception turned into the case's record, so that one
/// case never stops a suite: std::invalid_argument gives status invalid_input, any other
/// std::exception status error (solver_status "exception"); the message is kept.
Record RunCaseRecordingFailures(const CaseSpec& spec,
                                const std::function<Record(const CaseSpec&)>& run = RunCase);

/// The part of a record every case has: the case's identity (key, problem, seed, method,
/// options as given) and the build's versions; the outcome fields stay "not computed".
Record CaseIdentityRecord(const CaseSpec& spec);

}  // namespace ocpb
