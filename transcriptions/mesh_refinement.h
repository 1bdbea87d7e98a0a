// h-refinement of a collocation mesh from per-interval error estimates (Betts' scheme, with
// equal subdivision of the intervals that fail the tolerance).
#pragma once

#include <string>

#include "core/time_grid.h"
#include "core/types.h"

namespace ocpb {

/// The options of adaptive mesh refinement (transcription options "mesh_tolerance",
/// "mesh_max_iterations", "mesh_max_nodes", "mesh_max_new_points" of trapezoid and
/// hermite-simpson). With the default tolerance 0 refinement is off: one solve on the request's
/// grid, as without these options.
struct MeshRefinementOptions {
  /// Refine until the largest interval estimate (IntervalDefectErrors) is <= tolerance;
  /// 0: off. Must be >= 0 and finite.
  double tolerance = 0.0;
  /// At most this many meshes are solved, the request's grid being the first (>= 1).
  int max_iterations = 10;
  /// A refined mesh with more nodes t_0..t_N than this (N + 1 > max_nodes) is not solved:
  /// refinement stops on the last mesh (>= 2).
  int max_nodes = 2000;
  /// At most this many nodes are added to one interval per refinement (>= 1).
  int max_new_points = 5;

  bool enabled() const { return tolerance > 0.0; }
  /// True when every field keeps its rule above; otherwise false with "mesh_NAME: must be ..."
  /// in *error (may be null).
  bool IsValid(std::string* error) const;
};

/// Why the refinement stopped.
enum class MeshStopReason {
  kToleranceMet,   ///< the largest estimate is <= tolerance
  kMaxIterations,  ///< max_iterations meshes solved, tolerance not met
  kMaxNodes,       ///< the next mesh would exceed max_nodes, tolerance not met
  kSolveFailed,    ///< a solve did not succeed (its status is the result's); not refined further
  kNoEstimate,     ///< the estimate was not finite (NaN dynamics on the interpolant)
};
/// "tolerance_met", "max_iterations", "max_nodes", "solve_failed", "no_estimate".
const char* ToString(MeshStopReason reason);

/// How many nodes to add to an interval with estimate `error` > `tolerance`: the I that makes
/// the estimate of each of its I + 1 equal pieces, error / (I + 1)^order, at most tolerance,
/// I = ceil((error / tolerance)^(1 / order)) - 1, but at least 1 and at most max_new_points.
/// `order` is the estimate's exponent of h (DefectEstimateOrder). 0 when error <= tolerance
/// (and for a NaN error).
int NodesToAdd(double error, double tolerance, int order, int max_new_points);

/// `mesh` with every interval k whose errors[k] > tolerance split into NodesToAdd + 1 equal
/// pieces; the others kept. errors has mesh.intervals() entries.
TimeGrid RefineMesh(
    const TimeGrid& mesh, const Vec& errors, double tolerance, int order, int max_new_points);

}  // namespace ocpb
