// The part of a solve that every NLP backend shares: request -> transcription -> NLP, and an NLP
// solution -> SolveResult.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/ocp.h"
#include "core/solve_result.h"
#include "solvers/solver.h"
#include "transcriptions/transcription.h"

namespace ocpb {

/// What an NLP backend (Ipopt, NLopt) reports about one run on an Nlp, before any
/// optimal-control meaning is attached.
struct NlpSolution {
  /// OCPBench's grouping of the backend's status.
  SolveStatus status = SolveStatus::kError;
  /// The backend's own status name, verbatim ("Solve_Succeeded", "FTOL_REACHED", ...).
  std::string solver_status;
  /// Human-readable detail (why a run was refused, what failed, which options were forced).
  std::string message;
  /// The final iterate (the starting point when the backend produced none; see has_iterate).
  Vec z;
  /// True when z comes from the backend; false when it is the unchanged starting point (the
  /// backend failed before its first iterate, or the run was refused).
  bool has_iterate = false;
  /// Constraint multipliers at z, in the convention of core/nlp.h (Lagrangian
  /// sigma f + lambda^T g); empty when the backend offers none.
  Vec lambda;
  /// Multipliers of the variable bounds at z (z_lower, z_upper >= 0, the convention of
  /// NlpMultipliers); empty when the backend offers none.
  Vec z_lower, z_upper;
  /// The objective at z as the backend reports it (NaN when it reports none).
  double objective = NAN;
  /// The backend's iteration count (NLopt: objective evaluations).
  int iterations = -1;
  /// Per-iteration (Ipopt) or per-evaluation (NLopt) history.
  std::vector<IterationRecord> history;
  /// Backend-specific numbers by name (for example "ipopt_cpu_seconds").
  std::map<std::string, double> stats;
};

/// The transcription options of `request`: FindTranscription(request.transcription)'s defaults
/// with request.transcription_options applied (TranscriptionInfo::Configure), and the request's
/// grid, terminal form, initial guess and integrator. Throws std::invalid_argument for an empty
/// or unknown transcription name or a bad option.
TranscriptionOptions TranscriptionOptionsFor(const SolveRequest& request);

/// Builds the NLP for `request` (TranscriptionOptionsFor, then the transcription's Transcribe).
/// Throws std::invalid_argument for an unknown or empty transcription name, a bad option, or
/// when the transcription rejects the request.
std::unique_ptr<TranscribedNlp> TranscribeRequest(const Ocp& ocp, const SolveRequest& request);

/// How an NLP solver runs on a transcribed NLP from a primal starting point z0
/// (nlp.StartingPoint()) and starting multipliers y0 (empty unless a refined mesh maps the
/// previous one's: mesh_warm_multipliers; a backend that takes none ignores them).
using NlpBackend =
    std::function<NlpSolution(const TranscribedNlp& nlp, const Vec& z0, const NlpMultipliers& y0)>;

/// The shared driver of the NLP solvers: times the whole solve (transcription included), runs
/// `backend` on the transcribed NLP from its starting point, and fills a SolveResult:
/// controls = nlp.Controls(z) (what the evaluator judges), states and costates (from the
/// multipliers, when the backend returns them) on nlp.StateGrid(z) (stretched to T for a free
/// final time), objective = the NLP objective re-evaluated at z, and the backend's status,
/// history and statistics verbatim. `objective` and the history's J are in the problem's units
/// (divided by the transcription's objective scale). With the transcription's mesh refinement
/// on (option mesh_tolerance > 0) these steps run once per mesh inside SolveOnRefinedMeshes
/// (solvers/mesh_refinement_loop.h), each mesh transcribed anew and, from the second on, started
/// from the previous solution (controls, states and, with mesh_warm_multipliers, its
/// multipliers mapped by TranscribedNlp::StartingMultipliers); result.mesh is the final mesh,
/// the one the evaluator judges. A free final time on a transcription that does not take one
/// (TranscriptionInfo::takes_free_final_time) is kNotApplicable. std::invalid_argument from the
/// transcription propagates (an invalid request).
SolveResult SolveTranscribed(const std::string& solver_name,
                             const Ocp& ocp,
                             const SolveRequest& request,
                             const NlpBackend& backend);

/// max over constraints and bounds of the distance-like violation at z:
/// max_i max(g_l,i - g_i, g_i - g_u,i, 0) and the same for z against its bounds. NaN when g(z)
/// cannot be evaluated.
double NlpViolation(const Nlp& nlp, ConstVecRef z);

}  // namespace ocpb
