// The request the descent tests solve with: a uniform grid of N intervals over the problem's
// horizon and string options.
#pragma once

#include <map>
#include <string>
#include <utility>

#include "core/ocp.h"
#include "core/time_grid.h"
#include "solvers/solver.h"

namespace ocpb::testing {

inline SolveRequest DescentRequest(const Ocp& ocp,
                                   int N,
                                   std::map<std::string, std::string> options = {}) {
  SolveRequest r;
  r.grid = TimeGrid::Uniform(ocp.t0(), ocp.tf(), N);
  r.options = std::move(options);
  return r;
}

}  // namespace ocpb::testing
