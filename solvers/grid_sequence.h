// Grid sequencing for Newton on the discrete maximum principle: solve on a coarse grid (every
// 2^L-th node of the request's), then Newton on each finer grid from the coarser solution's
// states and costates interpolated to its nodes.
//
// Why: Newton's method is mesh independent (Allgower, Boehmer, Potra and Rheinboldt, "A
// mesh-independence principle for operator equations and their discretizations", SIAM J. Numer.
// Anal. 23, 1986): from a start near the solution it takes about as many steps on any fine enough
// grid. The expensive part of a polish (Newton's steps through the moving active set from the
// descent's poor start) is then paid on the coarsest grid, and each finer grid takes a few steps
// from the interpolated coarser solution (comm-path2d: 3-4 steps at N = 400 from N = 200;
// solvers/README-family.md). The principle is proved for smooth operators; for the semismooth
// maximum principle it is measured, not guaranteed, and a caller keeps a fallback.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "core/solve_result.h"
#include "core/time_grid.h"
#include "core/timer.h"
#include "core/types.h"
#include "solvers/indirect_newton.h"
#include "solvers/solver.h"

namespace ocpb {

/// How many times `grid` can be halved (every other node kept), at most `max_levels` times,
/// while each coarser grid keeps at least `min_intervals` intervals: 0 when max_levels <= 0, the
/// interval count is odd, or half of it is below min_intervals. N = 400 with (2, 100): 2 (200 and
/// 100 intervals); N = 300: 1 (150); N = 100: 0.
int GridSequenceLevels(const TimeGrid& grid, int max_levels, int min_intervals);

/// values (rows x from.size(), one column per node of `from`) interpolated linearly in time at
/// the nodes of `to` (rows x to.size()); nodes of `to` outside [from.t0(), from.tf()] take the
/// end values.
Mat InterpolateNodes(const TimeGrid& from, const Mat& values, const TimeGrid& to);

/// What NewtonOnFinerGrids did.
struct GridSequenceOutcome {
  /// The last Newton solve: on the finest grid when every grid converged, otherwise the one that
  /// failed (its status and message say why).
  SolveResult last;
  bool converged = false;
  /// Intervals of the grid whose Newton solve failed, or that was not started because the CPU
  /// limit had been reached (-1: none failed).
  int failed_intervals = -1;
  bool out_of_time = false;   ///< the CPU limit stopped the sequence before a grid
  int newton_iterations = 0;  ///< Newton steps over every grid tried
  double newton_cpu_seconds = 0.0;
  std::string message;  ///< one clause per grid: "Newton on N intervals: <its message>"
};

/// Newton (IndirectNewton::SolveFrom with `options`) on each grid of `finer`, coarse to fine,
/// from the previous solution's states and costates interpolated at its nodes (InterpolateNodes;
/// the first start is `coarse`'s; nu is re-estimated from p_N by SolveFrom). For a free final
/// time each grid is stretched to the previous solution's T (the relative node positions are
/// kept). Stops at the first grid that does not converge, and before a grid when clock.cpu() >=
/// max_cpu_seconds; each grid's Newton gets what is left of max_cpu_seconds as its own limit
/// (IndirectNewtonOptions::max_cpu_seconds: it stops within one step of it). Each
/// Newton row is appended to
/// *history, numbered by its place there, with its CPU time from `clock`'s start and the grid's
/// intervals in IterationRecord::intervals (-1 for the last grid of `finer`, the request's).
/// `coarse` must hold states and costates on its state_grid; `finer` must not be empty (throws
/// std::invalid_argument).
GridSequenceOutcome NewtonOnFinerGrids(
    const Ocp& ocp,
    const IndirectNewtonOptions& options,
    TerminalMode terminal,
    const SolveResult& coarse,
    const std::vector<TimeGrid>& finer,
    const Stopwatch& clock,
    std::vector<IterationRecord>* history,
    double max_cpu_seconds = std::numeric_limits<double>::infinity());

}  // namespace ocpb
