// Why a first-order stop at an iteration or time limit is where it is: the linear rate at which
// the descent's |theta| was falling, and the steps that rate still needs. The family's messages
// say it (issue 42: a method that does not converge says why).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "core/solve_result.h"

namespace ocpb {

/// |theta| over the last `window` rows (at most) of history[begin, end) with a finite theta:
/// |theta_last| = factor^steps |theta_first| defines the per-step factor (the first-order
/// descent converges linearly at best, so a factor near 1 is the reason it stops short).
struct DescentRate {
  int steps = 0;                ///< descent steps between the two rows
  double factor = 1.0;          ///< per-step factor of |theta| (>= 1: it did not fall)
  double last_theta = 0.0;      ///< |theta| of the last row
  double steps_to_target = -1;  ///< steps at `factor` from last_theta to the target (-1: none)
};

/// The rate over history[begin, end); `target` > 0 is the |theta| the stop test waited for (0:
/// none). nullopt when fewer than two rows with finite theta, or no step between them.
std::optional<DescentRate> MeasureDescentRate(const std::vector<IterationRecord>& history,
                                              std::size_t begin,
                                              double target,
                                              int window = 200);

/// "; over its last 200 steps |theta| fell by a factor 1 - 0.0013 per step (linear): about 4100
/// more to |theta| <= 0.0012 at that rate; a Newton end game (polish=true) needs far fewer
/// steps where it converges" (or "did not fall"); "" without a rate.
std::string DescentRateNote(const std::optional<DescentRate>& rate, double target);

}  // namespace ocpb
