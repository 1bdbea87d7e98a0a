// A deterministic channel: path loss only.
#pragma once

#include <string>

#include <Eigen/Core>

#include "problems/channel/channel_parameters.h"
#include "problems/channel/channel_quality.h"
#include "problems/channel/quality_units.h"

namespace ocpb {

/// s(q) from path loss alone (no shadowing, no multipath, no measurements), for tests of
/// other modules:
///
///   m(q) = K_PL - 10 n_PL log10 max(|q - q_b|, d_floor),
///   s(q) = power_unit_scale exp((ln10/10)^2 Sigma0 / 2 - (ln10/10) (m(q) - N0)),
///
/// the GP predictor's s with no measurement and a constant variance Sigma0 (default 0, i.e.
/// s = power_unit_scale / CNR). Exact gradient and Hessian; inside the distance floor they are
/// 0 (the kink is on the circle |q - q_b| = d_floor). The paper's constants by default.
/// (problems/comm_path2d.h has its own smooth-floor variant, PathLossChannel.)
class PathLossOnlyChannel final : public ChannelQuality {
 public:
  /// Throws std::invalid_argument on invalid parameters or units, or Sigma0 < 0.
  explicit PathLossOnlyChannel(const ChannelParameters& parameters = {},
                               const QualityUnits& units = {},
                               double variance_db2 = 0.0);

  void Evaluate(const Eigen::Vector2d& q,
                double* s,
                Eigen::Vector2d* grad,
                Eigen::Matrix2d* hess) const override;
  /// "path-loss K_PL=-41.34 n_PL=3.86 N0=-110dBm".
  std::string Describe() const override;

 private:
  ChannelParameters parameters_;
  QualityUnits units_;
  double variance_db2_;
};

}  // namespace ocpb
