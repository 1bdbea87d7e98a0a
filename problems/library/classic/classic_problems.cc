#include "problems/library/classic/alp_rider.h"
#include "problems/library/classic/dynamic_soaring.h"
#include "problems/library/classic/f8_aircraft.h"
#include "problems/library/classic/fuller.h"
#include "problems/library/classic/hypersensitive.h"
#include "problems/library/classic/lotka_volterra_fishing.h"
#include "problems/library/classic/min_energy_free_velocity.h"
#include "problems/library/classic/min_energy_target_line.h"
#include "problems/library/classic/neuenhofen_kerrigan_x1.h"
#include "problems/library/classic/orbit_raising.h"
#include "problems/library/classic/singular_double_integrator.h"
#include "problems/library/classic/tumor_antiangiogenesis.h"
#include "problems/library/classic/vanderpol_state_constrained.h"
#include "problems/library/library_groups.h"

namespace ocpb {

void AppendClassicProblems(std::vector<ProblemInfo>* list) {
  list->push_back(HypersensitiveProblemInfo());
  list->push_back(AlpRiderProblemInfo());
  list->push_back(SingularDoubleIntegratorProblemInfo());
  list->push_back(LotkaVolterraFishingProblemInfo());
  list->push_back(TumorAntiangiogenesisProblemInfo());
  list->push_back(VanDerPolStateConstrainedProblemInfo());
  list->push_back(F8AircraftProblemInfo());
  list->push_back(NeuenhofenKerriganX1ProblemInfo());
  list->push_back(MinEnergyFreeVelocityProblemInfo());
  list->push_back(MinEnergyTargetLineProblemInfo());
  list->push_back(OrbitRaisingProblemInfo());
  list->push_back(DynamicSoaringProblemInfo());
  list->push_back(FullerProblemInfo());
}

}  // namespace ocpb
