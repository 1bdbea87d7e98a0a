// Serializes FFTW planning across OCPBench (the FFTW planner is not thread-safe).
#pragma once

#include <mutex>

namespace ocpb {

/// Every fftw_plan_* and fftw_destroy_plan call in OCPBench holds this mutex; executing an
/// existing plan (fftw_execute*) is thread-safe and does not.
std::mutex& FftwPlannerMutex();

}  // namespace ocpb
