#include "solvers/grid_sequence.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace ocpb {

int GridSequenceLevels(const TimeGrid& grid, int max_levels, int min_intervals) {
  int levels = 0;
  int n = grid.intervals();
  while (levels < max_levels && n % 2 == 0 && n / 2 >= std::max(min_intervals, 1)) {
    n /= 2;
    ++levels;
  }
  return levels;
}

Mat InterpolateNodes(const TimeGrid& from, const Mat& values, const TimeGrid& to) {
  if (values.cols() != from.size()) {
    throw std::invalid_argument("grid sequencing: values need one column per node of the grid");
  }
  Mat out(values.rows(), to.size());
  for (int j = 0; j < to.size(); ++j) {
    const double t = to.t(j);
    if (t <= from.t0()) {
      out.col(j) = values.col(0);
    } else if (t >= from.tf()) {
      out.col(j) = values.col(from.size() - 1);
    } else {
      const int k = from.Locate(t);
      const double w = (t - from.t(k)) / from.h(k);
      out.col(j) = (1.0 - w) * values.col(k) + w * values.col(k + 1);
    }
  }
  return out;
}

GridSequenceOutcome NewtonOnFinerGrids(const Ocp& ocp,
                                       const IndirectNewtonOptions& options,
                                       TerminalMode terminal,
                                       const SolveResult& coarse,
                                       const std::vector<TimeGrid>& finer,
                                       const Stopwatch& clock,
                                       std::vector<IterationRecord>* history,
                                       double max_cpu_seconds) {
  if (finer.empty()) throw std::invalid_argument("grid sequencing: no finer grid to solve on");
  GridSequenceOutcome out;
  const SolveResult* previous = &coarse;
  for (size_t level = 0; level < finer.size(); ++level) {
    const TimeGrid& from = previous->state_grid;
    if (clock.cpu() >= max_cpu_seconds) {
      out.out_of_time = true;
      out.failed_intervals = finer[level].intervals();
      if (!out.message.empty()) out.message += "; ";
      out.message += "max_cpu_seconds reached before Newton on " +
                     std::to_string(finer[level].intervals()) + " intervals";
      return out;
    }
    SolveRequest request;
    request.terminal = terminal;
    // A free final time: the finer grid on the coarser solution's horizon (its T).
    request.grid =
        finer[level].tf() == from.tf() ? finer[level] : finer[level].StretchedTo(from.tf());
    const Mat X = InterpolateNodes(from, previous->states, request.grid);
    const Mat P = InterpolateNodes(from, previous->costates, request.grid);
    const double cpu0 = clock.cpu();
    // Newton's own limit: what is left of max_cpu_seconds.
    IndirectNewtonOptions limited = options;
    if (std::isfinite(max_cpu_seconds)) {
      limited.max_cpu_seconds =
          std::max(max_cpu_seconds - cpu0, std::numeric_limits<double>::min());
    }
    SolveResult n = IndirectNewton(limited).SolveFrom(ocp, request, X, P);
    out.newton_cpu_seconds += clock.cpu() - cpu0;
    out.newton_iterations += n.iterations;
    const bool finest = level + 1 == finer.size();
    const int offset = static_cast<int>(history->size());
    for (IterationRecord row : n.history) {
      row.iteration += offset;
      row.cpu_seconds += cpu0;
      row.intervals = finest ? -1 : request.grid.intervals();
      history->push_back(row);
    }
    if (!out.message.empty()) out.message += "; ";
    out.message +=
        "Newton on " + std::to_string(request.grid.intervals()) + " intervals: " + n.message;
    out.converged = n.status == SolveStatus::kConverged && n.states.cols() == request.grid.size() &&
                    n.costates.cols() == request.grid.size();
    out.last = std::move(n);
    if (!out.converged) {
      out.failed_intervals = request.grid.intervals();
      return out;
    }
    previous = &out.last;
  }
  return out;
}

}  // namespace ocpb
