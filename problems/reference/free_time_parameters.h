// The parameters every problem with an explicitly free final time shares (free_time_*.h).
#pragma once

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

}  // namespace ocpb
