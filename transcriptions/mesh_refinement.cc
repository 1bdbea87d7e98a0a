#include "transcriptions/mesh_refinement.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/invalid.h"

namespace ocpb {

bool MeshRefinementOptions::IsValid(std::string* error) const {
  if (!(tolerance >= 0.0) || !std::isfinite(tolerance)) {
    return Invalid(error,
                   "mesh_tolerance: must be >= 0 and finite (0: no refinement), got " +
                       std::to_string(tolerance));
  }
  if (max_iterations < 1) {
    return Invalid(error,
                   "mesh_max_iterations: must be >= 1, got " + std::to_string(max_iterations));
  }
  if (max_nodes < 2) {
    return Invalid(error, "mesh_max_nodes: must be >= 2, got " + std::to_string(max_nodes));
  }
  if (max_new_points < 1) {
    return Invalid(error,
                   "mesh_max_new_points: must be >= 1, got " + std::to_string(max_new_points));
  }
  return true;
}

const char* ToString(MeshStopReason reason) {
  switch (reason) {
    case MeshStopReason::kToleranceMet:
      return "tolerance_met";
    case MeshStopReason::kMaxIterations:
      return "max_iterations";
    case MeshStopReason::kMaxNodes:
      return "max_nodes";
    case MeshStopReason::kSolveFailed:
      return "solve_failed";
    case MeshStopReason::kNoEstimate:
      return "no_estimate";
  }
  return "unknown";
}

int NodesToAdd(double error, double tolerance, int order, int max_new_points) {
  if (!(error > tolerance)) return 0;
  const double pieces = std::ceil(std::pow(error / tolerance, 1.0 / order));
  // pieces may be huge (or inf for tolerance ~ 0): clamp before converting.
  const double added = std::clamp(pieces - 1.0, 1.0, static_cast<double>(max_new_points));
  return static_cast<int>(added);
}

TimeGrid RefineMesh(
    const TimeGrid& mesh, const Vec& errors, double tolerance, int order, int max_new_points) {
  if (errors.size() != mesh.intervals()) {
    throw std::invalid_argument("RefineMesh: one error per interval expected");
  }
  std::vector<double> points;
  points.reserve(static_cast<size_t>(mesh.size()));
  for (int k = 0; k < mesh.intervals(); ++k) {
    const int pieces = 1 + NodesToAdd(errors[k], tolerance, order, max_new_points);
    for (int j = 0; j < pieces; ++j) points.push_back(mesh.t(k) + mesh.h(k) * j / pieces);
  }
  points.push_back(mesh.tf());
  return TimeGrid::FromPoints(std::move(points));
}

}  // namespace ocpb
