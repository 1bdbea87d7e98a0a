// Mesh refinement of a collocation mesh from per-interval error estimates: h-refinement (Betts'
// scheme, with equal subdivision of the intervals that fail the tolerance) for the fixed-order
// schemes, ph-refinement (Patterson, Hager and Rao) for LGR's per-interval degrees.
#pragma once

#include <string>
#include <vector>

#include "core/time_grid.h"
#include "core/types.h"

namespace ocpb {

/// Which local error estimate drives the refinement (transcription option "mesh_estimate").
enum class MeshErrorEstimate {
  /// The scheme's own estimate: Betts' defect integral for trapezoid and Hermite-Simpson
  /// (IntervalDefectErrors, option value "defect"), Patterson-Hager-Rao's interpolation
  /// estimate for LGR (LgrIntervalErrors, option value "interpolation").
  kScheme,
  /// Explicit simulation of the interpolated control on each interval from the interval's
  /// collocated start state, compared with the collocated states inside and at the end of the
  /// interval (IntervalSimulationErrors; option value "simulation").
  kSimulation,
};

/// The options of adaptive mesh refinement (transcription options "mesh_tolerance",
/// "mesh_max_iterations", "mesh_max_nodes", "mesh_estimate", "mesh_warm_multipliers", and
/// "mesh_max_new_points" of
/// trapezoid and hermite-simpson, "mesh_min_degree", "mesh_max_degree", "mesh_reduce" of lgr).
/// With the default tolerance 0 refinement is off: one solve on the request's grid, as without
/// these options.
struct MeshRefinementOptions {
  /// Refine until the largest interval estimate is <= tolerance; 0: off. Must be >= 0 and
  /// finite.
  double tolerance = 0.0;
  /// At most this many meshes are solved, the request's grid being the first (>= 1).
  int max_iterations = 10;
  /// A refined mesh with more nodes than this is not solved: refinement stops on the last mesh
  /// (>= 2). Nodes: t_0..t_N (N + 1) for trapezoid and Hermite-Simpson; for LGR the collocation
  /// points plus tf (sum of the interval degrees + 1), the NLP's state points.
  int max_nodes = 2000;
  /// h-refinement: at most this many nodes are added to one interval per refinement (>= 1).
  int max_new_points = 5;
  /// The estimate (default: the scheme's own).
  MeshErrorEstimate estimate = MeshErrorEstimate::kScheme;
  /// ph-refinement (LGR): the degree of a new subinterval after a split, and the least degree
  /// lowering goes down to (N_min, in [1, 59]).
  int min_degree = 3;
  /// ph-refinement (LGR): an interval whose predicted degree exceeds this is split instead of
  /// raised (N_max, >= min_degree, <= 59: the estimate uses N + 1 points, at most 60).
  int max_degree = 10;
  /// ph-refinement (LGR): merge adjacent intervals and lower degrees where the tolerance is met
  /// with room to spare (PhRefineMesh); false: intervals are only raised or split.
  bool reduce = true;
  /// Start each mesh after the first from the previous solution's multipliers too, mapped to
  /// the new mesh (MultiplierTrajectories; the backend must take them: Ipopt's warm start,
  /// NLopt takes none); false: primal start only.
  bool warm_multipliers = true;

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

/// A mesh with a polynomial degree (LGR collocation points) per interval.
struct PhMesh {
  TimeGrid grid;
  std::vector<int> degrees;  ///< one per interval of grid
  /// The NLP's state points: sum of the degrees + 1 (the count max_nodes limits).
  int nodes() const;
};

/// The degree increase Patterson, Hager and Rao predict for an interval of degree N whose
/// estimate e exceeds the tolerance: P = ceil(log_N(e / tolerance)), at least 1 (their model:
/// each added point divides the error by N; N = 1 is taken as 2). 0 when e <= tolerance or e is
/// NaN.
int PhDegreeIncrease(double error, double tolerance, int degree);

/// By how much the degree of an interval whose estimate e meets the tolerance may be lowered
/// under the same model: floor(log_N(tolerance / e)) - 1 (one point of margin), at least 0, and
/// not below min_degree. 0 when e > tolerance or e is NaN.
int PhDegreeDecrease(double error, double tolerance, int degree, int min_degree);

/// The estimate a merged interval [t_k, t_{k+2}] of degree max(N_k, N_{k+1}) is predicted to
/// have from its two halves' estimates under the h-model e ~ h^(N + 1) of the LGR estimate (each
/// half's estimate scaled by (H / h_j)^(N_j + 1), the larger taken).
double PhMergedError(
    double error_a, double h_a, int degree_a, double error_b, double h_b, int degree_b);

/// One ph refinement step (Patterson, Hager and Rao, "A ph mesh refinement method for optimal
/// control", Optim. Control Appl. Meth. 36 (2015) 398-421, Sec. 4), on every interval k with
/// errors[k] > tolerance:
///  - raise the degree to N_k + P_k (P_k = PhDegreeIncrease) when that is <= max_degree;
///  - else split it into B_k = max(ceil((N_k + P_k) / min_degree), 2) equal subintervals of
///    degree min_degree.
/// With options.reduce, where the tolerance is met on a settled interval (the reduction the
/// same group describes in Liu, Hager and Rao, J. Franklin Inst. 352 (2015) 4081-4106, by
/// OCPBench's rule; settled: `previous` has an interval with the same endpoints and degree, so
/// that reduction never undoes the raise, split or merge just made -- without it meshes cycled,
/// measured on lqr; every interval is settled without `previous`):
///  - two adjacent intervals that both meet it are merged (left to right, each interval at most
///    once) into one of degree max(N_k, N_k+1) when PhMergedError <= tolerance / 10 (the factor
///    keeps a merged interval from failing on the next mesh);
///  - every interval that meets it (merged or not) has its degree lowered by PhDegreeDecrease.
/// With `previous` (the mesh before `mesh` and its estimates), OCPBench's guard against raising
/// the degree across a corner, where p-refinement converges slowly (the nonsmoothness the same
/// group detects from decay rates, Liu, Hager and Rao 2015): a failing interval that was raised
/// on the previous mesh (the same endpoints, a lower degree there) and whose estimate fell by
/// less than half the model's prediction, log_Nprev(e_prev / e) < (N - N_prev) / 2, is split
/// as above instead of raised again.
/// errors has mesh.grid.intervals() entries; an interval with a NaN estimate is kept as it is.
/// Throws std::invalid_argument when the sizes do not match.
PhMesh PhRefineMesh(const PhMesh& mesh,
                    const Vec& errors,
                    double tolerance,
                    const MeshRefinementOptions& options,
                    const PhMesh* previous = nullptr,
                    const Vec* previous_errors = nullptr);

}  // namespace ocpb
