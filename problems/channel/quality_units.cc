#include "problems/channel/quality_units.h"

#include <cmath>

namespace ocpb {

bool QualityUnits::IsValid(std::string* error) const {
  if (!std::isfinite(noise_dbm)) {
    if (error != nullptr) *error = "noise power N0 must be finite (dBm)";
    return false;
  }
  if (!(power_unit_scale > 0.0) || !std::isfinite(power_unit_scale)) {
    if (error != nullptr) *error = "power_unit_scale must be finite and > 0";
    return false;
  }
  return true;
}

double ExpectedInverseCnr(double mean_dbm, double variance_db2, const QualityUnits& units) {
  const double b = kDbToNeper;
  return units.power_unit_scale *
         std::exp(0.5 * b * b * variance_db2 - b * (mean_dbm - units.noise_dbm));
}

void ComposeInverseCnr(double mean_dbm,
                       const Eigen::Vector2d& mean_grad,
                       const Eigen::Matrix2d& mean_hess,
                       double variance_db2,
                       const Eigen::Vector2d& variance_grad,
                       const Eigen::Matrix2d& variance_hess,
                       const QualityUnits& units,
                       double* s,
                       Eigen::Vector2d* grad,
                       Eigen::Matrix2d* hess) {
  const double b = kDbToNeper;
  const double half_a = 0.5 * b * b;
  const double value = ExpectedInverseCnr(mean_dbm, variance_db2, units);
  if (s != nullptr) *s = value;
  if (grad == nullptr && hess == nullptr) return;
  const Eigen::Vector2d g = half_a * variance_grad - b * mean_grad;
  if (grad != nullptr) *grad = value * g;
  if (hess != nullptr) {
    *hess = value * (g * g.transpose() + half_a * variance_hess - b * mean_hess);
  }
}

}  // namespace ocpb
