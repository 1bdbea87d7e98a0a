#include "problems/library/ctbench_a/mountain_car.h"
#include "problems/library/library_groups.h"

namespace ocpb {

void AppendCtbenchProblemsA(std::vector<ProblemInfo>* list) {
  list->push_back(MountainCarProblemInfo());
}

}  // namespace ocpb
