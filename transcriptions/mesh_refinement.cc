#include "transcriptions/mesh_refinement.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/invalid.h"
#include "transcriptions/radau_nodes.h"

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
  // The LGR estimate uses K + 1 points, so degrees stay below kMaxRadauPoints.
  constexpr int kMaxMeshDegree = kMaxRadauPoints - 1;
  if (min_degree < 1 || min_degree > kMaxMeshDegree) {
    return Invalid(error,
                   "mesh_min_degree: must be in [1, " + std::to_string(kMaxMeshDegree) + "], got " +
                       std::to_string(min_degree));
  }
  if (max_degree < min_degree || max_degree > kMaxMeshDegree) {
    return Invalid(error,
                   "mesh_max_degree: must be in [mesh_min_degree, " +
                       std::to_string(kMaxMeshDegree) + "] = [" + std::to_string(min_degree) +
                       ", " + std::to_string(kMaxMeshDegree) + "], got " +
                       std::to_string(max_degree));
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

int PhMesh::nodes() const {
  int sum = 1;
  for (int d : degrees) sum += d;
  return sum;
}

int PhDegreeIncrease(double error, double tolerance, int degree) {
  if (!(error > tolerance)) return 0;
  const double base = std::log(std::max(degree, 2));
  const double P = std::ceil(std::log(error / tolerance) / base);
  // P may be huge (tolerance ~ 0): clamp before converting.
  return static_cast<int>(std::clamp(P, 1.0, 1000.0));
}

int PhDegreeDecrease(double error, double tolerance, int degree, int min_degree) {
  if (!(error <= tolerance) || degree <= min_degree) return 0;
  const double base = std::log(std::max(degree, 2));
  // error == 0 (an exact interval): log gives inf, clamped to the room above min_degree.
  const double P = std::floor(std::log(tolerance / error) / base) - 1.0;
  return static_cast<int>(std::clamp(P, 0.0, static_cast<double>(degree - min_degree)));
}

double PhMergedError(
    double error_a, double h_a, int degree_a, double error_b, double h_b, int degree_b) {
  const double H = h_a + h_b;
  return std::max(error_a * std::pow(H / h_a, degree_a + 1),
                  error_b * std::pow(H / h_b, degree_b + 1));
}

namespace {

// The index of the interval of `previous` with the endpoints of interval k of `mesh`, or -1.
int SameInterval(const PhMesh& mesh, int k, const PhMesh* previous) {
  if (previous == nullptr) return -1;
  const std::vector<double>& before = previous->grid.points();
  const auto it = std::lower_bound(before.begin(), before.end(), mesh.grid.t(k));
  if (it == before.end() || *it != mesh.grid.t(k) || it + 1 == before.end() ||
      *(it + 1) != mesh.grid.t(k + 1)) {
    return -1;
  }
  return static_cast<int>(it - before.begin());
}

// Whether interval k of `mesh` was raised from the previous mesh (same endpoints, lower degree)
// and its estimate fell by less than half of what the model predicted for the points added.
bool RaisedAcrossACorner(const PhMesh& mesh,
                         const Vec& errors,
                         int k,
                         const PhMesh* previous,
                         const Vec* previous_errors) {
  if (previous_errors == nullptr) return false;
  const int j = SameInterval(mesh, k, previous);
  if (j < 0) return false;
  const int degree_before = previous->degrees[j], degree = mesh.degrees[k];
  const double e_before = (*previous_errors)[j];
  if (degree_before >= degree || !(e_before > 0.0) || !(errors[k] > 0.0)) return false;
  const double observed = std::log(e_before / errors[k]) / std::log(std::max(degree_before, 2));
  return observed < 0.5 * (degree - degree_before);
}

}  // namespace

PhMesh PhRefineMesh(const PhMesh& mesh,
                    const Vec& errors,
                    double tolerance,
                    const MeshRefinementOptions& options,
                    const PhMesh* previous,
                    const Vec* previous_errors) {
  const int N = mesh.grid.intervals();
  if (errors.size() != N || static_cast<int>(mesh.degrees.size()) != N) {
    throw std::invalid_argument("PhRefineMesh: one error and one degree per interval expected");
  }
  if (previous != nullptr && previous_errors != nullptr &&
      (previous_errors->size() != previous->grid.intervals() ||
       static_cast<int>(previous->degrees.size()) != previous->grid.intervals())) {
    throw std::invalid_argument("PhRefineMesh: the previous mesh needs one error per interval");
  }
  // Reduction only touches settled intervals: ones the last refinement left as they were (the
  // same endpoints and degree on the previous mesh), so that it never undoes a raise, a split
  // or a merge it just made (without a previous mesh every interval is settled).
  const auto meets = [&](int k) {
    if (!(errors[k] <= tolerance)) return false;
    if (previous == nullptr) return true;
    const int j = SameInterval(mesh, k, previous);
    return j >= 0 && previous->degrees[j] == mesh.degrees[k];
  };
  PhMesh out;
  std::vector<double> points;
  auto add = [&](double t0, double h, int pieces, int degree) {
    for (int j = 0; j < pieces; ++j) {
      points.push_back(t0 + h * j / pieces);
      out.degrees.push_back(degree);
    }
  };
  for (int k = 0; k < N; ++k) {
    const int degree = mesh.degrees[k];
    const double t = mesh.grid.t(k), h = mesh.grid.h(k);
    if (errors[k] > tolerance) {  // refine: raise, or split when the raise is too high
      const int target = degree + PhDegreeIncrease(errors[k], tolerance, degree);
      if (target <= options.max_degree &&
          !RaisedAcrossACorner(mesh, errors, k, previous, previous_errors)) {
        add(t, h, 1, target);
      } else {
        const int pieces = std::max(2, (target + options.min_degree - 1) / options.min_degree);
        add(t, h, pieces, options.min_degree);
      }
      continue;
    }
    if (!options.reduce || !meets(k)) {  // NaN, or not settled: kept
      add(t, h, 1, degree);
      continue;
    }
    if (k + 1 < N && meets(k + 1)) {
      const int next = mesh.degrees[k + 1];
      const double hb = mesh.grid.h(k + 1);
      const double merged = PhMergedError(errors[k], h, degree, errors[k + 1], hb, next);
      if (merged <= tolerance / 10.0) {
        const int d = std::max(degree, next);
        add(t, h + hb, 1, d - PhDegreeDecrease(merged, tolerance, d, options.min_degree));
        ++k;
        continue;
      }
    }
    add(t, h, 1, degree - PhDegreeDecrease(errors[k], tolerance, degree, options.min_degree));
  }
  points.push_back(mesh.grid.tf());
  out.grid = TimeGrid::FromPoints(std::move(points));
  return out;
}

}  // namespace ocpb
