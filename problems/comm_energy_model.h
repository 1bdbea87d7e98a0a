// The split of a communication problem's running cost that judging a plan on another channel
// needs (the true channel instead of the predicted one).
#pragma once

#include <Eigen/Core>

#include "core/types.h"

namespace ocpb {

/// The communication problems' running cost is L(t, x, u) = P_c(u, s(q(x))) + P_m(x, u): the
/// transmit power for the rate in u over the channel quality s at the robot's position q(x),
/// plus the motion power. A plan is judged on another channel (ExecuteCommPlan,
/// problems/comm_true_energy.h) by keeping P_m and the dynamics and evaluating P_c with that
/// channel's s at q(x). CommPath2d and CommFixedPath implement it.
class CommEnergyModel {
 public:
  virtual ~CommEnergyModel() = default;
  /// The robot's position q(x) in the plane (comm-path2d: x1; comm-fixed-path: the path at arc
  /// length x1).
  virtual Eigen::Vector2d Position(ConstVecRef x) const = 0;
  /// P_m(x, u) = gamma (k1 |u|^2 + k2 |v|^2 + k3 n(v) + k4 + ...), W.
  virtual double MotionPower(ConstVecRef x, ConstVecRef u) const = 0;
  /// P_c = (2^R - 1)/K s for the rate R in u and a channel value s, W.
  virtual double TransmitPower(ConstVecRef u, double s) const = 0;
};

}  // namespace ocpb
