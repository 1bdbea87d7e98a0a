#include "problems/library/library_groups.h"

#include "problems/library/ctbench_b/balanced_field.h"
#include "problems/library/ctbench_b/beam.h"
#include "problems/library/ctbench_b/chain.h"
#include "problems/library/ctbench_b/double_oscillator.h"
#include "problems/library/ctbench_b/electric_vehicle.h"
#include "problems/library/ctbench_b/insurance.h"
#include "problems/library/ctbench_b/jackson.h"
#include "problems/library/ctbench_b/robbins.h"

namespace ocpb {

void AppendCtbenchProblemsB(std::vector<ProblemInfo>* list) {
  list->push_back(BalancedFieldProblemInfo());
  list->push_back(BeamProblemInfo());
  list->push_back(HangingChainProblemInfo());
  list->push_back(DoubleOscillatorProblemInfo());
  list->push_back(ElectricVehicleProblemInfo());
  list->push_back(InsuranceProblemInfo());
  list->push_back(JacksonProblemInfo());
  list->push_back(RobbinsProblemInfo());
}

}  // namespace ocpb
