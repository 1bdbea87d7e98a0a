// Adaptive h-refinement around any NLP backend: solve, estimate the error per interval, refine,
// re-solve warm-started, until the tolerance is met or a limit stops it.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "core/control_trajectory.h"
#include "core/solve_result.h"
#include "transcriptions/transcription.h"

namespace ocpb {

/// What one solve on one mesh gives the refinement loop.
struct MeshSolve {
  SolveResult result;        ///< as SolveTranscribed fills it for that mesh (timing aside)
  Vec errors;                ///< TranscribedNlp::IntervalErrors at the solution (one per interval)
  int order = 0;             ///< TranscribedNlp::IntervalErrorOrder
  ControlTrajectory states;  ///< TranscribedNlp::StateTrajectory at the solution
  std::vector<int> degrees;  ///< TranscribedNlp::IntervalDegrees (ph-refinement); empty for h
  /// TranscribedNlp::MultiplierTrajectoriesAt the solution (with mesh.warm_multipliers; nullopt
  /// when the backend returned no multipliers or the map does not apply)
  std::optional<MultiplierTrajectories> multipliers;
  /// Whether this solve was offered starting multipliers (options.initial_multipliers mapped
  /// to a non-empty NlpMultipliers)
  bool multipliers_offered = false;
};

/// Solves on `options.grid`, then, while the largest interval estimate exceeds
/// options.mesh.tolerance, on the refined mesh: RefineMesh of the last mesh (NodesToAdd per
/// interval) for the fixed-order schemes, PhRefineMesh of the last mesh and its degrees
/// (written to options.degrees) when the scheme reports IntervalDegrees (LGR; the mesh before
/// the last one is passed as `previous`, and when the refined mesh is one already solved, a
/// cycle of reductions and refinements, it is refined again without reduction). Each solve starts
/// from the previous one's controls (its own interpolation) and states (the scheme's
/// interpolant) read on the new mesh, and with options.mesh.warm_multipliers from its
/// multipliers (MeshSolve::multipliers, set as options.initial_multipliers; the solve maps them
/// to the new mesh, CollocationNlp::StartingMultipliers). Stops,
/// recording why (MeshStopReason), when the tolerance is met, when max_iterations meshes are
/// solved, when the next mesh would have more than max_nodes nodes (PhMesh::nodes for ph), when
/// a solve does not succeed (IsSuccess), or when the estimate is not finite.
///
/// The result is the last mesh's (its status, controls, states, costates, solver_stats), with
/// mesh = that mesh (nominal horizon), mesh_history (one row per mesh), mesh_stop_reason, a
/// message saying when the tolerance was not met, iterations summed over meshes and history
/// rows of every mesh in order (iteration numbers and CPU seconds continued across meshes).
/// solver_stats gains "mesh_iterations", "mesh_max_error" and "mesh_multiplier_starts" (how many
/// solves were offered mapped multipliers). cpu_seconds and wall_seconds are
/// left to the caller (the whole loop). Throws std::invalid_argument when the scheme has no
/// error estimate (errors empty).
SolveResult SolveOnRefinedMeshes(
    TranscriptionOptions options,
    const std::function<MeshSolve(const TranscriptionOptions& options)>& solve_on_mesh);

}  // namespace ocpb
