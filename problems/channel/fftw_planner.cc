#include "problems/channel/fftw_planner.h"

#include <list>
#include <stdexcept>

namespace ocpb {
namespace {

constexpr std::size_t kMaxCachedSizes = 16;

std::shared_ptr<const RealFft2dPlans> MakePlans(int ny, int nx) {
  auto plans = std::make_shared<RealFft2dPlans>();
  plans->ny = ny;
  plans->nx = nx;
  const std::size_t real_n = static_cast<std::size_t>(ny) * nx;
  const std::size_t complex_n = static_cast<std::size_t>(ny) * (nx / 2 + 1);
  double* real = fftw_alloc_real(real_n);
  fftw_complex* spectrum = fftw_alloc_complex(complex_n);
  if (real != nullptr && spectrum != nullptr) {
    // FFTW_ESTIMATE does not touch the arrays while planning.
    const std::lock_guard<std::mutex> lock(FftwPlannerMutex());
    plans->forward = fftw_plan_dft_r2c_2d(ny, nx, real, spectrum, FFTW_ESTIMATE);
    plans->backward = fftw_plan_dft_c2r_2d(ny, nx, spectrum, real, FFTW_ESTIMATE);
  }
  fftw_free(real);
  fftw_free(spectrum);
  if (plans->forward == nullptr || plans->backward == nullptr) {
    throw std::runtime_error("FFTW could not plan a real 2-D FFT of " + std::to_string(ny) + " x " +
                             std::to_string(nx));
  }
  return plans;
}

}  // namespace

std::mutex& FftwPlannerMutex() {
  static std::mutex mutex;
  return mutex;
}

RealFft2dPlans::~RealFft2dPlans() {
  const std::lock_guard<std::mutex> lock(FftwPlannerMutex());
  if (forward != nullptr) fftw_destroy_plan(forward);
  if (backward != nullptr) fftw_destroy_plan(backward);
}

std::shared_ptr<const RealFft2dPlans> CachedRealFft2dPlans(int ny, int nx) {
  // The planner mutex is constructed before the cache, hence destroyed after it: the cached
  // plans' destructors at exit still lock a live mutex.
  FftwPlannerMutex();
  static std::mutex mutex;
  static std::list<std::shared_ptr<const RealFft2dPlans>> cache;  // most recent first
  {
    const std::lock_guard<std::mutex> lock(mutex);
    for (auto it = cache.begin(); it != cache.end(); ++it) {
      if ((*it)->ny != ny || (*it)->nx != nx) continue;
      cache.splice(cache.begin(), cache, it);
      return cache.front();
    }
  }
  std::shared_ptr<const RealFft2dPlans> plans = MakePlans(ny, nx);
  const std::lock_guard<std::mutex> lock(mutex);
  cache.push_front(plans);
  if (cache.size() > kMaxCachedSizes) cache.pop_back();
  return plans;
}

}  // namespace ocpb
