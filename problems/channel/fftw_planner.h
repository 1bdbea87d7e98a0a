// Serializes FFTW planning across OCPBench (the FFTW planner is not thread-safe), and keeps the
// real 2-D plans the grid prediction needs, one pair per size.
#pragma once

#include <fftw3.h>

#include <memory>
#include <mutex>

namespace ocpb {

/// Every fftw_plan_* and fftw_destroy_plan call in OCPBench holds this mutex; executing an
/// existing plan (fftw_execute*) is thread-safe and does not.
std::mutex& FftwPlannerMutex();

/// A forward real-to-complex and a backward complex-to-real 2-D plan of size ny x nx (FFTW's
/// row-major order: nx varies fastest; the complex side is ny x (nx / 2 + 1)), out of place,
/// FFTW_ESTIMATE. Execute them with fftw_execute_dft_r2c / _c2r on arrays from fftw_alloc_*
/// (the alignment they were planned with); c2r overwrites its input.
struct RealFft2dPlans {
  int ny = 0, nx = 0;
  fftw_plan forward = nullptr;
  fftw_plan backward = nullptr;
  RealFft2dPlans() = default;
  RealFft2dPlans(const RealFft2dPlans&) = delete;
  RealFft2dPlans& operator=(const RealFft2dPlans&) = delete;
  ~RealFft2dPlans();  ///< destroys the plans under FftwPlannerMutex()
};

/// The plans of size ny x nx, made on first use and kept for later calls (the 16 sizes used
/// most recently; a size pushed out is destroyed once its last user lets go). Planning a
/// 1000 x 1000 pair costs about 39 M instructions, as much as a third of executing it, and an
/// online re-prediction asks for the same sizes again. Thread-safe; the result is identical to
/// planning afresh (FFTW_ESTIMATE plans are deterministic). Throws std::runtime_error when FFTW
/// cannot plan or allocate.
std::shared_ptr<const RealFft2dPlans> CachedRealFft2dPlans(int ny, int nx);

}  // namespace ocpb
