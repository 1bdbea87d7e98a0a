#include "problems/library/library_groups.h"

namespace ocpb {

void AppendClassicProblems(std::vector<ProblemInfo>* /*list*/) {}

}  // namespace ocpb
