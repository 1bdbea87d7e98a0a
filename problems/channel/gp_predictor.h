// The Gaussian-process channel predictor of the paper (Section II.B), exactly as written.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "problems/channel/channel_parameters.h"
#include "problems/channel/channel_quality.h"
#include "problems/channel/measurement_file.h"
#include "problems/channel/quality_units.h"

namespace ocpb {

/// Options of GpChannelPredictor.
struct GpPredictorOptions {
  QualityUnits units;  ///< N0 and the mW -> W scale of s (defaults: -110 dBm, watts)
  /// Two measurements closer than coincidence_tolerance are "coincident". false (default):
  /// the constructor and AddMeasurements throw std::invalid_argument naming both. true: they
  /// are merged into one measurement at the first position whose value is the mean of the
  /// group (the simulated channel has one value per point, so a repeat is not independent
  /// information; treating repeats as independent would under-state the variance there).
  bool merge_coincident = false;
  double coincidence_tolerance = 1e-9;  ///< m (>= 0)
  /// Within kink_radius of a measurement q_i the gradient and Hessian of that measurement's
  /// kernel term are taken as 0 (see the class comment). m (>= 0).
  double kink_radius = 1e-9;

  bool IsValid(std::string* error) const;
};

/// Mean and variance of the predicted Gamma_dB(q) with their derivatives.
struct PointPrediction {
  double mean_db = 0.0;       ///< Ybar_dB(q), dBm
  double variance_db2 = 0.0;  ///< Sigma(q), dB^2
  Eigen::Vector2d mean_grad = Eigen::Vector2d::Zero();
  Eigen::Vector2d variance_grad = Eigen::Vector2d::Zero();
  Eigen::Matrix2d mean_hess = Eigen::Matrix2d::Zero();
  Eigen::Matrix2d variance_hess = Eigen::Matrix2d::Zero();
};

/// Predicts the channel from m measurements Y at Q = {q_1..q_m} (Ali, Cai, Mostofi, Wardi,
/// ACC 2016, Section II.B, after Malmirchegini and Mostofi, IEEE TWC 2012):
///
///   Ybar_dB(q) = H_q theta + Psi(q)^T Phi^{-1} (Y - H_Q theta),
///   Sigma(q)   = xi^2 + rho^2 - Psi(q)^T Phi^{-1} Psi(q),
///   s(q)       = power_unit_scale exp((ln10/10)^2 Sigma/2) / 10^((Ybar_dB - N0)/10),
///
/// with H_q = [1, -10 log10 max(|q - q_b|, d_floor)], theta = (K_PL, n_PL),
/// Phi = Omega + rho^2 I, Omega_ij = xi^2 exp(-|q_i - q_j|/eta),
/// Psi_i(q) = xi^2 exp(-|q - q_i|/eta), using the (estimated) ChannelParameters given.
/// The predictor works on Gamma_dB, the received power in dBm for a 0 dBm transmitter (the
/// measurements' unit); the CNR is Gamma_dB - N0 and enters only in s (QualityUnits).
///
/// Numerics: Phi = L L^T (Cholesky) once; alpha = Phi^{-1}(Y - H_Q theta). A prediction costs
/// m kernel terms for the mean and one triangular solve w = L^{-1} Psi (m^2/2) for the
/// variance, Sigma = xi^2 + rho^2 - |w|^2; gradients add v = L^{-T} w (grad Sigma =
/// -2 (dPsi)^T v), Hessians add L^{-1} dPsi (Hess Sigma = -2 [(L^{-1} dPsi)^T (L^{-1} dPsi) +
/// sum_i v_i Hess Psi_i]). With e = q - q_i, d = |e|, u = e/d:
///   grad Psi_i = -(Psi_i/eta) u,   Hess Psi_i = Psi_i [u u^T/eta^2 - (I - u u^T)/(eta d)].
/// s follows by ComposeInverseCnr.
///
/// Non-smooth points (documented treatment):
/// - Kinks: exp(-|q - q_i|/eta) has a cone-shaped kink at each measurement, where the
///   gradient is undefined and the Hessian grows like 1/d. Within kink_radius (1e-9 m) of q_i
///   that term's gradient and Hessian are set to 0 (its value is exact). Anywhere else the
///   derivatives are the exact derivatives. Finite-difference tests stay away from the q_i.
/// - Base station: inside the distance floor the path-loss regressor is constant (gradient
///   and Hessian 0); the kink is on the circle |q - q_b| = d_floor. Measurements inside the
///   floor are rejected (ValidateMeasurements).
///
/// Online use: AddMeasurements() appends k measurements keeping the parameters fixed, either by
/// extending the Cholesky factor (bordered update: B = L^{-1} Phi_12, L_22 = chol(Phi_22 -
/// B^T B), O(m^2 k)) or by refactorizing Phi (O(m^3/3)); both give the same predictor to
/// rounding. Re-estimating the parameters means building a new predictor.
///
/// Evaluate() and the prediction functions are const and thread-safe.
class GpChannelPredictor final : public ChannelQuality {
 public:
  enum class UpdateMethod { kBorderedCholesky, kRefactorize };

  /// Throws std::invalid_argument on invalid parameters or options, bad measurements (see
  /// ValidateMeasurements), or coincident positions (unless merged); std::runtime_error when
  /// Phi is not numerically positive definite.
  GpChannelPredictor(const ChannelParameters& parameters,
                     const MeasurementSet& measurements,
                     const GpPredictorOptions& options = {});

  /// Mean and variance at q; order 0: values, 1: and gradients, 2: and Hessians.
  void Predict(const Eigen::Vector2d& q, int order, PointPrediction* out) const;
  double Mean(const Eigen::Vector2d& q) const;
  double Variance(const Eigen::Vector2d& q) const;

  void Evaluate(const Eigen::Vector2d& q,
                double* s,
                Eigen::Vector2d* grad,
                Eigen::Matrix2d* hess) const override;
  /// "gp-exact m=500 K_PL=-41.34 n_PL=3.86 xi=3.2 eta=3.09 rho=1.64".
  std::string Describe() const override;

  /// Appends measurements (validated like the constructor's; coincident ones with existing or
  /// new positions are rejected or merged per the options).
  void AddMeasurements(const MeasurementSet& more,
                       UpdateMethod method = UpdateMethod::kBorderedCholesky);

  /// Preallocates the Cholesky factor for m measurements, so that AddMeasurements up to m does
  /// not reallocate (it otherwise grows the capacity geometrically, copying the factor).
  void ReserveCapacity(int m) { Reserve(m, num_measurements()); }

  int num_measurements() const { return static_cast<int>(values_.size()); }
  const ChannelParameters& parameters() const { return parameters_; }
  const GpPredictorOptions& options() const { return options_; }
  /// Measurement positions, 2 x m (after merging).
  const Eigen::Matrix2Xd& positions() const { return positions_; }
  /// Measurement values Y, dBm (after merging).
  const Eigen::VectorXd& values() const { return values_; }
  /// alpha = Phi^{-1} (Y - H_Q theta).
  const Eigen::VectorXd& alpha() const { return alpha_; }
  /// The lower Cholesky factor L of Phi (m x m; the upper triangle is 0).
  Eigen::Block<const Eigen::MatrixXd> cholesky_factor() const {
    return factor_.topLeftCorner(num_measurements(), num_measurements());
  }
  /// xi^2 exp(-d / eta).
  double Kernel(double d) const { return xi2_ * std::exp(-d / parameters_.eta); }
  /// xi^2 + rho^2, the variance with no measurement nearby.
  double PriorVariance() const { return xi2_ + rho2_; }
  /// H_q theta, dBm, with its gradient and Hessian (may be null).
  double PathLossMean(const Eigen::Vector2d& q, Eigen::Vector2d* grad, Eigen::Matrix2d* hess) const;

 private:
  // Appends validated, de-duplicated measurements to positions_/values_/counts_.
  void Append(const MeasurementSet& more, bool* changed_existing);
  void Factorize();
  // Makes room for m x m in factor_ (capacity grows geometrically), keeping its top-left
  // keep x keep block.
  void Reserve(int m, int keep);
  // alpha from residual_solve_ = L^{-1} (Y - H theta): alpha = L^{-T} residual_solve_.
  void UpdateAlpha();

  ChannelParameters parameters_;
  GpPredictorOptions options_;
  double xi2_, rho2_;
  Eigen::Matrix2Xd positions_;
  Eigen::VectorXd values_;
  std::vector<int> counts_;         // measurements merged into each position
  Eigen::MatrixXd factor_;          // capacity x capacity; L is its top-left m x m block
  Eigen::VectorXd residual_solve_;  // L^{-1} (Y - H_Q theta)
  Eigen::VectorXd alpha_;
};

}  // namespace ocpb
