// Estimation of the channel parameters from measurements.
#pragma once

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "problems/channel/channel_parameters.h"
#include "problems/channel/measurement_file.h"

namespace ocpb {

/// How (K_PL, n_PL, xi, eta, rho) are estimated.
enum class EstimationMethod {
  /// "binned": the companion's two-stage least squares (Malmirchegini and Mostofi, IEEE TWC
  /// 2012), steps 1-4 below.
  kBinnedLeastSquares,
  /// "ml": maximum likelihood of the Gaussian model (likelihood_estimator.h): all five at
  /// once, (K_PL, n_PL) by generalized least squares, started from the binned estimate.
  kMaximumLikelihood,
  /// "reml": restricted maximum likelihood (the likelihood of the residual contrasts: removes
  /// the O(p/m) downward bias of the variances from estimating the path loss).
  kRestrictedMaximumLikelihood,
};
/// "binned", "ml" or "reml".
const char* ToString(EstimationMethod method);
/// One-line description for reports.
const char* Describe(EstimationMethod method);
/// Inverse of ToString; throws std::invalid_argument naming the valid ones.
EstimationMethod EstimationMethodFromString(const std::string& name);
/// The number code of a method for numeric parameter tables: 0 binned, 1 ml, 2 reml. Throws
/// std::invalid_argument otherwise.
EstimationMethod EstimationMethodFromCode(int code);

/// The binned procedure (method kBinnedLeastSquares):
///
/// 1. theta = (K_PL, n_PL) by ordinary least squares of y on H = [1, -10 log10 max(|q - q_b|,
///    d_floor)].
/// 2. Residuals r = y - H theta. Their empirical covariance binned by distance:
///      c_b = mean of r_i r_j over pairs i < j with bin_width b <= |q_i - q_j| < bin_width (b+1),
///    with d_b the mean distance of the bin's pairs; bins with fewer than min_pairs pairs, or
///    beyond max_lag, are dropped. Lag 0 (which carries the multipath power) is not used.
/// 3. (xi^2, eta) minimize sum_b w_b (c_b - xi^2 exp(-d_b / eta))^2 with w_b = n_b / d_b
///    (n_b pairs: the inverse-variance weight of a bin mean, decreasing with lag), subject to
///    0 <= xi^2 <= xi2_max and eta_min <= eta <= eta_max. For fixed eta the best xi^2 is linear
///    least squares (clamped); eta is found by a log-spaced scan followed by golden-section
///    refinement.
/// 4. rho^2 = max(mean(r^2) - xi^2, rho2_floor).
///
/// Maximum likelihood (kMaximumLikelihood, kRestrictedMaximumLikelihood) uses the same bounds on
/// eta and the same floor on rho^2 (applied after the fit), a nugget fraction rho^2 / (xi^2 +
/// rho^2) in [1e-4, 0.99], and no bound on xi^2; the bins (options bin_width, min_pairs,
/// max_lag) only give its starting point (eta = 1 m and a nugget fraction 0.2 if the binned
/// fit fails).
///
/// Maximum likelihood estimates better: over 20 seeds (500 samples, paper's grid;
/// BM_ChannelEstimatorAccuracy) its mean absolute errors are K_PL 1.94 dB, n_PL 0.127, xi 0.11
/// dB, eta 0.40 m, rho 0.18 dB against the binned fit's 2.03, 0.142, 0.28, 0.65, 0.67 (eta
/// biased -0.53 m and rho mostly at its floor there). It costs about 0.15 s instead of 1.3 ms
/// at m = 500 and 5-75 ms instead of under 1 ms at the online loop's 100-400 measurements,
/// which would double or triple an online re-planning cycle (30-50 ms); so the default stays
/// the companion's binned fit and maximum likelihood is an option ("ml").
struct EstimationOptions {
  EstimationMethod method = EstimationMethod::kBinnedLeastSquares;
  double bin_width = 0.2;    ///< m (> 0)
  int min_pairs = 40;        ///< pairs a bin needs to be used (>= 1)
  double max_lag = 15.0;     ///< largest pair distance used, m (> bin_width)
  double xi2_max = 50.0;     ///< upper bound on xi^2, dB^2 (> 0)
  double eta_min = 0.05;     ///< lower bound on eta, m (> 0)
  double eta_max = 5.0;      ///< upper bound on eta, m (> eta_min)
  double rho2_floor = 0.01;  ///< lower bound on rho^2, dB^2 (> 0)
  /// Maximum likelihood only: start from this estimate's eta and nugget fraction instead of the
  /// binned estimate (online: the previous estimate, which saves likelihood evaluations).
  std::optional<ChannelParameters> likelihood_start;

  bool IsValid(std::string* error) const;
};

/// What the estimation saw, for reports and plots.
struct EstimationSummary {
  std::vector<double> bin_lag;         ///< d_b of the bins used, m
  std::vector<double> bin_covariance;  ///< c_b, dB^2
  std::vector<long> bin_pairs;         ///< n_b
  double residual_variance = -1.0;     ///< mean(r^2), dB^2
  double fit_cost = -1.0;              ///< weighted sum of squares at the optimum
  bool xi2_at_bound = false;           ///< xi^2 ended at 0 or xi2_max
  bool eta_at_bound = false;           ///< eta ended at eta_min or eta_max
  bool rho2_floored = false;           ///< rho^2 was raised to rho2_floor
  EstimationMethod method = EstimationMethod::kBinnedLeastSquares;  ///< the method used
  /// Maximum likelihood only: -2 log L at the optimum (profiled; REML's for "reml") and the
  /// number of likelihood evaluations; whether the start came from the binned fit.
  double neg2_log_likelihood = NAN;
  int likelihood_evaluations = 0;
  bool started_from_binned = false;
};

/// Estimates (K_PL, n_PL, xi, eta, rho). The base station and distance floor are taken from
/// `known` (they are not estimated) and copied into the result. Throws std::invalid_argument
/// for fewer than 3 measurements, non-finite values or positions, a measurement within the
/// distance floor of the base station, positions that do not determine n_PL (all at one
/// distance), and (binned only) no usable bin or no spatial correlation in the residuals.
ChannelParameters EstimateChannelParameters(const MeasurementSet& measurements,
                                            const ChannelParameters& known,
                                            const EstimationOptions& options = {},
                                            EstimationSummary* summary = nullptr);

/// Checks measurements for the estimator and predictor: at least 3, sizes equal, all finite,
/// none within `known.distance_floor` of `known.base_station`. Throws std::invalid_argument
/// naming the first offending measurement.
void ValidateMeasurements(const MeasurementSet& measurements, const ChannelParameters& known);

}  // namespace ocpb
