// The parameters every problem with an explicitly free final time shares (free_time_*.h).
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/parameters.h"

namespace ocpb {

/// C (terminal penalty weight, 1e3), tf (the nominal final time where methods start, 1), and the
/// bounds tf_min (0.1) and tf_max of the free final time T (Ocp::SetFreeFinalTime checks
/// tf_min <= tf <= tf_max).
inline std::vector<ParameterSpec> FreeFinalTimeParameterSpecs(double tf_max) {
  return {
      {"C", {1000.0}, "terminal penalty weight (penalty form)", 0.0, 1e300, true},
      {"tf",
       {1.0},
       "nominal final time: where methods start (within [tf_min, tf_max])",
       0.0,
       1e6,
       true},
      {"tf_min", {0.1}, "lower bound of the free final time", 0.0, 1e6, true},
      {"tf_max", {tf_max}, "upper bound of the free final time", 0.0, 1e6, true},
  };
}

/// The free final time's bounds as the problem's parameters name them: throws
/// std::invalid_argument "tf_min: 3 must be <= tf = 1 (a free final time needs 0 < tf_min <= tf
/// <= tf_max)" (or the same of tf_max) before Ocp::SetFreeFinalTime sees them, so that the
/// message names the field.
inline void CheckFreeFinalTimeParameters(const Parameters& params) {
  const double tf = params.Scalar("tf");
  const double lower = params.Scalar("tf_min");
  const double upper = params.Scalar("tf_max");
  const std::string rule = " (a free final time needs 0 < tf_min <= tf <= tf_max)";
  auto text = [](double v) {
    std::ostringstream os;
    os << v;
    return os.str();
  };
  if (!(lower <= tf)) {
    throw std::invalid_argument("tf_min: " + text(lower) + " must be <= tf = " + text(tf) + rule);
  }
  if (!(tf <= upper)) {
    throw std::invalid_argument("tf_max: " + text(upper) + " must be >= tf = " + text(tf) + rule);
  }
}

}  // namespace ocpb
