// The reference problems with published optima, as one registry block.
#pragma once

#include <vector>

#include "problems/registry.h"

namespace ocpb {

/// Appends, in this order, "bryson-denham", "lqr", "hager", "vanderpol", "rayleigh", "catmix",
/// "brachistochrone", "zermelo", "steering", "goddard", "robot-arm", and the free-final-time
/// problems "double-integrator-free-time" and "brachistochrone-free-time", the problem class's
/// own references, and the COPS estimation problems "gasoil", "methanol" and "pinene"
/// (problems/reference/*.h state each formulation, reference value and source).
void AppendReferenceProblems(std::vector<ProblemInfo>* list);

}  // namespace ocpb
