// A scalar field sampled on a rectangular grid: what a record keeps to draw a solution over
// (the channel map under a robot's path).
#pragma once

#include <string>
#include <vector>

#include "core/types.h"

namespace ocpb {

/// The most values a record's field sample may hold: 501 x 501 (a 1 m map of a 500 m workspace,
/// about 5 MB of JSON). Samplers coarsen their spacing to stay within it, so that a large
/// workspace never makes a record of gigabytes.
inline constexpr double kMaxFieldSamplePoints = 501.0 * 501.0;

struct FieldSample {
  std::string quantity;      ///< the values' name in the record ("log10_s")
  std::string note;          ///< what the values are, with units
  std::vector<double> x, y;  ///< node coordinates
  Mat values;                ///< y.size() x x.size(): row j at y[j], column i at x[i]
  double spacing = 0.0;      ///< node spacing (0 when irregular)
};

}  // namespace ocpb
