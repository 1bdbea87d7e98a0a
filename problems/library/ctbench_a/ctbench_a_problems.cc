#include "problems/library/ctbench_a/cart_pendulum.h"
#include "problems/library/ctbench_a/dielectrophoretic_particle.h"
#include "problems/library/ctbench_a/glider.h"
#include "problems/library/ctbench_a/moonlander.h"
#include "problems/library/ctbench_a/mountain_car.h"
#include "problems/library/ctbench_a/quadrotor.h"
#include "problems/library/ctbench_a/space_shuttle.h"
#include "problems/library/ctbench_a/truck_trailer.h"
#include "problems/library/library_groups.h"

namespace ocpb {

void AppendCtbenchProblemsA(std::vector<ProblemInfo>* list) {
  list->push_back(MountainCarProblemInfo());
  list->push_back(GliderProblemInfo());
  list->push_back(SpaceShuttleProblemInfo());
  list->push_back(CartPendulumProblemInfo());
  list->push_back(MoonlanderProblemInfo());
  list->push_back(QuadrotorProblemInfo());
  list->push_back(DielectrophoreticParticleProblemInfo());
  list->push_back(TruckTrailerProblemInfo());
}

}  // namespace ocpb
