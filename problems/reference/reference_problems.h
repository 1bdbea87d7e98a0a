// The reference problems with published optima, as one registry block.
#pragma once

#include <vector>

#include "problems/registry.h"

namespace ocpb {

/// Appends, in this order, "bryson-denham", "lqr", "hager", "vanderpol", "rayleigh", "catmix",
/// "brachistochrone", "zermelo" and "steering" (problems/reference/*.h state each formulation,
/// reference value and source).
void AppendReferenceProblems(std::vector<ProblemInfo>* list);

}  // namespace ocpb
