// One benchmark case solved by one method, judged by the common evaluator, written as one
// record. `ocpbench solve` runs one; `ocpbench run` many.
#pragma once

#include <functional>
#include <string>

#include "bench/cli/case_spec.h"
#include "bench/cli/output_place.h"
#include "bench/cli/record.h"
#include "bench/cli/resolved_case.h"
#include "core/solve_result.h"

namespace ocpb {

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
/// record's status); throws std::invalid_argument for an invalid case (ResolveAndValidate)
/// before any solving.
Record RunCase(const CaseSpec& spec);
/// The same for a case already resolved and checked (ResolveAndValidate): nothing is resolved
/// or checked again.
Record RunCase(const ResolvedCase& resolved);

/// `run` (RunCase by default) with every exception turned into the case's record, so that one
/// case never stops a suite: std::invalid_argument gives status invalid_input, any other
/// std::exception status error (solver_status "exception"); the message is kept.
Record RunCaseRecordingFailures(const CaseSpec& spec,
                                const std::function<Record(const CaseSpec&)>& run =
                                    static_cast<Record (*)(const CaseSpec&)>(RunCase));

/// The part of a record every case has: the case's identity (key, problem, seed, method,
/// options as given) and the build's versions; the outcome fields stay "not computed".
Record CaseIdentityRecord(const CaseSpec& spec);

}  // namespace ocpb
