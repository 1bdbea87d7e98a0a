#include "problems/channel/shadowing_simulator.h"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "problems/channel/fftw_planner.h"

namespace ocpb {
namespace {

struct FftwBuffer {
  explicit FftwBuffer(std::size_t n)
      : data(static_cast<fftw_complex*>(fftw_malloc(sizeof(fftw_complex) * n))) {
    if (data == nullptr) throw std::runtime_error("shadowing: out of memory for the FFT buffer");
  }
  ~FftwBuffer() { fftw_free(data); }
  FftwBuffer(const FftwBuffer&) = delete;
  FftwBuffer& operator=(const FftwBuffer&) = delete;
  fftw_complex* data;
};

}  // namespace

struct ShadowingSimulator::Plan {
  fftw_plan plan = nullptr;
  ~Plan() {
    if (plan != nullptr) {
      std::lock_guard<std::mutex> lock(FftwPlannerMutex());
      fftw_destroy_plan(plan);
    }
  }
};

int NextFftSize(int n) {
  for (int m = std::max(n, 1);; ++m) {
    int r = m;
    for (int p : {2, 3, 5, 7}) {
      while (r % p == 0) r /= p;
    }
    if (r == 1) return m;
  }
}

ShadowingSimulator::ShadowingSimulator(const GridSpec& grid, double xi, double eta)
    : grid_(grid), xi_(xi), eta_(eta) {
  std::string error;
  if (!grid.IsValid(&error)) throw std::invalid_argument("shadowing: " + error);
  if (!(xi > 0.0) || !std::isfinite(xi) || !(eta > 0.0) || !std::isfinite(eta)) {
    throw std::invalid_argument("shadowing: xi and eta must be finite and > 0");
  }
  int mx = NextFftSize(2 * (grid.nx - 1));
  int my = NextFftSize(2 * (grid.ny - 1));
  for (int attempt = 0;; ++attempt) {
    if (ComputeEigenvalues(mx, my) || attempt == 4) break;
    mx = NextFftSize(mx * 3 / 2);
    my = NextFftSize(my * 3 / 2);
  }
  plan_ = std::make_unique<Plan>();
  FftwBuffer buffer(static_cast<std::size_t>(mx_) * my_);
  std::lock_guard<std::mutex> lock(FftwPlannerMutex());
  // FFTW is row-major: a (my_ x mx_) array whose fast index is x, the layout of sqrt_lambda_.
  plan_->plan = fftw_plan_dft_2d(my_, mx_, buffer.data, buffer.data, FFTW_FORWARD, FFTW_ESTIMATE);
  if (plan_->plan == nullptr) throw std::runtime_error("shadowing: FFTW could not plan the FFT");
}

ShadowingSimulator::~ShadowingSimulator() = default;

bool ShadowingSimulator::ComputeEigenvalues(int mx, int my) {
  const std::size_t n = static_cast<std::size_t>(mx) * my;
  FftwBuffer buffer(n);
  const double h = grid_.resolution, var = xi_ * xi_;
  for (int l = 0; l < my; ++l) {
    const double dy = h * std::min(l, my - l);
    for (int k = 0; k < mx; ++k) {
      const double dx = h * std::min(k, mx - k);
      fftw_complex& c = buffer.data[static_cast<std::size_t>(l) * mx + k];
      c[0] = var * std::exp(-std::sqrt(dx * dx + dy * dy) / eta_);
      c[1] = 0.0;
    }
  }
  {
    fftw_plan p;
    {
      std::lock_guard<std::mutex> lock(FftwPlannerMutex());
      p = fftw_plan_dft_2d(my, mx, buffer.data, buffer.data, FFTW_FORWARD, FFTW_ESTIMATE);
    }
    if (p == nullptr) throw std::runtime_error("shadowing: FFTW could not plan the FFT");
    fftw_execute(p);
    std::lock_guard<std::mutex> lock(FftwPlannerMutex());
    fftw_destroy_plan(p);
  }
  double max_l = -INFINITY, min_l = INFINITY, neg = 0.0, total = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double l = buffer.data[i][0];  // real: c is real and even
    max_l = std::max(max_l, l);
    min_l = std::min(min_l, l);
    total += std::abs(l);
    if (l < 0.0) neg -= l;
  }
  mx_ = mx;
  my_ = my;
  min_ratio_ = min_l / max_l;
  clipped_fraction_ = neg / total;
  sqrt_lambda_.resize(static_cast<Eigen::Index>(n));
  const double inv_n = 1.0 / static_cast<double>(n);
  for (std::size_t i = 0; i < n; ++i) {
    sqrt_lambda_[static_cast<Eigen::Index>(i)] =
        std::sqrt(std::max(buffer.data[i][0], 0.0) * inv_n);
  }
  return clipped_fraction_ < kNegativeTolerance;
}

Eigen::MatrixXd ShadowingSimulator::Draw(RandomStream* stream) const {
  const std::size_t n = static_cast<std::size_t>(mx_) * my_;
  FftwBuffer buffer(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double s = sqrt_lambda_[static_cast<Eigen::Index>(i)];
    buffer.data[i][0] = s * stream->Normal();
    buffer.data[i][1] = s * stream->Normal();
  }
  fftw_execute_dft(plan_->plan, buffer.data, buffer.data);
  Eigen::MatrixXd field(grid_.nx, grid_.ny);
  for (int j = 0; j < grid_.ny; ++j) {
    for (int i = 0; i < grid_.nx; ++i) {
      field(i, j) = buffer.data[static_cast<std::size_t>(j) * mx_ + i][0];
    }
  }
  return field;
}

}  // namespace ocpb
