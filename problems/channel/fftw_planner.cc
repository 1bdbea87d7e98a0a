#include "problems/channel/fftw_planner.h"

namespace ocpb {

std::mutex& FftwPlannerMutex() {
  static std::mutex mutex;
  return mutex;
}

}  // namespace ocpb
