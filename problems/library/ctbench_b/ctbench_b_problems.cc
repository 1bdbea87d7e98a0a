#include "problems/library/library_groups.h"

namespace ocpb {

void AppendCtbenchProblemsB(std::vector<ProblemInfo>* /*list*/) {}

}  // namespace ocpb
