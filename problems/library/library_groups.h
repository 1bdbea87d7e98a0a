// The reference library: problems of the field's public benchmark suites (OptimalControlProblems.jl
// and CTBenchmarks.jl, COPS 3.0, Betts' collection, PSOPT and GPOPS-II examples), one group per
// folder under problems/library/, each problem with its source, tags and published references
// (docs/problems.md).
#pragma once

#include <vector>

#include "problems/registry.h"

namespace ocpb {

/// problems/library/ctbench_a/: from OptimalControlProblems.jl / CTBenchmarks.jl (first half).
void AppendCtbenchProblemsA(std::vector<ProblemInfo>* list);
/// problems/library/ctbench_b/: from OptimalControlProblems.jl / CTBenchmarks.jl and COPS 3.0.
void AppendCtbenchProblemsB(std::vector<ProblemInfo>* list);
/// problems/library/classic/: from Betts' collection and the PSOPT and GPOPS-II examples.
void AppendClassicProblems(std::vector<ProblemInfo>* list);

}  // namespace ocpb
