#include "problems/reference/reference_problems.h"

#include "problems/reference/brachistochrone.h"
#include "problems/reference/bryson_denham.h"
#include "problems/reference/bryson_denham_bounds.h"
#include "problems/reference/catmix.h"
#include "problems/reference/coupled_ends.h"
#include "problems/reference/free_start.h"
#include "problems/reference/free_time_brachistochrone.h"
#include "problems/reference/free_time_double_integrator.h"
#include "problems/reference/gasoil.h"
#include "problems/reference/goddard.h"
#include "problems/reference/goddard_three_phase.h"
#include "problems/reference/hager.h"
#include "problems/reference/launch_vehicle.h"
#include "problems/reference/lqr.h"
#include "problems/reference/methanol.h"
#include "problems/reference/min_time_double_integrator.h"
#include "problems/reference/pinene.h"
#include "problems/reference/rayleigh.h"
#include "problems/reference/robot_arm.h"
#include "problems/reference/steering.h"
#include "problems/reference/time_parameter_double_integrator.h"
#include "problems/reference/two_phase_double_integrator.h"
#include "problems/reference/vanderpol.h"
#include "problems/reference/zermelo.h"

namespace ocpb {

void AppendReferenceProblems(std::vector<ProblemInfo>* list) {
  list->push_back(BrysonDenhamProblemInfo());
  list->push_back(LqrProblemInfo());
  list->push_back(HagerProblemInfo());
  list->push_back(VanDerPolProblemInfo());
  list->push_back(RayleighProblemInfo());
  list->push_back(CatmixProblemInfo());
  list->push_back(BrachistochroneProblemInfo());
  list->push_back(ZermeloProblemInfo());
  list->push_back(SteeringProblemInfo());
  list->push_back(GoddardProblemInfo());
  list->push_back(RobotArmProblemInfo());
  list->push_back(FreeTimeDoubleIntegratorProblemInfo());
  list->push_back(FreeTimeBrachistochroneProblemInfo());
  list->push_back(BrysonDenhamBoundsProblemInfo());
  list->push_back(FreeStartProblemInfo());
  list->push_back(CoupledEndsProblemInfo());
  list->push_back(TimeParameterDoubleIntegratorProblemInfo());
  list->push_back(TwoPhaseDoubleIntegratorProblemInfo());
  list->push_back(GoddardThreePhaseProblemInfo());
  list->push_back(LaunchVehicleProblemInfo());
  list->push_back(MinTimeDoubleIntegratorProblemInfo());
  list->push_back(GasOilProblemInfo());
  list->push_back(MethanolProblemInfo());
  list->push_back(PineneProblemInfo());
}

}  // namespace ocpb
