// Exact simulation of exponentially correlated shadowing on a grid (circulant embedding).
#pragma once

#include <complex>
#include <memory>

#include <Eigen/Core>

#include "problems/channel/channel_parameters.h"
#include "problems/channel/random_stream.h"

namespace ocpb {

/// Draws SH on a GridSpec with exactly the covariance
///
///   E[SH(a) SH(b)] = xi^2 exp(-|a - b| / eta)   (Gudmundson's model)
///
/// at the grid points, by circulant embedding (Dietrich and Newsam, SIAM J. Sci. Comput. 1997;
/// Wood and Chan, J. Comput. Graph. Stat. 1994): the covariance is wrapped on a periodic
/// Mx x My lattice with Mx >= 2 (nx - 1), My >= 2 (ny - 1), whose covariance matrix is block
/// circulant and diagonalized by the 2-D FFT with eigenvalues lambda = FFT(c). When every
/// lambda >= 0,
///
///   Z = FFT( sqrt(lambda / (Mx My)) (e1 + i e2) ),   e1, e2 iid N(0, I),
///
/// has real and imaginary parts that are two independent fields whose restriction to the grid
/// has exactly the covariance above; Draw() returns the real part. For the paper's grid
/// (500 x 500 at 0.1 m, eta = 3.09 m) the minimal embedding 1000 x 1000 has no negative
/// eigenvalue. In general the lattice is enlarged (x1.5, up to 4 times) until the negative
/// eigenvalues carry less than `kNegativeTolerance` of the total; what remains is set to 0 and
/// reported in `clipped_fraction()` (0 means exact).
///
/// Construction plans the FFT (FFTW3, FFTW_ESTIMATE) and computes lambda once; Draw() is const
/// and thread-safe. Cost per draw: one complex 2-D FFT of size Mx My (about 30 ms for 1000^2).
class ShadowingSimulator {
 public:
  static constexpr double kNegativeTolerance = 1e-10;

  /// Throws std::invalid_argument on an invalid grid or xi, eta <= 0.
  ShadowingSimulator(const GridSpec& grid, double xi, double eta);
  ~ShadowingSimulator();
  ShadowingSimulator(const ShadowingSimulator&) = delete;
  ShadowingSimulator& operator=(const ShadowingSimulator&) = delete;

  /// One field (nx x ny, dB), consuming 2 Mx My normals from `stream`.
  Eigen::MatrixXd Draw(RandomStream* stream) const;

  int embedding_nx() const { return mx_; }
  int embedding_ny() const { return my_; }
  /// Smallest eigenvalue over the largest, before clipping.
  double min_eigenvalue_ratio() const { return min_ratio_; }
  /// Sum of |negative eigenvalues| over the sum of |eigenvalues| (0: exact).
  double clipped_fraction() const { return clipped_fraction_; }
  const GridSpec& grid() const { return grid_; }

 private:
  struct Plan;
  bool ComputeEigenvalues(int mx, int my);

  GridSpec grid_;
  double xi_, eta_;
  int mx_ = 0, my_ = 0;
  Eigen::ArrayXd sqrt_lambda_;  // sqrt(max(lambda, 0) / (Mx My)), Mx x My column-major
  double min_ratio_ = 0.0, clipped_fraction_ = 0.0;
  std::unique_ptr<Plan> plan_;
};

/// The smallest n' >= n whose prime factors are 2, 3, 5 and 7 (fast FFT sizes).
int NextFftSize(int n);

}  // namespace ocpb
