#include "solvers/mesh_refinement_loop.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/timer.h"
#include "solvers/message_number.h"
#include "transcriptions/mesh_refinement.h"

namespace ocpb {
namespace {

// Numbers in messages (solvers/message_number.h), 3 significant digits.
std::string MeshNumber(double v) { return MessageNumber(v, 3); }

// max of the estimates, NaN when any is not finite.
double LargestError(const Vec& errors) {
  if (errors.size() == 0 || !errors.allFinite()) return NAN;
  return errors.maxCoeff();
}

MeshIterationRecord Row(const TranscriptionOptions& options,
                        const MeshSolve& m,
                        double max_error,
                        double cpu_seconds) {
  MeshIterationRecord row;
  row.intervals = options.grid.intervals();
  auto stat = [&](const char* key) {
    const auto it = m.result.solver_stats.find(key);
    return it == m.result.solver_stats.end() ? -1 : static_cast<int>(it->second);
  };
  row.nlp_variables = stat("nlp_variables");
  row.nlp_constraints = stat("nlp_constraints");
  row.max_error = max_error;
  row.iterations = m.result.iterations;
  row.cpu_seconds = cpu_seconds;
  row.status = m.result.status;
  row.solver_status = m.result.solver_status;
  row.degrees = m.degrees;
  return row;
}

}  // namespace

SolveResult SolveOnRefinedMeshes(
    TranscriptionOptions options,
    const std::function<MeshSolve(const TranscriptionOptions& options)>& solve_on_mesh) {
  const MeshRefinementOptions& mesh = options.mesh;
  std::vector<MeshIterationRecord> rows;
  std::vector<IterationRecord> history;
  int iterations = 0;
  int multiplier_starts = 0;  // solves offered mapped multipliers
  double cpu_before = 0.0;    // CPU of the meshes before the current one
  MeshSolve last;
  MeshStopReason reason = MeshStopReason::kMaxIterations;
  std::optional<PhMesh> previous;  // ph: the mesh before the last one, and its estimates
  Vec previous_errors;
  std::vector<PhMesh> seen;  // ph: every mesh solved
  double max_error = NAN;
  for (int it = 1;; ++it) {
    const Stopwatch watch;
    last = solve_on_mesh(options);
    if (last.errors.size() == 0 && IsSuccess(last.result.status)) {
      throw std::invalid_argument("mesh refinement: transcription has no error estimate");
    }
    max_error = IsSuccess(last.result.status) ? LargestError(last.errors) : NAN;
    const double cpu = watch.cpu();
    rows.push_back(Row(options, last, max_error, cpu));
    for (IterationRecord rec : last.result.history) {
      rec.iteration += iterations;
      rec.cpu_seconds += cpu_before;
      history.push_back(rec);
    }
    iterations += std::max(0, last.result.iterations);
    if (last.multipliers_offered) ++multiplier_starts;
    cpu_before += cpu;

    if (!IsSuccess(last.result.status)) {
      reason = MeshStopReason::kSolveFailed;
      break;
    }
    if (!std::isfinite(max_error)) {
      reason = MeshStopReason::kNoEstimate;
      break;
    }
    if (max_error <= mesh.tolerance) {
      reason = MeshStopReason::kToleranceMet;
      break;
    }
    if (it >= mesh.max_iterations) {
      reason = MeshStopReason::kMaxIterations;
      break;
    }
    if (!last.degrees.empty()) {  // ph: LGR's degrees change with the mesh
      PhMesh current{options.grid, last.degrees};
      seen.push_back(current);
      PhMesh next = PhRefineMesh(current,
                                 last.errors,
                                 mesh.tolerance,
                                 mesh,
                                 previous ? &*previous : nullptr,
                                 previous ? &previous_errors : nullptr);
      if (mesh.reduce && std::any_of(seen.begin(), seen.end(), [&](const PhMesh& m) {
            return m.degrees == next.degrees && m.grid.points() == next.grid.points();
          })) {
        // Reduction led back to a mesh already solved (a cycle, measured on goddard): refine
        // without it this time, which only raises and splits.
        MeshRefinementOptions no_reduction = mesh;
        no_reduction.reduce = false;
        next = PhRefineMesh(current, last.errors, mesh.tolerance, no_reduction);
      }
      previous = std::move(current);
      previous_errors = last.errors;
      if (next.nodes() > mesh.max_nodes) {
        reason = MeshStopReason::kMaxNodes;
        break;
      }
      options.grid = std::move(next.grid);
      options.degrees = std::move(next.degrees);
    } else {
      TimeGrid next =
          RefineMesh(options.grid, last.errors, mesh.tolerance, last.order, mesh.max_new_points);
      if (next.size() > mesh.max_nodes) {
        reason = MeshStopReason::kMaxNodes;
        break;
      }
      options.grid = std::move(next);
    }
    options.initial_guess = last.result.controls;
    if (last.states.nu() > 0) options.initial_states = last.states;
    options.initial_multipliers = std::move(last.multipliers);
  }

  SolveResult result = std::move(last.result);
  result.mesh = options.grid;
  result.mesh_history = std::move(rows);
  result.mesh_stop_reason = ToString(reason);
  result.iterations = iterations;
  result.history = std::move(history);
  result.solver_stats["mesh_iterations"] = static_cast<double>(result.mesh_history.size());
  result.solver_stats["mesh_max_error"] = max_error;
  result.solver_stats["mesh_multiplier_starts"] = multiplier_starts;
  if (reason != MeshStopReason::kToleranceMet) {
    std::string why = "mesh refinement stopped (" + std::string(ToString(reason)) + ") after " +
                      std::to_string(result.mesh_history.size()) + " meshes";
    if (std::isfinite(max_error)) {
      why += ", largest error estimate " + MeshNumber(max_error) + " > mesh_tolerance " +
             MeshNumber(mesh.tolerance);
    }
    why += " on " + std::to_string(options.grid.intervals()) + " intervals";
    result.message = result.message.empty() ? why : result.message + "; " + why;
  }
  return result;
}

}  // namespace ocpb
