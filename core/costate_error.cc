#include "core/costate_error.h"

#include <algorithm>
#include <cmath>

namespace ocpb {

double RelativeCostateError(const Mat& costates,
                            const TimeGrid& grid,
                            const std::function<Vec(double t)>& reference) {
  if (!reference || costates.size() == 0 || costates.cols() != grid.size()) return NAN;
  double error = 0.0, scale = 0.0;
  for (int j = 0; j < grid.size(); ++j) {
    const Vec p = reference(grid.t(j));
    if (p.size() != costates.rows() || !p.allFinite() || !costates.col(j).allFinite()) return NAN;
    error = std::max(error, (costates.col(j) - p).cwiseAbs().maxCoeff());
    scale = std::max(scale, p.cwiseAbs().maxCoeff());
  }
  return scale > 0.0 ? error / scale : NAN;
}

}  // namespace ocpb
