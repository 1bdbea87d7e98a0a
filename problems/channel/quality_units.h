// s(q) = E[1/CNR(q)] from a Gaussian dB-domain prediction, in the units the cost uses.
#pragma once

#include <string>

#include <Eigen/Core>

namespace ocpb {

/// The one place where the units of s(q) are fixed.
///
/// A predictor gives the received power Gamma_dB(q) for a 0 dBm transmitter as a Gaussian with
/// mean m (dBm) and variance Sigma (dB^2). Then CNR_dB = Gamma_dB - N0_dBm and, CNR being
/// log-normal (the paper's Eq. (4)),
///
///   s = power_unit_scale * E[1/CNR] = power_unit_scale * exp(a Sigma / 2 - b (m - N0_dBm)),
///   a = (ln 10 / 10)^2,  b = ln 10 / 10.
///
/// E[1/CNR] is the transmit power in mW per unit of (2^R - 1)/K (the transmitter reference is
/// 1 mW); power_unit_scale = 1e-3 turns it into watts, the unit in which the paper's costs fit.
struct QualityUnits {
  double noise_dbm = -110.0;       ///< N0, dBm (finite)
  double power_unit_scale = 1e-3;  ///< multiplies E[1/CNR]: 1e-3 gives W, 1 gives mW (> 0)

  bool IsValid(std::string* error) const;
};

inline constexpr double kDbToNeper = 0.23025850929940458;  ///< b = ln(10) / 10

/// s for a dB-domain mean (dBm) and variance (dB^2).
double ExpectedInverseCnr(double mean_dbm, double variance_db2, const QualityUnits& units);

/// s, its gradient and Hessian from the mean and variance with theirs (chain rule):
///   g = a Sigma / 2 - b m + const,  s = scale e^g,
///   grad s = s grad g,  Hess s = s (grad g grad g^T + Hess g).
/// `grad`/`hess` may be null; then the corresponding inputs are not read.
void ComposeInverseCnr(double mean_dbm,
                       const Eigen::Vector2d& mean_grad,
                       const Eigen::Matrix2d& mean_hess,
                       double variance_db2,
                       const Eigen::Vector2d& variance_grad,
                       const Eigen::Matrix2d& variance_hess,
                       const QualityUnits& units,
                       double* s,
                       Eigen::Vector2d* grad,
                       Eigen::Matrix2d* hess);

}  // namespace ocpb
