// Prediction of mean, variance and s at every point of a grid, fast.
#pragma once

#include <string>

#include <Eigen/Core>

#include "problems/channel/channel_parameters.h"
#include "problems/channel/gp_predictor.h"

namespace ocpb {

/// How PredictOnGrid computes the variance.
enum class GridVarianceMethod {
  /// Sigma from the measurements within the neighbourhood radius R of each tile (local
  /// kriging with the same parameters): Sigma_R(q) = xi^2 + rho^2 - Psi_N^T Phi_NN^{-1} Psi_N.
  /// Conditioning on a subset can only raise the variance, so 0 <= Sigma_R - Sigma <= the
  /// screened information of the measurements beyond R, which decays quickly with R: measured
  /// on the paper's setting (m = 500, estimated parameters, 4 seeds) the largest excess is
  /// 1e-4 to 2e-3 dB^2 at R = 3.5 eta (2e-5 to 1.4e-4 at 4 eta), i.e. a relative error in s of
  /// at most 6e-5 (problems/channel/README.md). Cost per point n_R^2 / 2, n_R the measurements
  /// within R of the tile.
  kLocal,
  /// The paper's formula with all m measurements: Sigma = xi^2 + rho^2 - |L^{-1} Psi|^2 as
  /// one blocked triangular solve per tile. Exact; cost N m^2 / 2 (about 30 s on the paper's
  /// grid with m = 500; for validation).
  kExact,
};
const char* ToString(GridVarianceMethod method);

struct GridPredictionOptions {
  GridVarianceMethod variance = GridVarianceMethod::kLocal;
  /// R = neighborhood_radius_in_eta * eta for kLocal (> 0).
  double neighborhood_radius_in_eta = 3.5;
  /// Tiles are tile_points x tile_points grid points (>= 2).
  int tile_points = 20;
  /// Measurements off the grid lattice: the part of the mean due to those beyond R of a tile
  /// is a smooth (analytic) function on the tile, interpolated from far_field_order x
  /// far_field_order Chebyshev nodes (>= 4) when R >= 2 tile widths, else summed directly.
  int far_field_order = 10;
  /// Worker threads; 0 means std::thread::hardware_concurrency().
  int num_threads = 0;
  /// The FFT of the mean's lattice convolution is sized for a grid of at least min_fft_nx x
  /// min_fft_ny points (>= 0; 0: the grid's own size). Predictions on regions of one larger
  /// grid (the online re-planning's) then share one FFT size, hence one cached FFTW plan
  /// (CachedRealFft2dPlans) instead of planning a new size at every update.
  int min_fft_nx = 0, min_fft_ny = 0;

  bool IsValid(std::string* error) const;
};

/// Mean, variance and s on a grid (each nx x ny, GridSpec layout).
struct GridPrediction {
  GridSpec grid;
  Eigen::MatrixXd mean_db;       ///< Ybar_dB, dBm
  Eigen::MatrixXd variance_db2;  ///< Sigma, dB^2
  Eigen::MatrixXd s;             ///< s in the predictor's QualityUnits
  double seconds = -1.0;         ///< wall time of PredictOnGrid
  std::string method;            ///< "local R=3.5eta tile=20 cheb=10 threads=2" or "exact ..."
};

/// Evaluates the predictor at every grid point.
///
/// Mean: the paper's formula with all m measurements (global alpha), exact. For measurements
/// at grid points (DrawRandomMeasurements, MeasureAlongPath) it is the linear convolution of
/// the alpha image with the kernel on the lattice, by FFT (error ~1e-13 dB); other
/// measurements are summed exactly within R of each tile and by Chebyshev interpolation
/// beyond (error < 1e-7 dB, tested). Variance: `options.variance`. Then
/// s = ExpectedInverseCnr(mean, variance) in the predictor's units. Tiles run on
/// `num_threads` threads; the result does not depend on the thread count.
///
/// Cost on the paper's setting (500 x 500, m = 500), kLocal: see problems/channel/README.md
/// (a few tenths of a second on this 2-core machine). When the system refuses a thread (a
/// process or memory limit), the prediction goes on with the threads it has (the same result;
/// `method` then says "threads=N (the system started only K)"). Throws std::invalid_argument on
/// invalid options or grid, std::runtime_error if a local Phi is not positive definite (never
/// std::terminate).
GridPrediction PredictOnGrid(const GpChannelPredictor& predictor,
                             const GridSpec& grid,
                             const GridPredictionOptions& options = {});

}  // namespace ocpb
