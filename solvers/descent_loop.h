// The iterations of the Hamiltonian descent (backward sweep, stopping tests, Armijo search) on
// DescentPasses: shared by the paper's method and the family built on it.
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "core/solve_result.h"
#include "core/timer.h"
#include "solvers/descent_passes.h"

namespace ocpb {

/// The proximal direction's eps schedule (Sakawa and Shindo's successive approximations, with
/// eps adapted from the Armijo outcome instead of their halving on failure): after a step
/// beta^j was accepted,
///   eps <- growth eps            when j = 0 (the full proximal step was acceptable: go longer),
///   eps <- beta^j eps            otherwise (the proximal step the accepted one resembles: for an
///                                 unconstrained H with curvature r << 1/eps the minimizer moves
///                                 by about eps |grad_u H|),
/// clamped to [min_eps, max_eps].
struct ProximalSchedule {
  double initial_eps = 1.0;  ///< eps of the first iteration (> 0)
  double growth = 2.0;       ///< factor after a full step (>= 1)
  double min_eps = 1e-12;    ///< (> 0)
  double max_eps = 1e12;     ///< (>= min_eps; may be infinity: the paper's direction)

  bool IsValid(std::string* error) const;
  /// eps after an accepted exponent j (>= 0) with step factor beta.
  double Next(double eps, int j, double beta) const;
};

/// What the loop does and when it stops (HamiltonianDescentOptions' meaning for each field).
struct DescentLoopOptions {
  ArmijoRule armijo;
  int max_iterations = 500;
  double theta_tolerance = 0.0;
  /// Relative stop: |theta| <= relative_theta_tolerance (1 + |J|) also converges (0: off).
  double relative_theta_tolerance = 0.0;
  double max_cpu_seconds = std::numeric_limits<double>::infinity();
  /// The proximal direction when set; the paper's direction otherwise.
  std::optional<ProximalSchedule> proximal;
};

/// How the loop ended: the result's status, the verbatim code and the reason.
struct DescentStop {
  SolveStatus status = SolveStatus::kError;
  std::string code;
  std::string why;
};

/// What the loop leaves besides the passes' iterate.
struct DescentLoopOutcome {
  DescentStop stop;
  int iterations = 0;          ///< accepted steps
  double theta = NAN;          ///< the last theta (NaN when none was computed)
  double eps = NAN;            ///< the proximal eps of the last sweep (NaN: paper's direction)
  bool have_costates = false;  ///< Backward ran at the final iterate
};

/// Runs the descent from the passes' current iterate (Start must have been called): repeatedly
/// Backward, the stopping tests of HamiltonianDescent (in its documented order), Armijo. The CPU
/// limit is tested before each iteration's search and before each Armijo trial after the first
/// (DescentPasses::Armijo), so the loop ends within one trial's or one sweep's cost of it. Appends
/// one IterationRecord per iterate to *history, numbered from `first_iteration`, with CPU times
/// from `clock`; the first record is the current iterate (armijo_j = `first_armijo`).
/// With record_first = false the first record is left out (a loop that continues an earlier one
/// whose last record already describes the current iterate).
///
/// `Passes` is DescentPasses (forward Euler, RK4 with one control per interval) or
/// StageDescentPasses (a Runge-Kutta scheme with one control per stage); the loop is the same.
template <class Passes>
DescentLoopOutcome RunDescentLoop(const DescentLoopOptions& options,
                                  const Stopwatch& clock,
                                  Passes* passes,
                                  std::vector<IterationRecord>* history,
                                  int first_iteration = 0,
                                  int first_armijo = -1,
                                  bool record_first = true);

}  // namespace ocpb
