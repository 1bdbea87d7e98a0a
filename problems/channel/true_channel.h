// The true channel of a simulated realization, as the cost sees it: what a robot really pays.
#pragma once

#include <memory>
#include <string>

#include <Eigen/Core>

#include "problems/channel/channel_quality.h"
#include "problems/channel/channel_simulator.h"
#include "problems/channel/quality_units.h"

namespace ocpb {

/// s_true(q) = power_unit_scale 10^(-(Gamma_dB(cell(q)) - N0)/10): the inverse CNR of the
/// simulated realization's grid cell that contains q (SimulatedChannel::GainAt, clamped to the
/// grid), in the units of the predictor's s (QualityUnits), so that the transmit power for rate
/// R at q is (2^R - 1)/K s_true(q). No expectation is taken: the simulator knows the
/// realization, shadowing and multipath included.
///
/// This is the judge, not something to plan with: s_true is piecewise constant over the cells
/// (0.1 m by default), so Evaluate returns a zero gradient and Hessian. Planning happens on a
/// prediction (ChannelMap, GpChannelPredictor); the energy on this channel is what the
/// prediction's plan really costs (online re-planning, drivers/online/, and the true-channel
/// fields of offline records, problems/comm_true_energy.h).
class TrueChannelQuality final : public ChannelQuality {
 public:
  /// Throws std::invalid_argument when `truth` is null or `units` are invalid.
  TrueChannelQuality(std::shared_ptr<const SimulatedChannel> truth, const QualityUnits& units);

  /// s_true(q) (see the class comment).
  double At(const Eigen::Vector2d& q) const;
  void Evaluate(const Eigen::Vector2d& q,
                double* s,
                Eigen::Vector2d* grad,
                Eigen::Matrix2d* hess) const override;
  /// "true channel seed=S cells=0.1m".
  std::string Describe() const override;

  const SimulatedChannel& truth() const { return *truth_; }
  const QualityUnits& units() const { return units_; }

 private:
  std::shared_ptr<const SimulatedChannel> truth_;
  QualityUnits units_;
};

}  // namespace ocpb
