#include "problems/library/library_groups.h"

namespace ocpb {

void AppendCtbenchProblemsA(std::vector<ProblemInfo>* /*list*/) {}

}  // namespace ocpb
