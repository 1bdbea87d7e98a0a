// How far a method's costates are from a known optimal costate.
#pragma once

#include <functional>

#include "core/time_grid.h"
#include "core/types.h"

namespace ocpb {

/// The largest componentwise error of `costates` (nx x grid.size(), column j at grid.t(j))
/// against `reference` p*(t), relative to the largest |p*| on the grid:
///   max_j |P_j - p*(t_j)|_inf / max_j |p*(t_j)|_inf.
/// Relative so that problems of different scales read alike; the max over every point of the
/// method's own costate grid (nodes, and the interior points of Hermite-Simpson and LGR) so that
/// no estimate is left out. NaN when the sizes do not fit (no costates, a reference of another
/// dimension), when a value is not finite, or when p* vanishes on the whole grid.
double RelativeCostateError(const Mat& costates,
                            const TimeGrid& grid,
                            const std::function<Vec(double t)>& reference);

}  // namespace ocpb
